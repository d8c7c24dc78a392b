#pragma once
// compile()'s part for image textures: the scene's textures (Scene::add_texture) as the kernel
// reads them (shading/image_texture.h), their pixels in one texel array.

namespace strahl {

class Scene;
struct RenderScene;

void compile_textures(const Scene& scene, RenderScene& out);

}  // namespace strahl
