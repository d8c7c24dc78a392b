#pragma once
// Whitted-style recursive ray tracing (lecture 2.1–2.5): nearest hit, local illumination
// (ambient + Lambert + Blinn-Phong per unshadowed light, all additive), then a mirror ray and a
// refracted ray, each weighted; recursion stops at max_depth and when a ray's weight in the
// pixel falls below min_weight. The recursion is written as a loop over an explicit stack
// (trace() below), so that the GPU runs the same code.
//
// Colour at a hit with material m, colour C, shading normal N (towards the viewer), view
// direction V, and per light the unit vector L, half vector H = (L + V)/|L + V|, radiance I and
// shadow-ray transmittance S:
//   local = (1 − T)·k_a·C·ambient_light + E
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
#include <type_traits>

#include "strahl/render/intersect_packet.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/render/medium_stack.h"
#include "strahl/render/ray_counters.h"
#include "strahl/render/surface_point.h"
#include "strahl/sampling/rng.h"
#include "strahl/shading/area_light.h"
#include "strahl/shading/blinn_phong.h"
#include "strahl/shading/glossy.h"
#include "strahl/shading/optics.h"

namespace strahl {

// The shadow ray from surface point `sp` towards a light in unit direction `to_light`.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Ray shadow_ray(const SurfacePoint& sp, const Vec3& to_light) {
  return spawn_ray(sp, to_light, sp.time);
}

// The packet front end (render/packet_radiance.h) handles scenes with up to this many lights.
inline constexpr int kMaxPacketLights = 4;

// What the packet front end found of point light i at a surface point: sample_light()'s answer
// and, where dot(n, to_light) > 0, the transmittance of the shadow ray it traced and
// dot(n, h) of the half vector h = normalize(to_light + view) — the same arithmetic as below.
struct KnownLight {
  LightSample sample;
  Vec3 transmittance;
  Real n_dot_h;
};

// Light of intensity `intensity` arriving from unit direction `to_light` over `distance`:
// Lambert + Blinn-Phong, times the shadow ray's transmittance — traced here, or, where `known` is
// given, taken from the packet front end with dot(n, h), which it computed side by side.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Vec3 shade_from(const SceneView& s, const SurfacePoint& sp, const Vec3& n, const Vec3& view,
                                          const Vec3& c, const Material& m, const Vec3& to_light, Real distance,
                                          const Vec3& intensity, RayCounters& counters,
                                          const KnownLight* known = nullptr) {
  const Real n_dot_l = dot(n, to_light);
  if (n_dot_l <= 0) return Vec3(0);  // light behind the surface
  Vec3 tr;
  if (known != nullptr) {
    tr = known->transmittance;
  } else {
    ++counters.shadow;
    tr = transmittance(s, shadow_ray(sp, to_light), distance);
  }
  if (is_black(tr)) return Vec3(0);  // in shadow: ambient only
  const Real n_dot_h = known != nullptr ? known->n_dot_h : dot(n, normalize(to_light + view));
  Vec3 contribution = c * (m.diffuse * (1 - m.transparency) * n_dot_l);
  if (n_dot_h > 0 && !is_black(m.specular)) contribution += m.specular * specular_power(n_dot_h, m.shininess);
  return contribution * intensity * tr;
}

// transmittance(s, r.ray(i), distance[i]) for the lanes of `cast`, into (tx[i], ty[i], tz[i]):
// as one packet (transmittance_packet) where more than half of the N lanes take part, else one
// by one — a packet half full or less costs more than its rays one by one (a light of 2×2
// samples in 8 lanes: 14 % slower in the lecture's scene). The other lanes are left as they are.
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void shadow_transmittance(const SceneView& s, std::uint32_t cast,
                                                                 const PacketRays<N>& shadow, const Real* distance,
                                                                 Real* tx, Real* ty, Real* tz) {
  if constexpr (N == 8 || N == 16) {
    if (wide_bvh_detail::popcount(cast) > N / 2) {
      transmittance_packet<N>(s, cast, shadow, distance, tx, ty, tz);
      return;
    }
  }
  for (std::uint32_t q = cast; q != 0; q &= q - 1) {
    const int i = wide_bvh_detail::lowest_bit(q);
    const Vec3 tr = transmittance(s, shadow.ray(i), distance[i]);
    tx[i] = tr.x, ty[i] = tr.y, tz[i] = tr.z;
  }
}

