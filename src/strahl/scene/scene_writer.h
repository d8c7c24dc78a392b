#pragma once
// Scene files written from a Scene (the Python module's Scene.save, docs/scene-format.md "Writing
// scene files"): YAML that load_scene() reads back to the same compiled scene — every number in
// its shortest form that reads back to the same double, every material written in place, each
// mesh in an OBJ file of its own beside the scene file, each texture's picture in a PFM file (its
// linear pixels exactly).

#include <filesystem>
#include <string>

#include "strahl/scene/scene.h"

namespace strahl {

// The scene as YAML text, groups and instances included; mesh number i (counting the scene's
// meshes from 0, the groups' first, then the objects') refers to the file
// "<mesh_stem>.mesh<i>.obj" (relative to the scene file), which save_scene writes. Throws
// strahl::Error for what a scene file cannot hold: a number that is not finite (naming what it
// is), an object of a kind scene files do not have.
std::string scene_to_yaml(const Scene& scene, const std::string& mesh_stem = "scene");

// A mesh as OBJ text that the OBJ reader reads back to the same positions, normals and faces
// (faces whose three corners have normals as f v//vn, the others as f v).
std::string mesh_to_obj(const MeshData& mesh);

// Writes the scene to `path` (.yaml or .yml), each mesh to "<stem of path>.mesh<i>.obj" and
// each picture of its image textures to "<stem of path>.texture<i>.pfm" beside it, every file through a temporary file and a rename, so that no existing file is
// ever left half-written. Throws strahl::Error naming the reason.
void save_scene(const Scene& scene, const std::filesystem::path& path);

}  // namespace strahl
