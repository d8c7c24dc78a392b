#include "strahl/scene/file_materials.h"

#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/validate.h"

namespace strahl {

void use_file_materials(Scene& scene, Mesh& mesh) {
  use_file_materials(mesh, [&](ImageTexture t) { return scene.add_texture(std::move(t)); });
}

void use_file_materials(Mesh& mesh, const std::function<std::uint32_t(ImageTexture)>& add_texture) {
  mesh.file_materials.clear();
  for (const FileMaterial& f : mesh.data.materials) {
    Material m = mesh.material;
    m.color = f.color;
    if (f.image) {
      ImageTexture t;
      t.image = f.image;
      t.mapping = ImageMapping::UV;
      t.bilinear = f.bilinear;
      t.loc = mesh.loc;
      m.texture = add_texture(std::move(t));
    }
    mesh.file_materials.push_back(m);
  }
}

std::shared_ptr<const Image> tinted(std::shared_ptr<const Image> picture, const Vec3& color) {
  if (color == Vec3(1, 1, 1)) return picture;
  auto out = std::make_shared<Image>(*picture);
  for (int y = 0; y < out->height(); ++y)
    for (int x = 0; x < out->width(); ++x) {
      Rgb& p = out->at(x, y);
      p = Rgb{float(p.r * color.x), float(p.g * color.y), float(p.b * color.z)};
    }
  return out;
}

std::uint32_t add_object_materials(const SceneObject& object, RenderScene& out) {
  validate::material(object.material, out.textures.size(), object.loc);
  const auto index = static_cast<std::uint32_t>(out.materials.size());
  out.materials.push_back(object.material);
  if (const auto* mesh = dynamic_cast<const Mesh*>(&object))
    for (const Material& m : mesh->file_materials) {
      validate::material(m, out.textures.size(), object.loc);
      out.materials.push_back(m);
    }
  return index;
}

}  // namespace strahl