// The GPU (one thread per camera sample) takes an area light's samples one after another; so do
// host builds with STRAHL_PORTABLE_KERNELS, where the test portable_kernels_match demands the
// images of the CPU's groups below, bit for bit.
#if defined(__CUDA_ARCH__) || defined(STRAHL_PORTABLE_KERNELS)
#define STRAHL_AREA_LIGHT_ONE_BY_ONE 1
#endif

#if !defined(STRAHL_AREA_LIGHT_ONE_BY_ONE)
// Strata first … first + size − 1 (size ≤ N) of an area light with k×k strata seen from one
// point (`light`: every lane from sp.p), added to `sum` in their order: the samples side by side,
// then their shadow rays (shadow_transmittance: from one point towards one light, as coherent as
// rays get), then shade_from()'s arithmetic on each with the shadow ray's answer (add_light_lanes).
// The sum is the one-by-one loop's of area_light_illumination, bit for bit.
template <int N>
STRAHL_FORCE_INLINE void add_area_light_group(const SceneView& s, const AreaLightLanes<N>& light, int k, int first,
                                              int size, const SurfacePoint& sp, const Vec3& n, const Vec3& view,
                                              const Vec3& c, const Material& m, RayCounters& counters,
                                              SampleStream& rng, Vec3& sum) {
  Real ux[N], uy[N];
  for (int i = 0; i < N; ++i) {
    const int stratum = first + i;
    const Vec2 u = i < size ? stratified(stratum % k, stratum / k, k, rng.next2()) : Vec2{0.5, 0.5};
    ux[i] = u.x, uy[i] = u.y;
  }
  Real lx[N], ly[N], lz[N], distance[N], ir[N], ig[N], ib[N];
  light.sample(ux, uy, lx, ly, lz, distance, ir, ig, ib);
  PacketRays<N> shadow;
  shadow.unit = true;  // (to_light: normalised by the sampler)
  Real tx[N], ty[N], tz[N];
  std::uint32_t cast = 0;  // shade_from() traces a shadow ray where the light is in front
  for (int i = 0; i < N; ++i) {
    const Vec3 to_light(lx[i], ly[i], lz[i]);
    const bool lit = i < size && !is_black(Vec3(ir[i], ig[i], ib[i])) && !(dot(n, to_light) <= 0);
    cast |= std::uint32_t(lit) << i;
    shadow.set(i, lit ? shadow_ray(sp, to_light) : Ray{sp.p, n, sp.time});
    distance[i] = lit ? distance[i] : Real(0);
  }
  counters.shadow += std::uint64_t(wide_bvh_detail::popcount(cast));
  for (int i = 0; i < N; ++i) tx[i] = ty[i] = tz[i] = 0;
  shadow_transmittance<N>(s, cast, shadow, distance, tx, ty, tz);
  // shade_from() on each sample with its shadow ray's answer, the samples side by side
  // (add_light_lanes: the same arithmetic; 0 where no ray was cast), added to `sum` in order.
  ShadingLanes<N> terms;
  Real n_dot_l[N], n_dot_h[N], rr[N], rg[N], rb[N];
  const Real kd = m.diffuse * (1 - m.transparency), shiny = is_black(m.specular) ? Real(0) : Real(1);
  for (int i = 0; i < N; ++i) {
    terms.cr[i] = c.x, terms.cg[i] = c.y, terms.cb[i] = c.z, terms.kd[i] = kd;
    terms.sr[i] = m.specular.x, terms.sg[i] = m.specular.y, terms.sb[i] = m.specular.z;
    terms.shiny[i] = shiny, terms.shininess[i] = m.shininess;
    n_dot_l[i] = n.x * lx[i] + n.y * ly[i] + n.z * lz[i];
    const Real hx = lx[i] + view.x, hy = ly[i] + view.y, hz = lz[i] + view.z;  // normalize(to_light + view)
    const Real inv = Real(1) / std::sqrt(hx * hx + hy * hy + hz * hz);
    n_dot_h[i] = n.x * (hx * inv) + n.y * (hy * inv) + n.z * (hz * inv);
    rr[i] = rg[i] = rb[i] = 0;
  }
  add_light_lanes<N>(ir, ig, ib, (1u << size) - 1, cast, n_dot_l, n_dot_h, tx, ty, tz, terms, rr, rg, rb);
  for (int i = 0; i < size; ++i) sum += Vec3(rr[i], rg[i], rb[i]);
}
#endif

