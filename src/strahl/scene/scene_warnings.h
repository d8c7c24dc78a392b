#pragma once
// Warnings about a compiled scene that renders but is likely not what was meant (docs/cli.md,
// "Warnings"): one line each in RenderScene::warnings.

#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"

namespace strahl {

// A one-sided light (rect, disk) whose emitting side faces away from every object, and a light
// whose brightest possible contribution to any pixel is below kFaintLight.
void add_light_warnings(const Scene& scene, RenderScene& out);

// An object whose material's image is uv-mapped but that has no texture coordinates (only meshes
// read from files with them carry any): it shows the image read at the point, as planar.
void add_texture_warning(const SceneObject& object, RenderScene& out);

// Below this (in the units of the image: 1 is white) a light cannot change an 8- or 16-bit
// pixel, wherever it is.
inline constexpr Real kFaintLight = Real(1e-6);

}  // namespace strahl
