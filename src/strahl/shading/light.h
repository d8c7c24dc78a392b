#pragma once
// Light sources of the lecture's local illumination: point lights (the lecture's
// addLightSource) and directional lights. Intensities add up over all lights.

#include <cstdint>

#include "strahl/math/vec3.h"

namespace strahl {

enum class LightKind : std::uint8_t { Point, Directional };

struct Light {
  LightKind kind = LightKind::Point;
  Vec3 position;   // Point: where the light is
  Vec3 direction;  // Directional: unit vector the light travels along
  Vec3 radiance{1};  // colour × intensity
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
