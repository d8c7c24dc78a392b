#pragma once
// The lecture's surface description: colour, ambient, Lambert diffuse, Blinn-Phong specular,
// mirror reflection and transparency/refraction, and emitted light. Defaults are the finish of
// the benchmark scene (POV-Ray `finish { ambient 0.1 diffuse 0.7 specular 0.6 roughness 0.01 }`).

#include <cmath>

#include "strahl/math/vec3.h"
#include "strahl/shading/image_texture.h"

namespace strahl {

struct Material {
  Vec3 color{0.8, 0.8, 0.8};  // diffuse and ambient colour C
  Real ambient = 0.1;         // k_a: ambient = k_a · C · ambient light
  Real diffuse = 0.7;         // k_d: Lambert = k_d · C · max(0, N·L) · light
  Vec3 specular{0.6};         // k_s (a colour): Blinn-Phong = k_s · max(0, N·H)^shininess · light
  Real shininess = 100;       // Blinn-Phong exponent (the lecture uses 120; POV-Ray's 1/roughness)
  Real reflectivity = 0;      // weight of the mirror ray, 0..1
  Real transparency = 0;      // the lecture's 1 − α: weight of the refracted ray, 0..1
  Real ior = 1;               // index of refraction of the object's interior
  bool fresnel = false;       // Schlick: reflection grows towards grazing angles, refraction shrinks
  bool filter = false;        // transmitted light (refraction and shadows) is tinted by `color`
  // An image texture (shading/image_texture.h) giving C instead of `color`: its index among the
  // scene's textures (Scene::add_texture), kNoTexture for none.
  std::uint32_t texture = kNoTexture;
  // Glossy reflection and translucency (shading/glossy.h): 0 = perfect mirror and clear
  // refraction, up to 1 = the widest lobe.
  Real roughness = 0;
  // Procedural checkerboard: squares of `checker_size` alternating `color` and `checker_color`
  // (0 = no checkerboard). Planes use their own 2D frame, other shapes a 3D (solid) checker.
  Real checker_size = 0;
  Vec3 checker_color{0.1};
  // Light the surface gives off by itself (POV-Ray's finish `emission`, as the material's colour
  // times it): radiance E added to the local colour whatever lights the surface. The path tracer
  // (render/path_tracer.h) carries it to other surfaces; Whitted's integrator only shows it.
  Vec3 emission{0};
};

// Is floor(a) odd? Computed in floating point: a cell index past the range of an integer type
// (a checker of size 1e-300, a point at 1e200) must not be converted to one, which is undefined
// behaviour. Every Real of magnitude 2^53 (float: 2^24) or more is an even whole number, and
// NaN or ±∞ (a size so small that 1/size overflows) count as even. floor(a) − 2·floor(floor(a)/2)
// is exact (halving a whole number is) and is fmod(floor(a), 2) without libm's call.
STRAHL_HOST_DEVICE inline bool odd_cell(Real a) {
  const Real cell = std::floor(a);
  return cell - 2 * std::floor(cell * Real(0.5)) == Real(1);
}

// Does the colour C vary over the surface (a checker or an image)?
STRAHL_HOST_DEVICE inline bool textured(const Material& m) { return m.checker_size > 0 || m.texture != kNoTexture; }

// Colour C at a point with plane coordinates (u, v) or, for solids, position p.
STRAHL_HOST_DEVICE inline Vec3 surface_color(const Material& m, const Vec3& texcoord, const kernel::Textures& textures) {
  if (m.texture != kNoTexture) return kernel::image_color(textures.images[m.texture], textures.texels, texcoord, m.color);
  if (m.checker_size <= 0) return m.color;
  const Real s = Real(1) / m.checker_size;
  const bool odd = (odd_cell(texcoord.x * s) != odd_cell(texcoord.y * s)) != odd_cell(texcoord.z * s);
  return odd ? m.checker_color : m.color;
}

}  // namespace strahl
