#pragma once
// Path tracing (Kajiya 1986): global illumination beside Whitted's ray tracing, for scenes with
// render.integrator: path. Whitted's local colour has an ambient term k_a·C·ambient_light that
// stands in for the light surfaces throw at each other; a path tracer computes that light. One
// camera sample follows one path: at each hit
//   – the direct light (render/whitted.h add_direct_light: Lambert + Blinn-Phong of every
//     unshadowed point light, area lights sampled — n×n at the first hit, one sample deeper),
//     plus the material's emission E: Whitted's local colour without its ambient term;
//   – then one way on, chosen at random among the three the material's light takes: the
//     diffuse bounce (weight w_d = k_d·(1 − T)·C, a cosine-distributed direction), the mirror
//     ray (w_r = k_r) and the refracted ray (w_t = T·tint), k_r and T after total internal
//     reflection and Fresnel as Whitted's split_at() divides them. Way i is taken with
//     probability p_i = a_i/Σa (a = the largest component of w) and the path's throughput β is
//     multiplied by w_i/p_i, so each way's expected contribution is w_i times its radiance.
// The Lambert BRDF is k_d·C/π and the cosine-distributed direction has density cos θ/π, so the
// diffuse bounce's weight is k_d·C: incoming radiance L over the hemisphere gives k_d·C·L, the
// convention area lights already follow (shading/area_light.h: a point light of intensity I at
// normal incidence lights a surface as a hemisphere of radiance I).
//
// Emitting materials (Material::emission E) add E at every hit — they are not sampled as lights,
// so a bounce that meets one is the only way their light arrives.
//
// Light is counted once: the area lights' surfaces show to camera, mirror and refracted rays
// (as in Whitted's images) but not to a ray after a diffuse bounce, whose point sampled them
// already as direct light; the background shows to every ray (it is not sampled as a light).
// The Blinn-Phong highlight stays a term of the direct light only, as in the lecture.
//
// A path ends at max_depth hits, where no way on has any weight, where the diffuse direction
// drawn would enter the surface (a shading normal far from the geometric one), when the camera
// sample's ray budget is spent, and by Russian roulette after the third hit: the path goes on
// with probability q = min(1, max component of β) and β is divided by q. The estimate is
// unbiased for the chosen max_depth; min_weight is Whitted's and not used here.
//
// Kernel code (CPU and GPU): one loop, no recursion, no allocation. The random numbers come
// from the camera sample's stream in a fixed order per hit (area lights' samples, the way on,
// its direction, the roulette).

#include "strahl/render/whitted.h"

namespace strahl {

// The diffuse direction: cosine-distributed about the unit normal n (density cos θ/π).
STRAHL_HOST_DEVICE inline Vec3 diffuse_direction(const Vec3& n, const Vec2& u) {
  return normalize(Frame::around(n).to_world(square_to_cosine_hemisphere(u)));
}

// The hits a path always reaches where its ways on have weight; Russian roulette decides on
// every ray after them.
inline constexpr int kRouletteDepth = 3;

// Radiance arriving along the camera ray `ray` by path tracing (see above).
STRAHL_HOST_DEVICE inline Vec3 trace_path(const SceneView& s, Ray ray, RayCounters& counters, SampleStream& rng) {
  const int max_depth = s.settings.max_depth < kMaxTraceDepth ? s.settings.max_depth : kMaxTraceDepth;
  const Real time = ray.time;  // every ray of a camera sample sees the scene at one instant
  std::uint32_t budget = s.settings.ray_budget;
  MediumStack media(s.settings.medium_ior);
  Vec3 radiance{0};
  Vec3 beta{1};               // the path's throughput: the weight of the light arriving along `ray`
  bool sees_emitters = true;  // false after a diffuse bounce (its point sampled the area lights)
  for (int depth = 1;; ++depth) {
    const Hit hit = closest_hit(s, ray, 0, kInfinity);
    const int emitter = s.area_light_count > 0 ? nearest_emitter(s, ray, hit.t) : -1;
    if (emitter >= 0) {
      if (sees_emitters) radiance += beta * s.lights[emitter].radiance;
      return radiance;
    }
    if (!hit.found()) return radiance + beta * s.settings.background;

    const SurfacePoint sp = surface_at(s, ray, hit);
    const Material& m = s.materials[sp.material];
    const bool front = dot(ray.direction, sp.geometric_normal) < 0;  // normals then face the viewer
    const Vec3 n = front ? sp.normal : -sp.normal;
    const Vec3 c = surface_color(m, sp.texcoord, s.textures);
    Vec3 direct = m.emission;  // (no ambient term)
    add_direct_light(s, sp, n, -ray.direction, c, m, counters, rng, direct, nullptr, depth > 1);
    radiance += beta * direct;
    if (depth >= max_depth) return radiance;

    // The way on.
    Real kr, kt;
    Vec3 refracted_dir;
    split_at(m, ray.direction, n, front, media, kr, kt, refracted_dir);
    const Vec3 wd = c * (m.diffuse * (1 - m.transparency));
    const Vec3 wt = transmission_tint(m) * kt;
    const Real ad = max_component(wd), ar = kr, at = max_component(wt);
    const Real total = ad + ar + at;
    if (!(total > 0) || !spend(budget, counters)) return radiance;
    // Way 0, 1 or 2 for pick in [0, a_d), [a_d, a_d + a_r), [a_d + a_r, Σa); the last way with a
    // weight where rounding puts pick at Σa.
    const Real pick = rng.next() * total;
    int way = at > 0 ? 2 : ar > 0 ? 1 : 0;
    if (pick < ad) way = 0;
    else if (pick < ad + ar) way = 1;
    if (way == 0) {
      const Vec3 facing = front ? sp.geometric_normal : -sp.geometric_normal;
      const Vec3 dir = diffuse_direction(n, rng.next2());
      if (!(dot(dir, facing) > 0)) return radiance;  // would enter the surface
      ++counters.reflection;
      beta = beta * wd * (total / ad);
      sees_emitters = false;
      ray = spawn_ray(sp, dir, time);
    } else if (way == 1) {
      ++counters.reflection;
      Vec3 dir = reflect(ray.direction, n);
      if (m.roughness > 0) dir = glossy_direction(dir, sp.geometric_normal, m.roughness, rng.next2());
      beta *= total;  // w_r/p_r = k_r·Σa/k_r
      sees_emitters = true;
      ray = spawn_ray(sp, dir, time);
    } else {
      ++counters.refraction;
      Vec3 dir = refracted_dir;
      if (m.roughness > 0) dir = glossy_direction(dir, sp.geometric_normal, m.roughness, rng.next2());
      beta = beta * wt * (total / at);
      sees_emitters = true;
      ray = spawn_ray(sp, dir, time);
      if (front) media.enter(m.ior);
      else media.leave();
    }
    if (depth >= kRouletteDepth) {
      const Real q = max_component(beta);
      if (q < 1) {
        if (!(rng.next() < q)) return radiance;
        beta = beta / q;
      }
    }
  }
}

}  // namespace strahl
