#pragma once
// A mesh's faces in the materials its file gives them (a glTF file's base colours and pictures,
// an OBJ file's Kd and map_Kd: MeshData::materials), each one the mesh's own material with the
// file's colour and, where the file has one, its picture as a uv-mapped image texture of the scene.

#include <cstdint>
#include <functional>
#include <memory>

namespace strahl {

class Image;
class Mesh;
class Scene;
struct Vec3;
class SceneObject;
struct ImageTexture;
struct RenderScene;

// Fills mesh.file_materials from mesh.data.materials, each picture a texture that `add_texture`
// adds (returning its index, as Scene::add_texture does). Nothing for a mesh whose data has no
// materials.
void use_file_materials(Mesh& mesh, const std::function<std::uint32_t(ImageTexture)>& add_texture);
// The same with the pictures added to the scene's textures.
void use_file_materials(Scene& scene, Mesh& mesh);

// A file material's picture times its colour (glTF's base colour factor, MTL's Kd): the picture
// itself where the colour is white.
std::shared_ptr<const Image> tinted(std::shared_ptr<const Image> picture, const Vec3& color);

// compile()'s part: the object's material, checked, appended to out.materials, and after it (for
// a mesh) its file materials; returns the index of the object's own (its file materials' are
// the ones after it).
std::uint32_t add_object_materials(const SceneObject& object, RenderScene& out);

}  // namespace strahl
