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
// (directories, FIFOs, devices). With `materials`, each face's `usemtl` material too, from the
// `mtllib` files (mtl_loader.h): its Kd and map_Kd (MeshData::materials, face_materials).
MeshData load_obj(const std::filesystem::path& path, bool materials = false);

// The same from the bytes of an OBJ file already in memory (tests, fuzzing); `name` stands for
// the file in messages. The second reads the materials too, the mtllib files from `dir`.
MeshData parse_obj(std::string_view text, const std::string& name);
MeshData parse_obj(std::string_view text, const std::string& name, const std::filesystem::path& dir);

}  // namespace strahl
