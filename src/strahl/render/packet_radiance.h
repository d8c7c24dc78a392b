#pragma once
// Camera samples in packets: up to N consecutive samples of one pixel (coherent rays: they leave
// the same eye through one pixel) take their first step together — the camera rays' nearest hits,
// then, light by light, the shadow rays from those hits — through the packet queries of
// intersect_packet.h, whose planes and sphere loops run the lanes side by side and whose BVH
// fetches each node once per packet. A sample whose surface spawns no ray (no mirror, no
// glass) is shaded there too, the lanes side by side (add_light_lanes; an area light's strata
// stratum after stratum, each lane's drawn from its own stream: add_area_light_lanes). So is a
// sample on a mirror or on glass, and the packet's samples there take their reflected rays
// together, then their refracted rays, each as another such step, through their ray trees
// (packet_tree) while enough lanes follow the same branch. Every other sample,
// and every lane where too few go on together, goes on alone in the one integrator, trace()
// (render/whitted.h), from the step it reached (FirstHit, TraceStart): shading, reflected and
// refracted rays.
// The radiance of each sample is sample_radiance()'s bit for bit (same hits, same shadow rays,
// same arithmetic; the counters the same too), except where a camera ray meets two triangles at
// exactly the same t (accel/packet.h).

#include "strahl/render/integrator.h"
#include "strahl/render/intersect_packet.h"
#include "strahl/render/surface_lanes.h"
#include "strahl/sampling/pixel_sampler.h"

