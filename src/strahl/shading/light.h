#pragma once
// Light sources of the lecture's local illumination: point lights (the lecture's
// addLightSource), spotlights (point lights that shine into a cone, as POV-Ray's) and
// directional lights, and the area lights of distributed ray tracing (rectangle, disk, sphere;
// sampled in shading/area_light.h). Intensities add up over all lights.

#include <cmath>
#include <cstdint>

#include "strahl/math/vec3.h"

namespace strahl {

enum class LightKind : std::uint8_t { Point, Directional, Spot, Rect, Disk, Sphere };

struct Light {
  LightKind kind = LightKind::Point;
  Vec3 position;   // Point, Spot: where the light is; Rect: a corner; Disk, Sphere: the centre
  Vec3 direction;  // Directional: unit vector the light travels along; Spot: the cone's axis
                   // (unit once compiled), from the light into the scene
  Vec3 radiance{1};  // colour × intensity; area lights: the emitted radiance L
  // Spot only: full light within `angle` degrees of the axis, none beyond `falloff` degrees, a
  // smooth step between; everything times cos^tightness of the angle. compile() sets the cosines.
  Real angle = 30, falloff = 45, tightness = 0;
  Real cos_angle = 1, cos_falloff = 1;
  // Point and spot lights: POV-Ray's fade with distance d, for fade_power > 0 (then
  // fade_distance > 0): 2/(1 + (d/fade_distance)^fade_power).
  Real fade_distance = 0, fade_power = 0;
  // Area lights only.
  Vec3 edge_u, edge_v;  // Rect: the two edges from the corner; it emits towards edge_u × edge_v
  Vec3 normal;          // Rect, Disk: unit normal of the emitting side
  Real radius = 0;      // Disk, Sphere
  int samples = 1;      // n: n×n stratified samples per shading point

  STRAHL_HOST_DEVICE constexpr bool is_area() const { return kind >= LightKind::Rect; }
  // Whether less than all of the light reaches some points: a spot's cone, a fade.
  STRAHL_HOST_DEVICE constexpr bool shaped() const { return kind == LightKind::Spot || fade_power > 0; }
};

// The kind's name, as scene files write it.
constexpr const char* light_kind_name(LightKind kind) {
  switch (kind) {
    case LightKind::Point: return "point";
    case LightKind::Directional: return "directional";
    case LightKind::Spot: return "spot";
    case LightKind::Rect: return "rect";
    case LightKind::Disk: return "disk";
    case LightKind::Sphere: return "sphere";
  }
  return "light";
}

// Direction from `p` towards the light (unit) and the distance to it (infinite for directional).
struct LightSample {
  Vec3 to_light;
  Real distance;
};

// The share of a spotlight's intensity that leaves it towards a point seen in unit direction
// `to_light` from there (1 for every other light): POV-Ray's spotlight (Attenuate_Light in its
// core/lighting/lightsource.cpp). With c the cosine of the angle between the axis and the way to
// the point: 0 where c ≤ 0, else c^tightness, times — where the cone has an edge (cos_angle > 0)
// and c < cos_angle — the cubic step (3 − 2x)·x² of x = (c − cos_falloff)/(cos_angle − cos_falloff),
// 0 below cos_falloff (outside the falloff angle, or anywhere off full light when falloff ≤ angle).
STRAHL_HOST_DEVICE inline Real spot_factor(const Light& light, const Vec3& to_light) {
  if (light.kind != LightKind::Spot) return 1;
  const Real c = -dot(to_light, light.direction);
  if (!(c > 0)) return 0;
  Real share = light.tightness > 0 ? std::pow(c, light.tightness) : Real(1);
  if (light.cos_angle > 0 && c < light.cos_angle) {
    if (c < light.cos_falloff) return 0;
    const Real x = (c - light.cos_falloff) / (light.cos_angle - light.cos_falloff);
    share *= (3 - 2 * x) * x * x;
  }
  return share;
}

// POV-Ray's fade of a light over `distance` (Attenuate_Light): 1 without a fade_power; else
// 2/(1 + (d/fade_distance)^fade_power) — 1 at fade_distance, up to 2 close to the light.
STRAHL_HOST_DEVICE inline Real fade_factor(const Light& light, Real distance) {
  if (!(light.fade_power > 0)) return 1;
  return 2 / (1 + std::pow(distance / light.fade_distance, light.fade_power));
}

// The share of a point or spot light's intensity that reaches a point `distance` away in unit
// direction `to_light` from it: the spot's share times the fade; 1 for a light not shaped().
STRAHL_HOST_DEVICE inline Real light_share(const Light& light, const Vec3& to_light, Real distance) {
  Real share = spot_factor(light, to_light);
  if (light.fade_power > 0 && share > 0) share *= fade_factor(light, distance);
  return share;
}

STRAHL_HOST_DEVICE inline LightSample sample_light(const Light& light, const Vec3& p) {
  if (light.kind == LightKind::Directional) return {-light.direction, kInfinity};
  const Vec3 d = light.position - p;
  const Real dist = length(d);
  return {d / dist, dist};
}

}  // namespace strahl
