#pragma once
// A mesh file read by its extension (case-insensitive): .obj (obj_loader.h) or .ply (ply_loader.h).
// The one place that maps extensions to readers, shared by scene files and strahl-bench.

#include <filesystem>

#include "strahl/scene/mesh_data.h"

namespace strahl {

// Throws strahl::Error naming the file (and line/column where the reader knows them), also for
// an extension that is neither .obj nor .ply.
MeshData load_mesh(const std::filesystem::path& path);

}  // namespace strahl