namespace strahl {

// Whether the packet front end handles the scene: Whitted's integrator (a path tracer's samples
// go one by one) and lights that FirstHit::lights has room for.
STRAHL_HOST_DEVICE inline bool packet_radiance_supported(const SceneView& s) {
  return s.light_count <= kMaxPacketLights && s.settings.integrator == IntegratorKind::Whitted;
}

// local_illumination()'s per-surface terms of a material that spawns no ray: the colour at
// `texcoord`, the ambient term, k_d (times the opacity), k_s and whether it is not black, the
// shininess.
struct LocalTerms {
  Vec3 c, ambient;
  Real kd;
  Vec3 ks;
  Real shiny, shininess;
};
STRAHL_HOST_DEVICE inline LocalTerms local_terms(const Material& material, const Vec3& texcoord,
                                                 const kernel::Textures& textures, const Vec3& ambient_light) {
  LocalTerms t;
  t.c = surface_color(material, texcoord, textures);
  const Real opacity = 1 - material.transparency;
  t.ambient = t.c * ambient_light * (material.ambient * opacity) + material.emission;  // unlit_term()
  t.kd = material.diffuse * (1 - material.transparency);
  t.ks = material.specular;
  t.shiny = is_black(material.specular) ? 0 : 1;
  t.shininess = material.shininess;
  return t;
}

// What the first step of a packet of rays found (packet_step): the lanes that hit a surface,
// their normals, and either their colour or, for the lanes that go on in trace(), its FirstHit.
template <int N>
struct PacketStep {
  FirstHitSlot slots[N];      // the lanes of `active & ~local`: what trace()'s first step finds
  Real nx[N], ny[N], nz[N];   // the normals towards the viewer (0 in lanes that do not shade)
  Real rr[N], rg[N], rb[N];   // the local lanes' colours (not guarded)
  std::uint32_t lit = 0;      // lanes that hit a surface (and no emitter): they shade
  std::uint32_t local = 0;    // lanes whose material spawns no ray, shaded here (point lights only)
  std::uint32_t spawn = 0;    // lanes on a mirror or glass the packet follows (packet_spawner), shaded here too
};

// For unit directions (l_x[i], l_y[i], l_z[i]) towards a light from the lanes' surface points
// (step's normals towards the viewer, the views −r's directions): dot(n, to_light), shade_from()'s
// dot(n, h) with h = normalize(to_light + view), and the shadow rays as shadow_ray() makes them
// (spawn_ray's offset along the geometric normal, to the side of the light) — lane by lane the
// same arithmetic, side by side.
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void light_lanes(const SurfaceLanes<N>& surface, const PacketStep<N>& step,
                                                        const PacketRays<N>& r, const Real* l_x, const Real* l_y,
                                                        const Real* l_z, Real* n_dot_l, Real* n_dot_h,
                                                        PacketRays<N>& shadow) {
  shadow.unit = true;  // (unit directions)
  for (int i = 0; i < N; ++i) {
    const Real nx = step.nx[i], ny = step.ny[i], nz = step.nz[i];
    const Real lx = l_x[i], ly = l_y[i], lz = l_z[i];
    n_dot_l[i] = nx * lx + ny * ly + nz * lz;
    const Real hx = lx + -r.dx[i], hy = ly + -r.dy[i], hz = lz + -r.dz[i];
    const Real inv = Real(1) / std::sqrt(hx * hx + hy * hy + hz * hz);
    n_dot_h[i] = nx * (hx * inv) + ny * (hy * inv) + nz * (hz * inv);
    const Real gx = surface.gx[i], gy = surface.gy[i], gz = surface.gz[i];
    const Real side = lx * gx + ly * gy + lz * gz >= 0 ? Real(1) : Real(-1);
    const Real o = side * surface.offset[i];
    shadow.ox[i] = surface.px[i] + gx * o, shadow.oy[i] = surface.py[i] + gy * o, shadow.oz[i] = surface.pz[i] + gz * o;
    shadow.dx[i] = lx, shadow.dy[i] = ly, shadow.dz[i] = lz, shadow.time[i] = r.time[i];
  }
}

// area_light_illumination()'s term of area light `light` (k×k strata), added to step's colours
// in the lanes of `lanes` (shaded here: their terms in `shading`), each lane's random numbers
// drawn from its stream rng[i] in area_light_illumination()'s order: stratum after stratum, the
// lanes' samples side by side (AreaLightLanes: a shading point per lane), their shadow rays
// together (shadow_transmittance), their terms (add_light_lanes) summed per lane, and the sums'
// mean added — the same samples, rays and arithmetic as each lane's alone.
template <int N>
STRAHL_HOST_DEVICE STRAHL_NOINLINE void add_area_light_lanes(const SceneView& s, const Light& light,
                                                             std::uint32_t lanes, const SurfaceLanes<N>& surface,
                                                             PacketStep<N>& step, const PacketRays<N>& r,
                                                             SampleStream* rng, const ShadingLanes<N>& shading,
                                                             RayCounters& counters) {
  const int k = light.samples;
  const AreaLightLanes<N> sampler(light, surface.px, surface.py, surface.pz);
  Real sum_r[N] = {}, sum_g[N] = {}, sum_b[N] = {};
  for (int stratum = 0; stratum < k * k; ++stratum) {
    // Each lane's stratified(stratum % k, stratum / k, k, rng[i].next2()), the lanes side by side
    // (lanes outside `lanes` draw too, and are not advanced).
    Real ux[N], uy[N];
    const Real sx = Real(stratum % k), sy = Real(stratum / k), side = Real(k);
    for (int i = 0; i < N; ++i) {
      const SampleStream& r_i = rng[i];
      const Real a = to_unit(keyed_bits(r_i.key, r_i.sample, r_i.dimension));
      const Real b = to_unit(keyed_bits(r_i.key, r_i.sample, r_i.dimension + 1));
      ux[i] = (sx + a) / side, uy[i] = (sy + b) / side;
    }
    for (std::uint32_t m = lanes; m != 0; m &= m - 1) rng[wide_bvh_detail::lowest_bit(m)].dimension += 2;
    Real lx[N], ly[N], lz[N], distance[N], ir[N], ig[N], ib[N];
    sampler.sample(ux, uy, lx, ly, lz, distance, ir, ig, ib);
    Real n_dot_l[N], n_dot_h[N];
    PacketRays<N> shadow;
    light_lanes<N>(surface, step, r, lx, ly, lz, n_dot_l, n_dot_h, shadow);
    std::uint32_t cast = 0;  // shade_from() casts a shadow ray where the sample lights the front
    for (int i = 0; i < N; ++i) {
      const bool black = ir[i] == 0 && ig[i] == 0 && ib[i] == 0;
      cast |= std::uint32_t(!black && !(n_dot_l[i] <= 0)) << i;
    }
    cast &= lanes;
    counters.shadow += std::uint64_t(wide_bvh_detail::popcount(cast));
    Real tx[N], ty[N], tz[N];
    for (int i = 0; i < N; ++i) tx[i] = ty[i] = tz[i] = 0;
    shadow_transmittance<N>(s, cast, shadow, distance, tx, ty, tz);
    add_light_lanes<N>(ir, ig, ib, lanes, cast, n_dot_l, n_dot_h, tx, ty, tz, shading, sum_r, sum_g, sum_b);
  }
  const Real mean = Real(1) / (k * k);
  for (int i = 0; i < N; ++i) {
    step.rr[i] = step.rr[i] + sum_r[i] * mean;
    step.rg[i] = step.rg[i] + sum_g[i] * mean;
    step.rb[i] = step.rb[i] + sum_b[i] * mean;
  }
}

// Whether the packet front end follows reflected and refracted rays in packets in scene s
// (packet_tree): no area lights (whose samples draw random numbers), a depth and a ray budget.
STRAHL_HOST_DEVICE inline bool packet_trees(const SceneView& s) {
  const int max_depth = s.settings.max_depth < kMaxTraceDepth ? s.settings.max_depth : kMaxTraceDepth;
  return s.area_light_count == 0 && max_depth >= 2 && s.settings.ray_budget > 0;
}

// Whether a hit on material m spawns rays that packet_tree() follows: reflected or refracted rays
// whose directions draw no random numbers (no roughness).
STRAHL_HOST_DEVICE inline bool packet_spawner(const Material& m) {
  return (m.reflectivity > 0 || m.transparency > 0) && !(m.roughness > 0);
}

// trace()'s first step for the active lanes of r (camera rays, or a branch of packet_tree), the
// lanes side by side: the nearest hits, then, light by light, the shadow rays from those hits
// (one packet per light); the lanes whose material spawns no ray are shaded too
// (add_light_lanes), in scenes with area lights only where the lanes' random-number streams
// rng[] are given (add_area_light_lanes draws their samples from them, as trace() would). The
// same hits, shadow rays and arithmetic as trace()'s, lane by lane; no other random numbers are
// drawn.
template <int N>
STRAHL_HOST_DEVICE inline void packet_step(const SceneView& s, std::uint32_t active, const PacketRays<N>& r,
                                           PacketStep<N>& __restrict out, RayCounters& counters,
                                           SampleStream* rng = nullptr) {
  PacketHits<N> hits;
  closest_hit_packet<N>(s, active, r, hits);

  // trace()'s first step up to the shadow rays: emitter, surface point, normal — side by side
  // (surface_lanes) where every lane hit a sphere, a plane or nothing (the emitters, where there
  // are area lights, lane by lane), else lane by lane; the points, geometric normals, offsets,
  // materials and texture coordinates in `surface`, the normals towards the viewer in
  // (nx, ny, nz) (0 in lanes that do not shade). The lanes that go on in trace() get their FirstHit below, once known.
  FirstHitSlot* const slots = out.slots;
  SurfaceLanes<N> surface;
  Real* const px = surface.px; Real* const py = surface.py; Real* const pz = surface.pz;
  Real* const gx = surface.gx; Real* const gy = surface.gy; Real* const gz = surface.gz;
  Real* const offset = surface.offset;
  Real* const nx = out.nx; Real* const ny = out.ny; Real* const nz = out.nz;
  std::uint32_t& lit = out.lit;  // lanes that hit a surface (and no emitter): they shade
  lit = 0;
  const bool side_by_side = hits.in_lanes || hits.lanes.set(active, hits.hit.at);
  int emitter[N];  // side by side: the area light each lane's ray meets first, or −1
  if (side_by_side) {
    surface_lanes<N>(s, active, r, hits.lanes, surface, lit);
    for (int i = 0; i < N; ++i) {
      const Real x = gx[i], y = gy[i], z = gz[i];
      const bool front = r.dx[i] * x + r.dy[i] * y + r.dz[i] * z < 0;  // dot(direction, geometric normal)
      nx[i] = front ? x : -x, ny[i] = front ? y : -y, nz[i] = front ? z : -z;
      emitter[i] = -1;
    }
    for (std::uint32_t m = s.area_light_count > 0 ? active : 0; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      emitter[i] = nearest_emitter(s, r.ray(i), hits.at(i).t);  // (a lane meeting one does not shade)
      if (emitter[i] >= 0) lit &= ~(1u << i);
    }
  } else {
    lit = 0;
    for (std::uint32_t m = active; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      FirstHit& f = slots[i].first;
      const Ray ray = r.ray(i);
      f.hit = hits.at(i);
      f.emitter = s.area_light_count > 0 ? nearest_emitter(s, ray, f.hit.t) : -1;
      if (f.emitter >= 0 || !f.hit.found()) continue;
      surface_at(s, ray, f.hit, f.sp);
      const SurfacePoint& sp = f.sp;
      const bool front = dot(ray.direction, sp.geometric_normal) < 0;
      const Vec3 n = front ? sp.normal : -sp.normal;
      px[i] = sp.p.x, py[i] = sp.p.y, pz[i] = sp.p.z;
      nx[i] = n.x, ny[i] = n.y, nz[i] = n.z;
      gx[i] = sp.geometric_normal.x, gy[i] = sp.geometric_normal.y, gz[i] = sp.geometric_normal.z;
      offset[i] = sp.offset;
      surface.material[i] = sp.material;
      surface.ux[i] = sp.texcoord.x, surface.uy[i] = sp.texcoord.y, surface.uz[i] = sp.texcoord.z;
      lit |= 1u << i;
    }
  }
  for (std::uint32_t m = ~lit & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    px[i] = py[i] = pz[i] = nx[i] = ny[i] = nz[i] = gx[i] = gy[i] = gz[i] = offset[i] = 0;
    surface.material[i] = 0;
  }

  // Lanes whose material spawns no ray get their colour here, the local illumination alone
  // (local_illumination's arithmetic, side by side): the ambient term now, each light's term as
  // its shadow rays come back. So do the lanes on a mirror or glass whose rays the packet
  // follows (their local colour).
  std::uint32_t& local = out.local;
  std::uint32_t& spawn = out.spawn;
  local = spawn = 0;
  const bool trees = packet_trees(s);
  // (Area lights draw random numbers: their lanes are shaded here only with the lanes' streams.)
  const bool shade_here = s.area_light_count == 0 || rng != nullptr;
  Real* const rr = out.rr; Real* const rg = out.rg; Real* const rb = out.rb;
  ShadingLanes<N> shading;
  Real* const cr = shading.cr; Real* const cg = shading.cg; Real* const cb = shading.cb; Real* const kd = shading.kd;
  Real* const sr = shading.sr; Real* const sg = shading.sg; Real* const sb = shading.sb;
  Real* const shiny = shading.shiny; Real* const shininess = shading.shininess;
  // All lit lanes on one material without a texture (as a pixel's samples mostly are): its terms
  // computed once and set in every lit lane side by side. Else lane by lane, the terms of the last
  // material without a texture kept for the next lane of the same material.
  const int first_lit = lit != 0 ? wide_bvh_detail::lowest_bit(lit) : 0;
  std::uint32_t other_material = 0;  // lanes on another material than the first lit lane's
  for (int i = 0; i < N; ++i) other_material |= std::uint32_t(surface.material[i] != surface.material[first_lit]) << i;
  int one_material = int(lit != 0 && shade_here && (other_material & lit) == 0);
  bool one_spawner = false;
  if (one_material != 0) {
    const Material& material = s.materials[surface.material[first_lit]];
    one_spawner = trees && packet_spawner(material);
    if (((material.reflectivity > 0 || material.transparency > 0) && !one_spawner) || textured(material))
      one_material = 0;
  }
  if (one_material != 0) {
    const Vec3 texcoord(surface.ux[first_lit], surface.uy[first_lit], surface.uz[first_lit]);  // (not textured: unused)
    const LocalTerms t =
        local_terms(s.materials[surface.material[first_lit]], texcoord, s.textures, s.settings.ambient_light);
    (one_spawner ? spawn : local) = lit;
    // (In every lane: add_light_lanes adds nothing outside `lit`; the colour is 0 there.)
    for (int i = 0; i < N; ++i) {
      cr[i] = t.c.x, cg[i] = t.c.y, cb[i] = t.c.z, rr[i] = t.ambient.x, rg[i] = t.ambient.y, rb[i] = t.ambient.z;
      kd[i] = t.kd, sr[i] = t.ks.x, sg[i] = t.ks.y, sb[i] = t.ks.z, shiny[i] = t.shiny, shininess[i] = t.shininess;
    }
    for (std::uint32_t m = ~lit & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      rr[i] = rg[i] = rb[i] = 0;
    }
  } else {
    std::uint32_t plain = ~0u;  // its index (~0u: none yet)
    bool plain_spawner = false;  // whether it spawns rays the packet follows (packet_spawner)
    LocalTerms terms{}, fresh{};
    for (std::uint32_t m = shade_here ? lit : 0; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      const std::uint32_t material_index = surface.material[i];
      const LocalTerms* t = &terms;
      bool spawner = plain_spawner;
      if (material_index != plain) {
        const Material& material = s.materials[material_index];
        spawner = false;
        if (material.reflectivity > 0 || material.transparency > 0) {
          if (!(trees && packet_spawner(material))) continue;
          spawner = true;
        }
        fresh = local_terms(material, Vec3(surface.ux[i], surface.uy[i], surface.uz[i]), s.textures,
                            s.settings.ambient_light);
        if (!textured(material)) plain = material_index, terms = fresh, plain_spawner = spawner;
        t = &fresh;
      }
      (spawner ? spawn : local) |= 1u << i;
      cr[i] = t->c.x, cg[i] = t->c.y, cb[i] = t->c.z, rr[i] = t->ambient.x, rg[i] = t->ambient.y, rb[i] = t->ambient.z;
      kd[i] = t->kd, sr[i] = t->ks.x, sg[i] = t->ks.y, sb[i] = t->ks.z, shiny[i] = t->shiny, shininess[i] = t->shininess;
    }
    // The other lanes' values are not used; they are set all the same.
    for (std::uint32_t m = ~(local | spawn) & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      cr[i] = cg[i] = cb[i] = kd[i] = sr[i] = sg[i] = sb[i] = shiny[i] = shininess[i] = rr[i] = rg[i] = rb[i] = 0;
    }
  }
  // The lanes that go on in trace(): what its first step found (the other path wrote it already).
  if (side_by_side)
    for (std::uint32_t m = active & ~local; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      FirstHit& f = slots[i].first;
      f.hit = hits.at(i);
      f.emitter = emitter[i];
      if ((lit >> i) & 1u) surface.get(i, r.time[i], f.sp);
    }

  // The shadow rays to each point light, as local_illumination() casts them (sample_light,
  // shadow_ray: the same arithmetic, side by side), in one packet per light.
  for (std::uint32_t k = 0; k < s.light_count; ++k) {
    const Light& light = s.lights[k];
    if (light.is_area()) {
      if (local != 0) add_area_light_lanes<N>(s, light, local, surface, out, r, rng, shading, counters);
      continue;
    }
    Real lx[N], ly[N], lz[N], distance[N];
    if (light.kind == LightKind::Directional) {
      for (int i = 0; i < N; ++i)
        lx[i] = -light.direction.x, ly[i] = -light.direction.y, lz[i] = -light.direction.z, distance[i] = kInfinity;
    } else {
      for (int i = 0; i < N; ++i) {
        const Real ex = light.position.x - px[i], ey = light.position.y - py[i], ez = light.position.z - pz[i];
        const Real dist = std::sqrt(ex * ex + ey * ey + ez * ez);
        const Real inv = Real(1) / dist;  // d / dist (vec3.h's operator/)
        lx[i] = ex * inv, ly[i] = ey * inv, lz[i] = ez * inv, distance[i] = dist;
      }
    }
    Real n_dot_l[N], n_dot_h[N];
    PacketRays<N> shadow;
    light_lanes<N>(surface, out, r, lx, ly, lz, n_dot_l, n_dot_h, shadow);
    std::uint32_t cast = 0;  // shade_from() casts no ray where dot(n, to_light) <= 0
    for (int i = 0; i < N; ++i) cast |= std::uint32_t(!(n_dot_l[i] <= 0)) << i;
    // The share that reaches each lane's point (local_illumination's: a spot's cone, a fade):
    // none, no shadow ray.
    Real share[N];
    if (light.shaped()) {
      for (int i = 0; i < N; ++i) {
        share[i] = light_share(light, Vec3(lx[i], ly[i], lz[i]), distance[i]);
        if (!(share[i] > 0)) cast &= ~(1u << i);
      }
    }
    cast &= lit;
    Real tx[N], ty[N], tz[N];
    for (std::uint32_t m = lit & ~local; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      slots[i].first.lights[k].sample = LightSample{Vec3(lx[i], ly[i], lz[i]), distance[i]};
    }
    if (cast != 0) {
      for (std::uint32_t m = cast; m != 0; m &= m - 1) ++counters.shadow;
      transmittance_packet<N>(s, cast, shadow, distance, tx, ty, tz);
      for (std::uint32_t m = cast & ~local; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        slots[i].first.lights[k].transmittance = Vec3(tx[i], ty[i], tz[i]);
        slots[i].first.lights[k].n_dot_h = n_dot_h[i];
      }
    } else {
      for (int i = 0; i < N; ++i) tx[i] = ty[i] = tz[i] = 0;
    }
    if ((local | spawn) != 0) {
      Real ir[N], ig[N], ib[N];
      for (int i = 0; i < N; ++i) ir[i] = light.radiance.x, ig[i] = light.radiance.y, ib[i] = light.radiance.z;
      if (light.shaped())
        for (int i = 0; i < N; ++i) ir[i] *= share[i], ig[i] *= share[i], ib[i] *= share[i];
      add_light_lanes<N>(ir, ig, ib, local | spawn, cast, n_dot_l, n_dot_h, tx, ty, tz, shading, rr, rg, rb);
    }
  }
}

// A packet's rays follow their ray trees together through at most this many levels, and a
// branch (the reflected or the refracted rays of the lanes at one level) while at least this
// many lanes take it; deeper, and where fewer take it, each lane goes on alone in trace().
inline constexpr int kPacketTreeDepth = 8;
inline constexpr int kPacketTreeLanes = 4;

// What trace() carries down a lane's ray tree, per lane: the ray's weight (its share of the
// pixel), the rays left in the sample's budget, the media it travels in, its random numbers
// (drawn only in trace(): where a lane goes on alone).
template <int N>
struct TreeLanes {
  Real weight[N];
  std::uint32_t budget[N];
  UninitializedLanes<MediumStack, N> media;
  SampleStream* rng;  // the lanes' streams (the camera samples')

