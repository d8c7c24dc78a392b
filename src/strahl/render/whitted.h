#pragma once
// Whitted-style recursive ray tracing (lecture 2.1–2.5): nearest hit, local illumination
// (ambient + Lambert + Blinn-Phong per unshadowed light, all additive), then a mirror ray and a
// refracted ray, each weighted; recursion stops at max_depth and when a ray's weight in the
// pixel falls below min_weight.
//
// Colour at a hit with material m, colour C, shading normal N (towards the viewer), view
// direction V, and per light the unit vector L, half vector H = (L + V)/|L + V|, radiance I and
// shadow-ray transmittance S:
//   local = (1 − T)·k_a·C·ambient_light
//         + Σ_lights S·I·[ (1 − T)·k_d·C·max(0, N·L) + k_s·max(0, N·H)^shininess ]   (when N·L > 0)
//   colour = local + k_r·trace(reflected) + T·tint·trace(refracted)
// with T the transparency. Total internal reflection moves T into k_r; with Fresnel enabled a
// Schlick fraction F of T moves to k_r. Highlights are not dimmed by transparency (glass shines).
//
// Distributed ray tracing (Cook 1984) extends this: area lights contribute the mean of n×n
// stratified samples, each treated as a point light (shading/area_light.h); a ray meeting an
// area light's surface returns its radiance L; rough materials perturb the mirror and refracted
// directions (shading/glossy.h). The random numbers come from the camera sample's SampleStream,
// drawn in a fixed order, so images stay deterministic.

#include <cmath>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/medium_stack.h"
#include "strahl/render/ray_counters.h"
#include "strahl/render/surface_point.h"
#include "strahl/sampling/rng.h"
#include "strahl/shading/area_light.h"
#include "strahl/shading/glossy.h"
#include "strahl/shading/optics.h"

namespace strahl {

// x^e for the Blinn-Phong exponent: by repeated squaring when e is a whole number below 2^16
// (a handful of multiplications instead of a call to pow, which dominated the shading cost).
STRAHL_HOST_DEVICE inline Real specular_power(Real x, Real e) {
  if (e >= 0 && e < 65536 && e == Real(static_cast<unsigned>(e))) {
    Real result = 1;
    for (unsigned n = static_cast<unsigned>(e); n != 0; n >>= 1) {
      if (n & 1) result *= x;
      x *= x;
    }
    return result;
  }
  return std::pow(x, e);
}

// Light of intensity `intensity` arriving from unit direction `to_light` over `distance`:
// Lambert + Blinn-Phong, times the shadow ray's transmittance.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Vec3 shade_from(const SceneView& s, const SurfacePoint& sp, const Vec3& n, const Vec3& view,
                                          const Vec3& c, const Material& m, const Vec3& to_light, Real distance,
                                          const Vec3& intensity, RayCounters& counters) {
  const Real n_dot_l = dot(n, to_light);
  if (n_dot_l <= 0) return Vec3(0);  // light behind the surface
  ++counters.shadow;
  const Ray shadow_ray = spawn_ray(sp, to_light, sp.time);
  const Vec3 tr = transmittance(s, shadow_ray, distance);
  if (is_black(tr)) return Vec3(0);  // in shadow: ambient only
  const Vec3 h = normalize(to_light + view);
  const Real n_dot_h = dot(n, h);
  Vec3 contribution = c * (m.diffuse * (1 - m.transparency) * n_dot_l);
  if (n_dot_h > 0 && !is_black(m.specular)) contribution += m.specular * specular_power(n_dot_h, m.shininess);
  return contribution * intensity * tr;
}

// An area light's contribution: the mean over n×n jittered strata of its sample domain.
STRAHL_HOST_DEVICE STRAHL_NOINLINE inline Vec3 area_light_illumination(const SceneView& s, const Light& light,
                                                                     const SurfacePoint& sp, const Vec3& n,
                                                                     const Vec3& view, const Vec3& c, const Material& m,
                                                                     RayCounters& counters, SampleStream& rng) {
  const int k = light.samples;
  Vec3 sum{0};
  for (int j = 0; j < k; ++j) {
    for (int q = 0; q < k; ++q) {
      const AreaLightSample ls = sample_area_light(light, sp.p, stratified(q, j, k, rng.next2()));
      if (is_black(ls.intensity)) continue;
      sum += shade_from(s, sp, n, view, c, m, ls.to_light, ls.distance, ls.intensity, counters);
    }
  }
  return sum * (Real(1) / (k * k));
}

