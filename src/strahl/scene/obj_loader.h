#pragma once
// Wavefront OBJ meshes through tinyobjloader; polygons are triangulated.

#include <filesystem>

#include "strahl/scene/mesh_data.h"

namespace strahl {

// Throws strahl::Error naming the file (and line where tinyobjloader reports one).
MeshData load_obj(const std::filesystem::path& path);

}  // namespace strahl
