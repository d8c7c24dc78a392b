#pragma once
// A 64-bit fingerprint of a compiled scene: every shape, material, light, the camera and the
// trace and sampling settings (not the acceleration structure, which is derived from them).
// Two processes that compiled the same scene get the same value — MPI ranks check it before
// rendering together, and a resume journal checks it before its tiles are reused.

#include <cstdint>

#include "strahl/render/render_scene.h"

namespace strahl {

std::uint64_t scene_hash(const RenderScene& scene);

}  // namespace strahl
