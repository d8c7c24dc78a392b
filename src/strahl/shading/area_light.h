#pragma once
// Area lights for soft shadows (Cook et al. 1984, distributed ray tracing): a rectangle, a disk
// or a sphere of constant emitted radiance L. A shading point estimates the irradiance
//   E = ∫_light L cos θ cos θ' / r² dA
// from n×n stratified (jittered) samples on the light. Rectangles and disks are sampled
// uniformly by area; spheres by the cone of directions they subtend (uniform in solid angle),
// which wastes no samples on the far side. Each sample acts like a point light of "intensity"
//   I = L · cos θ' / (π · r² · pdf_A)     (or L / (π · pdf_ω) for solid-angle sampling)
// in the Whitted shading of render/whitted.h, so a Lambert surface under a light filling its
// whole hemisphere with L = 1 is as bright as under a point light of intensity 1 at normal
// incidence (the 1/π of the Lambert BRDF). Rectangles and disks emit from one side only.
//
// Emitters are visible: a camera or mirror ray meeting one returns L (intersect_emitter). They
// cast no shadows of their own: shadow rays do not test light shapes.

#include <cmath>

#include "strahl/geometry/sphere.h"
#include "strahl/math/frame.h"
#include "strahl/sampling/warp.h"
#include "strahl/shading/light.h"

namespace strahl {

// One sample on an area light as seen from a shading point.
struct AreaLightSample {
  Vec3 point;       // on the light
  Vec3 to_light;    // unit, from the shading point
  Real distance = 0;
  Vec3 intensity;   // I above; zero when the sample does not illuminate the point
  Real pdf = 0;     // density of `point`: per area (Rect, Disk) or of `to_light` per solid angle (Sphere)
};

STRAHL_HOST_DEVICE inline Real area_light_area(const Light& l) {
  switch (l.kind) {
    case LightKind::Rect: return length(cross(l.edge_u, l.edge_v));
    case LightKind::Disk: return kPi * l.radius * l.radius;
    case LightKind::Sphere: return 4 * kPi * l.radius * l.radius;
    default: return 0;
  }
}

// Radiance L of a light emitting total power Φ (one-sided Lambertian emitter: Φ = π·L·A).
STRAHL_HOST_DEVICE inline Real radiance_from_power(const Light& l, Real power) {
  const Real a = area_light_area(l);
  return a > 0 ? power / (kPi * a) : 0;
}

// Samples the light for shading point p with the unit-square point u.
STRAHL_HOST_DEVICE inline AreaLightSample sample_area_light(const Light& l, const Vec3& p, const Vec2& u) {
  AreaLightSample s;
  switch (l.kind) {
    case LightKind::Rect:
    case LightKind::Disk: {
      Real area;
      if (l.kind == LightKind::Rect) {
        s.point = l.position + l.edge_u * u.x + l.edge_v * u.y;
        area = length(cross(l.edge_u, l.edge_v));
      } else {
        const Vec2 d = square_to_disk(u);
        const Frame f = Frame::around(l.normal);
        s.point = l.position + (f.u * d.x + f.v * d.y) * l.radius;
        area = kPi * l.radius * l.radius;
      }
      s.pdf = 1 / area;
      const Vec3 d = s.point - p;
      const Real r2 = length_squared(d);
      s.distance = std::sqrt(r2);
      if (!(s.distance > 0)) return s;
      s.to_light = d / s.distance;
      const Real cos_light = -dot(s.to_light, l.normal);
      if (cos_light <= 0) return s;  // the point sees the back of the light
      s.intensity = l.radiance * (cos_light * area / (kPi * r2));
      return s;
    }
    case LightKind::Sphere: {
      const Vec3 axis = l.position - p;
      const Real d2 = length_squared(axis);
      const Real r2 = l.radius * l.radius;
      if (d2 <= r2) return s;  // inside the light: not lit by it
      const Real dist = std::sqrt(d2);
      const Real sin2_max = r2 / d2;
      const Real cos_max = std::sqrt(std::fmax(Real(0), 1 - sin2_max));
      const Frame f = Frame::around(axis / dist);
      s.to_light = normalize(f.to_world(square_to_uniform_cone(u, cos_max)));
      s.pdf = uniform_cone_pdf(cos_max);
      // Where the direction meets the sphere (nearest root; grazing rays numerically missing it
      // take the tangent point's distance).
      const kernel::Sphere sphere{l.position, l.radius, 0};
      Real t = kernel::intersect(sphere, Ray{p, s.to_light}, 0, kInfinity);
      if (t == kInfinity) t = dot(axis, s.to_light);
      s.distance = t;
      s.point = p + s.to_light * t;
      s.intensity = l.radiance * (1 / (kPi * s.pdf));
      return s;
    }
    default: return s;
  }
}

// The stratum (i, j) of an n×n grid, jittered by `jitter`.
STRAHL_HOST_DEVICE inline Vec2 stratified(int i, int j, int n, const Vec2& jitter) {
  return {(i + jitter.x) / n, (j + jitter.y) / n};
}

// Distance along the ray to the light's emitting surface in (t_min, t_max), or kInfinity.
// Rectangles and disks are seen from their emitting side only.
STRAHL_HOST_DEVICE inline Real intersect_emitter(const Light& l, const Ray& ray, Real t_min, Real t_max) {
  switch (l.kind) {
    case LightKind::Rect:
    case LightKind::Disk: {
      const Real denom = dot(ray.direction, l.normal);
      if (denom >= 0) return kInfinity;  // parallel, or arriving at the back
      const Real t = dot(l.position - ray.origin, l.normal) / denom;
      if (!(t > t_min && t < t_max)) return kInfinity;
      const Vec3 q = ray.at(t) - l.position;
      if (l.kind == LightKind::Disk) return length_squared(q) <= l.radius * l.radius ? t : kInfinity;
      const Real uu = length_squared(l.edge_u), vv = length_squared(l.edge_v);
      const Real a = dot(q, l.edge_u), b = dot(q, l.edge_v);
      // Edges are perpendicular (the loader checks), so the coordinates are independent.
      return (a >= 0 && a <= uu && b >= 0 && b <= vv) ? t : kInfinity;
    }
    case LightKind::Sphere: return kernel::intersect(kernel::Sphere{l.position, l.radius, 0}, ray, t_min, t_max);
    default: return kInfinity;
  }
}

}  // namespace strahl
