#pragma once
// Wavefront OBJ meshes, read by one strict pass of our own: it checks every line (numbers, index
// ranges, text bytes) and names file:line:column for the first problem; polygons are split into
// triangles by scene/polygon.h (in linear time when convex). Time linear in the file's size.

#include <filesystem>
#include <string>
#include <string_view>

#include "strahl/scene/mesh_data.h"

namespace strahl {

// Throws strahl::Error naming the file, line and column. Refuses what is not a regular file
// (directories, FIFOs, devices).
MeshData load_obj(const std::filesystem::path& path);

// The same from the bytes of an OBJ file already in memory (tests, fuzzing); `name` stands for
// the file in messages.
MeshData parse_obj(std::string_view text, const std::string& name);

}  // namespace strahl
