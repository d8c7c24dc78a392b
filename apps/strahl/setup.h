#pragma once
// The steps of a render that strahl and strahl-mpi share: where the image goes, the scene with
// the command line's settings over its own, and the AOV images beside the output.

#include <string>

#include "options.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"

namespace strahl::cli {

// -o, or <scene name>.png in the current directory.
std::string output_path(const Options& o);

// The scene file (or the lecture's scene) with the command line's settings over the scene's.
Scene configured_scene(const Options& o);

// <output stem>.<name>.exr beside the image, for each AOV asked for.
void write_aovs(const RenderScene& scene, const Options& o, const std::string& output);

}  // namespace strahl::cli
