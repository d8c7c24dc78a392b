#pragma once
// Scene files: YAML (.yaml, .yml) and JSON (.json, read by the same YAML reader), and POV-Ray
// scenes (.pov, translated into the same format: pov/pov_scene.h).
// Every key is documented in docs/scene-format.md, the POV-Ray subset in docs/pov-import.md.

#include <filesystem>
#include <functional>
#include <string>

#include "strahl/scene/mesh_data.h"
#include "strahl/scene/pov/pov_scene.h"
#include "strahl/scene/scene.h"

namespace strahl {

// Throws strahl::Error with file:line:column for syntax errors, unknown keys, wrong types,
// missing fields and impossible values.
// `pov`: the image size and declared names a .pov scene is read with.
Scene load_scene(const std::filesystem::path& path, const PovOptions& pov = {});

// Where a `mesh` object's `file` comes from, if not from a file beside the scene.
using MeshSource = std::function<MeshData(const std::string& file)>;

// The same from text; `name` is used in error messages, `base_dir` resolves mesh paths (or
// `meshes` gives each mesh for its `file` value).
Scene parse_scene(const std::string& text, const std::string& name, const std::filesystem::path& base_dir,
                  const MeshSource& meshes = {});

// Named indices of refraction (vacuum, air, water, ice, acrylic, glass, diamond); false if unknown.
bool named_ior(const std::string& name, Real& ior);

}  // namespace strahl
