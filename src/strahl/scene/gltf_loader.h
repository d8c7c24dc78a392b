#pragma once
// glTF 2.0 meshes (.gltf with its buffers in .bin files or data: URIs, and binary .glb), read by
// hand on nlohmann::json: the triangles of the file's default scene, every node's meshes placed by
// the node's world transform, with their NORMAL and TEXCOORD_0; with `materials`, also each
// face's material (base colour factor and texture: MeshData::materials). Cameras, lights, skins,
// morph targets and animations are not read. What is read and what is refused is listed in
// docs/scene-format.md (`mesh`).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "strahl/scene/mesh_data.h"

namespace strahl {

// Throws strahl::Error naming the file and, for a problem in the JSON, the member's path
// ("meshes[0].primitives[1].indices: …"), or line and column for a syntax error. Safe on any
// input: every accessor is checked against its buffer before it is read, and counts are checked
// before anything is allocated for them.
MeshData load_gltf(const std::filesystem::path& path, bool materials = false);

// The same from the bytes of a .gltf or .glb file already in memory (tests, fuzzing); `name`
// stands for the file in messages, and buffer files are looked for in `dir`. A scene of more than
// `max_triangles` triangles (a mesh drawn by many nodes is counted for each) is an error, before
// anything is allocated for them; the fuzz target lowers it.
inline constexpr std::uint64_t kMaxGltfTriangles = 0x7fffffff;  // (MeshData's 32-bit indices)
MeshData parse_gltf(std::string_view bytes, const std::string& name, const std::filesystem::path& dir,
                    bool materials = false, std::uint64_t max_triangles = kMaxGltfTriangles);

}  // namespace strahl