  // Where lane i's ray, at depth `depth`, goes on alone in trace(): its weight, budget and media,
  // and the budget it leaves written back here.
  STRAHL_HOST_DEVICE TraceStart start(const SceneView& s, int i, int depth) {
    return TraceStart{depth, weight[i], s.settings.ray_budget - budget[i], &media.at[i], &budget[i]};
  }
};

template <int N>
STRAHL_HOST_DEVICE void packet_tree(const SceneView& s, const PacketRays<N>& r, const PacketStep<N>& step,
                                    std::uint32_t lanes, int depth, TreeLanes<N>& at, Vec3* color,
                                    RayCounters& counters);

// The radiance along the rays r of the lanes `lanes` at depth `depth` (each lane's weight,
// budget and media in `at`) into color[] (not guarded): their first step together and on down
// their trees (packet_tree) when enough lanes take the branch, else trace() lane by lane.
template <int N>
STRAHL_HOST_DEVICE STRAHL_NOINLINE void packet_branch(const SceneView& s, PacketRays<N>& r, std::uint32_t lanes,
                                                      int depth, TreeLanes<N>& at, Vec3* color, RayCounters& counters) {
  if (wide_bvh_detail::popcount(lanes) < kPacketTreeLanes || depth > kPacketTreeDepth) {
    for (std::uint32_t m = lanes; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      color[i] = trace(s, r.ray(i), counters, at.rng[i], nullptr, at.start(s, i, depth));
    }
    return;
  }
  const int first = wide_bvh_detail::lowest_bit(lanes);
  for (std::uint32_t m = ~lanes & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {  // lanes nobody reads
    const int i = wide_bvh_detail::lowest_bit(m);
    r.ox[i] = r.ox[first], r.oy[i] = r.oy[first], r.oz[i] = r.oz[first];
    r.dx[i] = r.dx[first], r.dy[i] = r.dy[first], r.dz[i] = r.dz[first], r.time[i] = r.time[first];
  }
  PacketStep<N> step;
  packet_step<N>(s, lanes, r, step, counters);
  packet_tree<N>(s, r, step, lanes, depth, at, color, counters);
}

// The lanes `lanes` of the packet r at depth `depth`, whose first step is `step`, finished as
// trace() finishes them (their weights, budgets and media in `at`, updated), into color[] (not
// guarded): a local lane's colour is its local illumination, a lane that met nothing gets the
// background; a lane on a mirror or glass (PacketStep::spawn) adds k_r times its reflected ray's
// radiance and then T·tint times its refracted ray's — the reflected rays of all such lanes one
// branch (packet_branch), then their refracted rays another, as trace() takes them depth first
// — with trace()'s tests and arithmetic (total internal reflection, Fresnel, min_weight, the
// budget); any other lane goes on alone in trace() from its first step.
template <int N>
STRAHL_HOST_DEVICE void packet_tree(const SceneView& s, const PacketRays<N>& r, const PacketStep<N>& step,
                                    std::uint32_t lanes, int depth, TreeLanes<N>& at, Vec3* color,
                                    RayCounters& counters) {
  const int max_depth = s.settings.max_depth < kMaxTraceDepth ? s.settings.max_depth : kMaxTraceDepth;
  const Real min_weight = s.settings.min_weight;
  Real kr[N], kt[N];
  Vec3 refracted_dir[N];
  bool front[N];
  std::uint32_t reflecting = 0, transmitting = 0;  // lanes with a reflected ray; with k_t > 0
  PacketRays<N> child;
  child.unit = false;  // (reflect() and refract() keep unit length only up to rounding)
  TreeLanes<N> below;  // the children's weights, budgets and media
  below.rng = at.rng;
  for (std::uint32_t m = lanes; m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    const FirstHit& f = step.slots[i].first;
    if ((step.local >> i) & 1u) {
      color[i] = Vec3(step.rr[i], step.rg[i], step.rb[i]);
      continue;
    }
    if (!((step.lit >> i) & 1u)) {
      color[i] = s.settings.background;  // (no area lights: nothing else to meet)
      continue;
    }
    if (!((step.spawn >> i) & 1u)) {
      color[i] = trace(s, r.ray(i), counters, at.rng[i], &f, at.start(s, i, depth));
      continue;
    }
    // trace()'s step at a hit that spawns rays, lane by lane.
    color[i] = Vec3(step.rr[i], step.rg[i], step.rb[i]);
    if (!(depth < max_depth)) continue;
    const SurfacePoint& sp = f.sp;
    const Material& material = s.materials[sp.material];
    const Vec3 direction(r.dx[i], r.dy[i], r.dz[i]);
    front[i] = dot(direction, sp.geometric_normal) < 0;
    const Vec3 n = front[i] ? sp.normal : -sp.normal;
    split_at(material, direction, n, front[i], at.media.at[i], kr[i], kt[i], refracted_dir[i]);
    if (kt[i] > 0) transmitting |= 1u << i;
    if (kr[i] > 0 && kr[i] * at.weight[i] >= min_weight && spend(at.budget[i], counters)) {
      ++counters.reflection;
      child.set(i, spawn_ray(sp, reflect(direction, n), r.time[i]));
      below.weight[i] = at.weight[i] * kr[i];
      below.budget[i] = at.budget[i];
      below.media.at[i] = at.media.at[i];
      reflecting |= 1u << i;
    }
  }
  UninitializedLanes<Vec3, N> radiance_slots;  // (set in the lanes that take a branch)
  Vec3* const radiance = radiance_slots.at;
  if (reflecting != 0) {
    packet_branch<N>(s, child, reflecting, depth + 1, below, radiance, counters);
    for (std::uint32_t m = reflecting; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      at.budget[i] = below.budget[i];  // (what the reflected subtree left)
      color[i] += radiance[i] * kr[i];
    }
  }
  // The refracted rays (trace()'s start_refracted), after the reflected subtrees.
  std::uint32_t refracting = 0;
  for (std::uint32_t m = transmitting; m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    if (!(kt[i] * at.weight[i] >= min_weight && spend(at.budget[i], counters))) continue;
    ++counters.refraction;
    const SurfacePoint& sp = step.slots[i].first.sp;
    child.set(i, spawn_ray(sp, refracted_dir[i], r.time[i]));
    below.weight[i] = at.weight[i] * kt[i];
    below.budget[i] = at.budget[i];
    below.media.at[i] = at.media.at[i];
    if (front[i])
      below.media.at[i].enter(s.materials[sp.material].ior);
    else
      below.media.at[i].leave();
    refracting |= 1u << i;
  }
  if (refracting != 0) {
    packet_branch<N>(s, child, refracting, depth + 1, below, radiance, counters);
    for (std::uint32_t m = refracting; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      at.budget[i] = below.budget[i];
      color[i] += radiance[i] * transmission_tint(s.materials[step.slots[i].first.sp.material]) * kt[i];
    }
  }
}

// The camera samples cs[0 … count − 1] (count ≤ N), their film positions and times also in
// `film` (its first N lanes, padded: FilmLanes::pad), lane i sample number index[i] of the pixel
// whose random numbers are keyed by key[i] (PixelSequence::stream): their radiance (guarded as
// sample_radiance's) into L[]. The lanes may be samples of one pixel or of several.
template <int N, int M>
STRAHL_HOST_DEVICE inline void packet_radiance_of(const SceneView& s, const CameraSample* cs, const FilmLanes<M>& film,
                                                  const std::uint64_t* key, const std::uint32_t* index, int count,
                                                  Vec3* L, RayCounters& counters) {
  static_assert(N <= M);
  const std::uint32_t active = count >= 32 ? ~0u : (1u << count) - 1;
  // The camera rays: directions side by side (Camera::directions, generate_ray's arithmetic).
  Real time[N], dx[N], dy[N], dz[N];
  s.camera.directions<N>(film.x, film.y, dx, dy, dz);
  const Camera& camera = s.camera;
  for (int i = 0; i < N; ++i) time[i] = camera.shutter_open + film.time[i] * (camera.shutter_close - camera.shutter_open);
  PacketRays<N> r;  // the camera rays, side by side
  r.unit = true;     // (Camera::directions and through_lens normalise them)
  for (int i = 0; i < N; ++i) {
    r.ox[i] = camera.eye.x, r.oy[i] = camera.eye.y, r.oz[i] = camera.eye.z;
    r.dx[i] = dx[i], r.dy[i] = dy[i], r.dz[i] = dz[i], r.time[i] = time[i];
  }
  if (camera.lens_radius > 0) {
    Real lens_x[N], lens_y[N];
    for (int i = 0; i < N; ++i) lens_x[i] = cs[i < count ? i : 0].lens.x, lens_y[i] = cs[i < count ? i : 0].lens.y;
    for (int i = 0; i < N; ++i) {  // Camera::through_lens, lane by lane
      Ray ray{camera.eye, Vec3(dx[i], dy[i], dz[i])};
      camera.lens_ray(ray, Vec2{lens_x[i], lens_y[i]});
      r.ox[i] = ray.origin.x, r.oy[i] = ray.origin.y, r.oz[i] = ray.origin.z;
      r.dx[i] = ray.direction.x, r.dy[i] = ray.direction.y, r.dz[i] = ray.direction.z;
    }
  }
  counters.camera += std::uint64_t(count);

  // The lanes' random numbers, for the area lights' samples of the lanes packet_step() shades.
  UninitializedLanes<SampleStream, N> streams;
  if (s.area_light_count > 0)
    for (int i = 0; i < N; ++i) streams.at[i] = SampleStream{key[i < count ? i : 0], index[i < count ? i : 0]};
  PacketStep<N> step;
  packet_step<N>(s, active, r, step, counters, s.area_light_count > 0 ? streams.at : nullptr);
  const std::uint32_t lit = step.lit, local = step.local;

  // The local lanes' colours, guarded as guard_sample() does, side by side.
  const std::uint32_t valid = valid_lanes<N>(step.rr, step.rg, step.rb);
  // (Every lane below count, without a branch: the lanes that go on in trace() overwrite theirs.)
  for (int i = 0; i < count; ++i) {
    const bool ok = (valid >> i) & 1u;
    L[i] = Vec3(ok ? step.rr[i] : Real(0), ok ? step.rg[i] : Real(0), ok ? step.rb[i] : Real(0));
  }
  for (std::uint32_t m = local & ~valid; m != 0; m &= m - 1) ++counters.invalid_samples;
  std::uint32_t rest = active & ~local;  // the lanes still to finish
  if (wide_bvh_detail::popcount(step.spawn) >= kPacketTreeLanes) {
    // The lanes on mirrors and glass on down their ray trees together, from depth 1.
    SampleStream rng[N];
    TreeLanes<N> at;
    at.rng = rng;
    Vec3 radiance[N];
    for (std::uint32_t m = step.spawn; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      rng[i] = SampleStream{key[i], index[i]};
      at.weight[i] = 1;
      at.budget[i] = s.settings.ray_budget;
      at.media.at[i] = MediumStack(s.settings.medium_ior);
    }
    packet_tree<N>(s, r, step, step.spawn, 1, at, radiance, counters);
    for (std::uint32_t m = step.spawn; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      L[i] = guard_sample(radiance[i], counters);
    }
    rest &= ~step.spawn;
  }
  for (std::uint32_t lanes = rest; lanes != 0; lanes &= lanes - 1) {
    const int i = wide_bvh_detail::lowest_bit(lanes);
    const FirstHit& f = step.slots[i].first;
    if (!((lit >> i) & 1u) && f.emitter < 0) {
      L[i] = guard_sample(s.settings.background, counters);  // trace(): the ray met nothing
      continue;
    }
    SampleStream rng{key[i], index[i]};
    if ((lit >> i) & 1u) {
      const Material& m = s.materials[f.sp.material];
      if (!(m.reflectivity > 0) && !(m.transparency > 0)) {
        // trace() would spawn no ray here: its colour is the local illumination alone.
        const Vec3 n(step.nx[i], step.ny[i], step.nz[i]);
        const Vec3 view(-r.dx[i], -r.dy[i], -r.dz[i]);
        L[i] = guard_sample(local_illumination(s, f.sp, n, view, counters, rng, f.lights), counters);
        continue;
      }
    }
    L[i] = guard_sample(trace(s, r.ray(i), counters, rng, &f), counters);
  }
}

// Samples first … first + count − 1 (count ≤ N) of pixel sequence p: their camera samples into
// cs[], their radiance (guarded as sample_radiance's) into L[].
template <int N>
STRAHL_HOST_DEVICE inline void packet_radiance(const SceneView& s, const PixelSequence& p, std::uint32_t first,
                                               int count, CameraSample* cs, Vec3* L, RayCounters& counters) {
  FilmLanes<N> film;
  p.samples<N>(first, count, cs, film);
  std::uint64_t key[N];
  std::uint32_t index[N];
  for (int i = 0; i < N; ++i) key[i] = p.stream, index[i] = first + std::uint32_t(i);
  packet_radiance_of<N>(s, cs, film, key, index, count, L, counters);
}

}  // namespace strahl
