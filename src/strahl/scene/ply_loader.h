#pragma once
// Stanford PLY meshes (format ascii 1.0, binary_little_endian 1.0 and binary_big_endian 1.0),
// read by hand; polygons are triangulated as fans. What is read and what is refused is listed in
// docs/scene-format.md (`mesh`).

#include <filesystem>
#include <string>
#include <string_view>

#include "strahl/scene/mesh_data.h"

namespace strahl {

// Throws strahl::Error naming the file, and the line for errors in the header or in an ascii
// body (binary bodies name the byte offset in the message instead). Safe on any input: every
// count is checked against the size of the file before anything is allocated for it.
MeshData load_ply(const std::filesystem::path& path);

// The same from the bytes of a PLY file already in memory (for tests and fuzzing); `name` stands
// for the file in error messages.
MeshData parse_ply(std::string_view bytes, const std::string& name);

}  // namespace strahl
