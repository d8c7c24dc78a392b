#pragma once
// Light sources of the lecture's local illumination: point lights (the lecture's
// addLightSource) and directional lights, and the area lights of distributed ray tracing
// (rectangle, disk, sphere; sampled in shading/area_light.h). Intensities add up over all lights.

#include <cstdint>

#include "strahl/math/vec3.h"

namespace strahl {

enum class LightKind : std::uint8_t { Point, Directional, Rect, Disk, Sphere };

struct Light {
  LightKind kind = LightKind::Point;
  Vec3 position;   // Point: where the light is; Rect: a corner; Disk, Sphere: the centre
  Vec3 direction;  // Directional: unit vector the light travels along
  Vec3 radiance{1};  // colour × intensity; area lights: the emitted radiance L
  // Area lights only.
  Vec3 edge_u, edge_v;  // Rect: the two edges from the corner; it emits towards edge_u × edge_v
  Vec3 normal;          // Rect, Disk: unit normal of the emitting side
  Real radius = 0;      // Disk, Sphere
  int samples = 1;      // n: n×n stratified samples per shading point

  STRAHL_HOST_DEVICE constexpr bool is_area() const { return kind >= LightKind::Rect; }
};

// Direction from `p` towards the light (unit) and the distance to it (infinite for directional).
struct LightSample {
  Vec3 to_light;
  Real distance;
};

STRAHL_HOST_DEVICE inline LightSample sample_light(const Light& light, const Vec3& p) {
  if (light.kind == LightKind::Directional) return {-light.direction, kInfinity};
  const Vec3 d = light.position - p;
  const Real dist = length(d);
  return {d / dist, dist};
}

}  // namespace strahl
