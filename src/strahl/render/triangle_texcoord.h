#pragma once
// The texture coordinate of a point on a mesh triangle (render/surface_point.h and, for
// instanced groups, render/instance_surface.h): a uv-mapped image (shading/image_texture.h) reads
// the mesh's own (u, v), every other texture the point.

#include <cstdint>

#include "strahl/geometry/hit.h"
#include "strahl/render/scene_view.h"

namespace strahl {

// A triangle's texture coordinate: its vertices' (u, v) at the hit where it has them (`uvs` at
// `index` ≥ 0: a mesh whose material has an image) and its material's image is uv-mapped; else
// the point p.
STRAHL_HOST_DEVICE inline Vec3 triangle_texcoord(const SceneView& s, const kernel::VertexTexcoords* uvs,
                                                 std::int32_t index, std::uint32_t material, const Hit& hit,
                                                 const Vec3& p) {
  if (index < 0) return p;
  const std::uint32_t texture = s.materials[material].texture;
  if (texture == kNoTexture || s.textures.images[texture].mapping != ImageMapping::UV) return p;
  return kernel::texcoord_at(uvs[index], hit.b1, hit.b2);
}

}  // namespace strahl