STRAHL_HOST_DEVICE inline Vec3 local_illumination(const SceneView& s, const SurfacePoint& sp, const Vec3& n,
                                                  const Vec3& view, RayCounters& counters, SampleStream& rng) {
  const Material& m = s.materials[sp.material];
  const Vec3 c = surface_color(m, sp.texcoord);
  const Real opacity = 1 - m.transparency;
  Vec3 result = c * s.settings.ambient_light * (m.ambient * opacity);
  for (std::uint32_t i = 0; i < s.light_count; ++i) {
    const Light& light = s.lights[i];
    if (!light.is_area()) {
      const LightSample ls = sample_light(light, sp.p);
      result += shade_from(s, sp, n, view, c, m, ls.to_light, ls.distance, light.radiance, counters);
      continue;
    }
    result += area_light_illumination(s, light, sp, n, view, c, m, counters, rng);
  }
  return result;
}

// Takes one ray from the sample's budget; false (and the cut counted) when none is left.
STRAHL_HOST_DEVICE inline bool spend(std::uint32_t& budget, RayCounters& counters) {
  if (budget == 0) {
    ++counters.cut;
    return false;
  }
  --budget;
  return true;
}

// The nearest area light the ray meets before t_max, or −1.
STRAHL_HOST_DEVICE inline int nearest_emitter(const SceneView& s, const Ray& ray, Real t_max) {
  int nearest = -1;
  for (std::uint32_t i = 0; i < s.light_count; ++i) {
    if (!s.lights[i].is_area()) continue;
    const Real t = intersect_emitter(s.lights[i], ray, 0, t_max);
    if (t < t_max) {
      t_max = t;
      nearest = int(i);
    }
  }
  return nearest;
}

// Radiance arriving along `ray`. `depth` is 1 for camera rays; `weight` is the ray's share of the
// pixel; `budget` is what is left of the camera sample's ray budget (TraceSettings::ray_budget):
// each reflected or refracted ray takes one, and once none is left further ones are cut (not
// traced, counted), depth first, the reflected ray before the refracted one.
STRAHL_HOST_DEVICE inline Vec3 trace(const SceneView& s, const Ray& ray, int depth, Real weight,
                                     const MediumStack& media, RayCounters& counters, SampleStream& rng,
                                     std::uint32_t& budget) {
  const Hit hit = closest_hit(s, ray, 0, kInfinity);
  if (s.area_light_count > 0) {
    const int emitter = nearest_emitter(s, ray, hit.t);
    if (emitter >= 0) return s.lights[emitter].radiance;
  }
  if (!hit.found()) return s.settings.background;

  const SurfacePoint sp = surface_at(s, ray, hit);
  const Material& m = s.materials[sp.material];
  // Does the ray arrive at the front (outside) of the surface? Normals then face the viewer.
  const bool front = dot(ray.direction, sp.geometric_normal) < 0;
  const Vec3 n = front ? sp.normal : -sp.normal;
  const Vec3 view = -ray.direction;

  Vec3 color = local_illumination(s, sp, n, view, counters, rng);
  if (depth >= s.settings.max_depth) return color;

  Real kr = m.reflectivity;
  Real kt = m.transparency;
  Vec3 refracted_dir;
  MediumStack next_media = media;
  if (kt > 0) {
    // Entering: from the current medium into the object; leaving: from the object to the outer one.
    const Real n1 = front ? media.current() : m.ior;
    const Real n2 = front ? m.ior : media.outer();
    if (!refract(ray.direction, n, n1 / n2, refracted_dir)) {
      kr += kt;  // total internal reflection: all transmitted light is reflected
      kt = 0;
    } else {
      if (m.fresnel) {
        const Real f = schlick(dot(view, n), n1, n2);
        kr += kt * f;
        kt *= 1 - f;
      }
      next_media = front ? media.entered(m.ior) : media.left();
    }
  }
  if (kr > 0 && kr * weight >= s.settings.min_weight && spend(budget, counters)) {
    ++counters.reflection;
    Vec3 dir = reflect(ray.direction, n);
    if (m.roughness > 0) dir = glossy_direction(dir, sp.geometric_normal, m.roughness, rng.next2());
    const Ray r = spawn_ray(sp, dir, ray.time);
    color += trace(s, r, depth + 1, weight * kr, media, counters, rng, budget) * kr;
  }
  if (kt > 0 && kt * weight >= s.settings.min_weight && spend(budget, counters)) {
    ++counters.refraction;
    if (m.roughness > 0) refracted_dir = glossy_direction(refracted_dir, sp.geometric_normal, m.roughness, rng.next2());
    const Ray r = spawn_ray(sp, refracted_dir, ray.time);
    const Vec3 tint = m.filter ? m.color : Vec3(1);
    color += trace(s, r, depth + 1, weight * kt, next_media, counters, rng, budget) * tint * kt;
  }
  return color;
}

}  // namespace strahl