// An area light's contribution: the mean over k×k jittered strata of its sample domain (k: the
// light's n, or 1 at a path tracer's deeper vertices).
STRAHL_HOST_DEVICE STRAHL_NOINLINE inline Vec3 area_light_illumination(const SceneView& s, const Light& light, int k,
                                                                     const SurfacePoint& sp, const Vec3& n,
                                                                     const Vec3& view, const Vec3& c, const Material& m,
                                                                     RayCounters& counters, SampleStream& rng) {
  const int strata = k * k;
  Vec3 sum{0};
#if !defined(STRAHL_AREA_LIGHT_ONE_BY_ONE)
  // On the CPU a group of samples at a time, side by side (add_area_light_group): 2×2 strata in
  // 4 lanes, more in groups of 8. One sample alone (a light of 1×1, a path's deeper hits) is
  // taken as below: in 4 lanes it would leave three idle.
  if (strata > 1) {
    if (strata <= 4) {
      add_area_light_group<4>(s, AreaLightLanes<4>(light, sp.p), k, 0, strata, sp, n, view, c, m, counters, rng, sum);
    } else {
      const AreaLightLanes<8> lanes(light, sp.p);
      for (int first = 0; first < strata; first += 8)
        add_area_light_group<8>(s, lanes, k, first, strata - first < 8 ? strata - first : 8, sp, n, view, c, m,
                                counters, rng, sum);
    }
    return sum * (Real(1) / (k * k));
  }
#endif
  const AreaLightSampler sampler(light, sp.p);
  for (int stratum = 0; stratum < strata; ++stratum) {
    const AreaLightSample ls = sampler.sample(stratified(stratum % k, stratum / k, k, rng.next2()));
    if (is_black(ls.intensity)) continue;
    sum += shade_from(s, sp, n, view, c, m, ls.to_light, ls.distance, ls.intensity, counters);
  }
  return sum * (Real(1) / (k * k));
}

// The ambient term of the local colour: (1 − T)·k_a·C·ambient_light, C = c.
STRAHL_HOST_DEVICE inline Vec3 ambient_term(const SceneView& s, const Material& m, const Vec3& c) {
  const Real opacity = 1 - m.transparency;
  return c * s.settings.ambient_light * (m.ambient * opacity);
}

// Adds to `result` the light of every light source, one after another: Lambert + Blinn-Phong of
// each unshadowed point light and each area light's mean over k×k samples — k the light's n, or
// 1 where `one_sample` (a path's deeper vertices, render/path_tracer.h). `known`, where given,
// holds known[i] for each point light i (the packet front end's); else the lights are sampled
// and the shadow rays traced here.
STRAHL_HOST_DEVICE inline void add_direct_light(const SceneView& s, const SurfacePoint& sp, const Vec3& n,
                                                const Vec3& view, const Vec3& c, const Material& m,
                                                RayCounters& counters, SampleStream& rng, Vec3& result,
                                                const KnownLight* known = nullptr, bool one_sample = false) {
  for (std::uint32_t i = 0; i < s.light_count; ++i) {
    const Light& light = s.lights[i];
    if (!light.is_area()) {
      // The share that reaches this point (a spot's cone, a fade; 1 for other lights); none:
      // no shadow ray either.
      const LightSample ls = known != nullptr ? known[i].sample : sample_light(light, sp.p);
      const Real share = light_share(light, ls.to_light, ls.distance);
      if (!(share > 0)) continue;
      result += shade_from(s, sp, n, view, c, m, ls.to_light, ls.distance, light.radiance * share, counters,
                           known != nullptr ? &known[i] : nullptr);
      continue;
    }
    result += area_light_illumination(s, light, one_sample ? 1 : light.samples, sp, n, view, c, m, counters, rng);
  }
}

// The local colour's terms that need no light: the ambient term and the material's emission E.
STRAHL_HOST_DEVICE inline Vec3 unlit_term(const SceneView& s, const Material& m, const Vec3& c) {
  return ambient_term(s, m, c) + m.emission;
}

