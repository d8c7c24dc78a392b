#pragma once
// A mesh file read by its extension (case-insensitive): .obj (obj_loader.h), .ply (ply_loader.h),
// .gltf or .glb (gltf_loader.h).
// The one place that maps extensions to readers, shared by scene files and strahl-bench.

#include <filesystem>

#include "strahl/scene/mesh_data.h"
#include "strahl/util/large_array.h"

namespace strahl {

// Throws strahl::Error naming the file (and line/column where the reader knows them), also for
// an extension that is none of these.
// With `materials`, a glTF or OBJ file's faces also get its materials (MeshData::materials); PLY
// files give none.
MeshData load_mesh(const std::filesystem::path& path, bool materials = false);

// Whether the file's extension is .gltf or .glb (case-insensitive); whether it is a format that
// gives its faces materials (glTF, OBJ with mtllib).
bool is_gltf_file(const std::filesystem::path& path);
bool gives_materials(const std::filesystem::path& path);

// The whole file in memory, in one read (a LargeArray: 2 MiB pages from 1 MiB on, not zeroed
// first); its size is what was actually read (the file may have shrunk since its size was asked).
// Throws strahl::Error "cannot open mesh file: …", "cannot read mesh file: …" or "too large".
LargeArray<char> read_mesh_file(const std::filesystem::path& path);

}  // namespace strahl