// The local colour: the ambient term and the emission, then each light's (add_direct_light;
// `known` as there).
STRAHL_HOST_DEVICE inline Vec3 local_illumination(const SceneView& s, const SurfacePoint& sp, const Vec3& n,
                                                  const Vec3& view, RayCounters& counters, SampleStream& rng,
                                                  const KnownLight* known = nullptr) {
  const Material& m = s.materials[sp.material];
  const Vec3 c = surface_color(m, sp.texcoord, s.textures);
  Vec3 result = unlit_term(s, m, c);
  add_direct_light(s, sp, n, view, c, m, counters, rng, result, known);
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

// How a hit on material m (unit normal n towards the arriving ray, `front` where the ray arrives
// at the outside; the ray in `media`) divides the light it passes on: k_r (kr) for the reflected
// ray and T (kt) for the refracted one, which leaves in `refracted_dir` where kt > 0. Total
// internal reflection moves T into k_r; with Fresnel a Schlick fraction of T moves to k_r.
STRAHL_HOST_DEVICE inline void split_at(const Material& m, const Vec3& direction, const Vec3& n, bool front,
                                        const MediumStack& media, Real& kr, Real& kt, Vec3& refracted_dir) {
  kr = m.reflectivity;
  kt = m.transparency;
  if (!(kt > 0)) return;
  // Entering: from the current medium into the object; leaving: from the object to the outer one.
  const Real n1 = front ? media.current() : m.ior;
  const Real n2 = front ? m.ior : media.outer();
  if (!refract(direction, n, n1 / n2, refracted_dir)) {
    kr += kt;  // total internal reflection: all transmitted light is reflected
    kt = 0;
  } else if (m.fresnel) {
    const Real f = schlick(dot(-direction, n), n1, n2);
    kr += kt * f;
    kt *= 1 - f;
  }
}

// The tint of the light a refracted ray brings back through material m: its colour where it
// filters, else none.
STRAHL_HOST_DEVICE inline Vec3 transmission_tint(const Material& m) { return m.filter ? m.color : Vec3(1); }

// The deepest ray tree trace() follows: scenes allow max_depth up to this (camera rays are depth 1).
inline constexpr int kMaxTraceDepth = 64;

// What the packet front end has already found for a camera ray, as trace()'s first step would
// find it: the nearest hit, the area light met first (−1: none), and, where the ray hit a surface
// and no emitter, its surface point and what it found of each point light (area lights' entries
// unset).
struct FirstHit {
  Hit hit;
  int emitter;
  SurfacePoint sp;
  KnownLight lights[kMaxPacketLights];
};

// Uninitialised storage for FirstHit (its Vec3 members would be zeroed, sixteen per packet).
union FirstHitSlot {
  FirstHit first;
  STRAHL_HOST_DEVICE FirstHitSlot() {}
};

// A hit of the ray tree whose local colour is known and one of whose children (the reflected ray,
// then the refracted one) is being traced: what it needs to add the child's radiance and to
// start the refracted ray when the reflected one's subtree is done.
struct TraceFrame {
  Vec3 color;                 // local illumination, plus k_r times the reflected radiance once known
  Vec3 p, geometric_normal;   // spawn_ray's start of the refracted ray
  Vec3 refracted_dir;         // before the glossy perturbation, drawn when the ray starts
  Real offset;
  Real weight;                // this hit's ray's share of the pixel
  Real kr, kt;                // after total internal reflection and Fresnel
  MediumStack::Undo media;    // how to leave the refracted ray's media
  std::uint32_t material;
  bool front;                 // the ray arrived at the outside: the refracted ray enters the object
  bool refracting;            // the child being traced is the refracted ray (else the reflected one)
};

// Uninitialised storage for the frames (Vec3's members default to 0, and zeroing the whole stack
// for every camera sample would cost more than most samples' tracing).
union TraceFrameSlot {
  TraceFrame frame;
  STRAHL_HOST_DEVICE TraceFrameSlot() {}
};

// Starts frame f's refracted ray if it has one and its weight and the ray budget allow it:
// `ray`, `weight` and `media` become the refracted ray's (the glossy direction drawn now, after
// the reflected ray's whole subtree, as recursion would draw it).
STRAHL_HOST_DEVICE inline bool start_refracted(const SceneView& s, TraceFrame& f, Real time, Ray& ray, Real& weight,
                                               MediumStack& media, std::uint32_t& budget, RayCounters& counters,
                                               SampleStream& rng) {
  if (!(f.kt > 0 && f.kt * f.weight >= s.settings.min_weight && spend(budget, counters))) return false;
  ++counters.refraction;
  const Material& m = s.materials[f.material];
  Vec3 dir = f.refracted_dir;
  if (m.roughness > 0) dir = glossy_direction(dir, f.geometric_normal, m.roughness, rng.next2());
  ray = spawn_ray(f.p, f.geometric_normal, dir, time, f.offset);
  weight = f.weight * f.kt;
  f.media = f.front ? media.enter(m.ior) : media.leave();
  f.refracting = true;
  return true;
}

// Radiance arriving along the camera ray `ray` (depth 1, weight 1, in the scene's medium).
// Whitted's recursion written as one loop over an explicit stack of the pending hits on the
// path from the camera (kernel code for the CPU and the GPU alike: no recursion, no allocation).
// At a hit: local illumination; below max_depth, the reflected ray and then the refracted ray,
// each traced if its weight (its share of the pixel, the product of the k_r and k_t factors on
// its path) is at least min_weight and the camera sample's ray budget (TraceSettings::ray_budget)
// has a ray left; once none is left further rays are cut (not traced, counted). Rays are traced
// depth first, the reflected subtree before the refracted ray, and each hit's colour is
// local + k_r·reflected + T·tint·refracted added in that order, so the random numbers (area lights,
// glossy directions) are drawn in the same order and the sums are the same as a recursive
// trace()'s, bit for bit.
//
// `first`, where given, is the first step of `ray` already taken by the packet front end (the
// same hit, surface point and shadow rays): trace() goes on from there. `start`, where given,
// places `ray` deeper in a camera sample's ray tree (the packet front end's reflected and
// refracted rays, render/packet_radiance.h): its depth, its weight, the rays left in the budget,
// the media it travels in; and where to tell how many rays are left when its subtree is done.
//
// trace_observed() tells an observer the ray tree as it walks it (render/explain.h shows one
// camera sample's): observer->ray(kind, depth, ray, weight) as each ray starts; then
// observer->emitter(light, L), ->background(colour) or ->surface(hit, sp, front, n, local) and,
// below max_depth, ->split(k_r, T, reflects, n_1, n_2) (after total internal reflection and
// Fresnel; `reflects`: the reflected ray is traced; n_1 → n_2 the indices of refraction a
// refracted ray crosses); and observer->done(depth, colour) once the ray's
// radiance is known.
struct TraceStart {
  int depth = 1;
  Real weight = 1;
  std::uint32_t spent = 0;              // rays of the scene's ray_budget already taken (≤ it)
  const MediumStack* media = nullptr;   // null: the scene's medium
  std::uint32_t* left = nullptr;        // where given: the budget left at the end
};
enum class TracedRay : std::uint8_t { Camera, Reflected, Refracted };
struct NoTraceObserver {};
// trace()'s body, and trace_observed()'s (below); with NoTraceObserver (trace()) every call of
// the observer is left out at compile time.
template <class Observer>
STRAHL_HOST_DEVICE inline Vec3 walk_ray_tree(const SceneView& s, Ray ray, RayCounters& counters, SampleStream& rng,
                                             const FirstHit* first, const TraceStart& start, Observer* observer) {
  constexpr bool observed = !std::is_same_v<Observer, NoTraceObserver>;
  TracedRay kind = TracedRay::Camera;        // of `ray` (as the observer is told)
  TraceFrameSlot stack[kMaxTraceDepth - 1];  // hits at depths 1 … max_depth − 1 (deeper ones spawn no rays)
  int top = 0;                               // frames in use: `ray` is at depth top + start.depth
  const int max_depth = s.settings.max_depth < kMaxTraceDepth ? s.settings.max_depth : kMaxTraceDepth;
  const Real min_weight = s.settings.min_weight;
  const Real time = ray.time;                // every ray of a camera sample sees the scene at one instant
  std::uint32_t budget = s.settings.ray_budget - start.spent;
  // The media of `ray`, restored on the way back up.
  MediumStack media = start.media != nullptr ? *start.media : MediumStack(s.settings.medium_ior);
  Real weight = start.weight;                // `ray`'s share of the pixel

  for (;;) {
    if constexpr (observed) observer->ray(kind, top + start.depth, ray, weight);
    // `ray`'s own colour, unless it spawns a child: then its frame is pushed and the child traced.
    Vec3 color;
    const FirstHit* known = first;
    first = nullptr;
    const Hit hit = known != nullptr ? known->hit : closest_hit(s, ray, 0, kInfinity);
    const int emitter = known != nullptr ? known->emitter : s.area_light_count > 0 ? nearest_emitter(s, ray, hit.t) : -1;
    if (emitter >= 0) {
      color = s.lights[emitter].radiance;
      if constexpr (observed) observer->emitter(emitter, color);
    } else if (!hit.found()) {
      color = s.settings.background;
      if constexpr (observed) observer->background(color);
    } else {
      const SurfacePoint sp = known != nullptr ? known->sp : surface_at(s, ray, hit);
      const Material& m = s.materials[sp.material];
      // Does the ray arrive at the front (outside) of the surface? Normals then face the viewer.
      const bool front = dot(ray.direction, sp.geometric_normal) < 0;
      const Vec3 n = front ? sp.normal : -sp.normal;
      const Vec3 view = -ray.direction;
      color = local_illumination(s, sp, n, view, counters, rng, known != nullptr ? known->lights : nullptr);
      if constexpr (observed) observer->surface(hit, sp, front, n, color);
      if (top + start.depth < max_depth) {
        Real kr, kt;
        Vec3 refracted_dir;
        split_at(m, ray.direction, n, front, media, kr, kt, refracted_dir);
        const bool reflects = kr > 0 && kr * weight >= min_weight && spend(budget, counters);
        if constexpr (observed)  // (the indices split_at() refracts between)
          observer->split(kr, kt, reflects, front ? media.current() : m.ior, front ? m.ior : media.outer());
        if (reflects || kt > 0) {
          TraceFrame& f = stack[top].frame;
          f.color = color;
          f.p = sp.p;
          f.geometric_normal = sp.geometric_normal;
          f.refracted_dir = refracted_dir;
          f.offset = sp.offset;
          f.weight = weight;
          f.kr = kr;
          f.kt = kt;
          f.material = sp.material;
          f.front = front;
          f.refracting = false;
          if (reflects) {
            ++counters.reflection;
            Vec3 dir = reflect(ray.direction, n);
            if (m.roughness > 0) dir = glossy_direction(dir, sp.geometric_normal, m.roughness, rng.next2());
            ray = spawn_ray(sp, dir, time);
            weight = weight * kr;
            kind = TracedRay::Reflected;
            ++top;
            continue;
          }
          if (start_refracted(s, f, time, ray, weight, media, budget, counters, rng)) {
            kind = TracedRay::Refracted;
            ++top;
            continue;
          }
        }
      }
    }
    // Return `color` to the hits waiting for it, until one starts its refracted ray or none is left.
    if constexpr (observed) observer->done(top + start.depth, color);
    for (;;) {
      if (top == 0) {
        if (start.left != nullptr) *start.left = budget;
        return color;
      }
      TraceFrame& f = stack[top - 1].frame;
      if (!f.refracting) {
        f.color += color * f.kr;
        if (start_refracted(s, f, time, ray, weight, media, budget, counters, rng)) {
          kind = TracedRay::Refracted;
          break;
        }
      } else {
        f.color += color * transmission_tint(s.materials[f.material]) * f.kt;
        media.undo(f.media);
      }
      color = f.color;
      --top;
      if constexpr (observed) observer->done(top + start.depth, color);
    }
  }
}

STRAHL_HOST_DEVICE inline Vec3 trace(const SceneView& s, Ray ray, RayCounters& counters, SampleStream& rng,
                                     const FirstHit* first = nullptr, const TraceStart& start = {}) {
  return walk_ray_tree<NoTraceObserver>(s, ray, counters, rng, first, start, nullptr);
}

// trace() of a camera ray, telling `observer` the ray tree as it walks it (see above).
template <class Observer>
STRAHL_HOST_DEVICE inline Vec3 trace_observed(const SceneView& s, Ray ray, RayCounters& counters, SampleStream& rng,
                                              Observer& observer) {
  return walk_ray_tree(s, ray, counters, rng, nullptr, TraceStart{}, &observer);
}

}  // namespace strahl
