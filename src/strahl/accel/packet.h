#pragma once
// Packet queries on any acceleration structure: N = 8 or 16 rays (coherent ones: a tile of
// pixels' primary rays, or the shadow rays from their hits to one light) asked together, lane i
// taking part when bit i of `active` is set. The BVH runs its packet traversal
// (wide_bvh_packet.h); Embree (host) its rtcIntersect8/16 / rtcOccluded8/16; every other structure
// (and the BVH of a scene that is one leaf) answers lane by lane with the single-ray queries.
// Answers are the single-ray queries' (nearest_hit, occluded of accel.h), lane for lane; only
// the answers of active lanes are written.

#include <cstdint>

#include "strahl/accel/accel.h"
#include "strahl/accel/wide_bvh_packet.h"

namespace strahl {

// N values without their default member initialisers (a memset per packet, ~1.5 % of the lecture
// scene's instructions), for arrays whose every lane is assigned before it is read.
template <class T, int N>
union UninitializedLanes {
  T at[N];
  STRAHL_HOST_DEVICE UninitializedLanes() {}
};

// The rays of a packet as plain arrays, one per coordinate, for loops over the lanes that the
// compiler turns into SIMD (and the GPU runs as they are).
// The packet front end (render/packet_radiance.h) fills them directly from its own arrays.
template <int N>
struct PacketRays {
  Real ox[N], oy[N], oz[N], dx[N], dy[N], dz[N], time[N];
  // Every lane's direction is a unit vector up to rounding (the packet front end's camera and
  // shadow rays): packet_cone() then needs no lengths.
  bool unit = false;

  PacketRays() = default;  // (the lanes uninitialised: for filling lane by lane)
  STRAHL_HOST_DEVICE explicit PacketRays(const Ray* rays) {
    for (int i = 0; i < N; ++i) {
      ox[i] = rays[i].origin.x, oy[i] = rays[i].origin.y, oz[i] = rays[i].origin.z;
      dx[i] = rays[i].direction.x, dy[i] = rays[i].direction.y, dz[i] = rays[i].direction.z;
      time[i] = rays[i].time;
    }
  }
  STRAHL_HOST_DEVICE Ray ray(int i) const { return Ray{Vec3(ox[i], oy[i], oz[i]), Vec3(dx[i], dy[i], dz[i]), time[i]}; }
  STRAHL_HOST_DEVICE void set(int i, const Ray& ray) {
    ox[i] = ray.origin.x, oy[i] = ray.origin.y, oz[i] = ray.origin.z;
    dx[i] = ray.direction.x, dy[i] = ray.direction.y, dz[i] = ray.direction.z, time[i] = ray.time;
  }
};

// A bound on the active lanes' rays, for skipping a sphere that none of them can meet before
// computing their roots: every point o_i + t·d_i (t ≥ 0) of lane i lies within `spread` of the
// cone of apex `apex` (the first active lane's origin), unit axis `axis` and half-angle
// θ (cos_theta, sin_theta) — because o_i + t·d_i lies within |o_i − apex| of apex + t·d_i, which is
// in the cone. Camera rays through one pixel share their origin (spread 0) and form a cone of a
// pixel's width; a pixel's shadow rays to one light start close together with nearly parallel
// directions. `valid` is false where the directions span 90° or more (or are not finite): no bound.
struct PacketCone {
  Vec3 apex, axis;
  Real cos_theta = -1, sin_theta = 0, spread = 0;
  bool valid = false;
};

// The cone of the active lanes' rays of r, for hits at t > t_min[i] ≥ 0 (no cone when some
// t_min is negative: a root behind the origin would not be in it). Its axis is lane `first`'s
// direction; the lanes' directions need not be unit (a lane test's hit means the same line
// whatever |d|). Written as loops over all lanes and minima and maxima over four columns of
// lanes, so that the lanes run side by side (a running minimum over the lanes would be one long
// chain).
template <int N>
STRAHL_HOST_DEVICE inline PacketCone packet_cone(const PacketRays<N>& r, std::uint32_t active, const Real* t_min) {
  PacketCone k;
  if (active == 0) return k;
  const int first = wide_bvh_detail::lowest_bit(active);
  const Real ax = r.ox[first], ay = r.oy[first], az = r.oz[first];
  const Real fx = r.dx[first], fy = r.dy[first], fz = r.dz[first];
  // The axis: lane `first`'s direction, normalised — in a unit packet as it is (unit up to
  // rounding, as every lane's is taken to be below; the margins cover some 1e-16 of it), which
  // spares a square root and a division on the path to every sphere test.
  Real ux = fx, uy = fy, uz = fz;
  if (!r.unit) {
    const Real inv = Real(1) / std::sqrt(fx * fx + fy * fy + fz * fz);
    ux = fx * inv, uy = fy * inv, uz = fz * inv;
  }
  // Per lane: the cosine of its angle to the axis and its origin's squared distance from the
  // apex; an inactive lane (garbage) gets 1 and 0, a NaN or infinite one marks the cone unusable.
  Real cos_lane[N], spread2[N];
  std::uint32_t unusable = 0;  // lanes whose values are NaN or infinite
  if (r.unit)
    for (int i = 0; i < N; ++i) cos_lane[i] = ux * r.dx[i] + uy * r.dy[i] + uz * r.dz[i];
  else
    for (int i = 0; i < N; ++i)
      cos_lane[i] = (ux * r.dx[i] + uy * r.dy[i] + uz * r.dz[i]) /
                    std::sqrt(r.dx[i] * r.dx[i] + r.dy[i] * r.dy[i] + r.dz[i] * r.dz[i]);
  for (int i = 0; i < N; ++i) {
    const Real ex = r.ox[i] - ax, ey = r.oy[i] - ay, ez = r.oz[i] - az;
    const Real e2 = ex * ex + ey * ey + ez * ez;
    spread2[i] = e2;
    unusable |= std::uint32_t(!(cos_lane[i] >= -2) | !(e2 < kInfinity) | !(t_min[i] >= 0)) << i;
  }
  if ((unusable & active) != 0) return k;
  // The least cosine and the largest spread over the active lanes: four columns of lanes side by
  // side (an inactive lane counts as 1 and 0), then the four columns.
  static_assert(N % 4 == 0);
  for (std::uint32_t m = ~active & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    cos_lane[i] = 1, spread2[i] = 0;
  }
  Real least[4], most[4];
  for (int j = 0; j < 4; ++j) least[j] = cos_lane[j], most[j] = spread2[j];
  for (int c = 4; c < N; c += 4)
    for (int j = 0; j < 4; ++j) {
      least[j] = cos_lane[c + j] < least[j] ? cos_lane[c + j] : least[j];
      most[j] = spread2[c + j] > most[j] ? spread2[c + j] : most[j];
    }
  const Real least01 = least[1] < least[0] ? least[1] : least[0], least23 = least[3] < least[2] ? least[3] : least[2];
  const Real most01 = most[1] > most[0] ? most[1] : most[0], most23 = most[3] > most[2] ? most[3] : most[2];
  // Widened by far more than the rounding of the products and quotients above (a few 1e-16).
  k.cos_theta = (least23 < least01 ? least23 : least01) - Real(1e-12);
  if (!(k.cos_theta > Real(1e-3))) return k;
  k.sin_theta = std::sqrt(1 - k.cos_theta * k.cos_theta);
  k.apex = Vec3(ax, ay, az);
  k.axis = Vec3(ux, uy, uz);
  k.spread = std::sqrt(most23 > most01 ? most23 : most01);
  k.valid = true;
  return k;
}

// False only when no ray of the cone's packet can meet the sphere — then none of the sphere lane
// tests below finds a root in any lane, computed as they compute it: the sphere is grown by the
// rays' spread and by 1e-8 of the distances involved (the lane tests' rounding is some 1e-16 of
// them), and the cone of half-angle θ misses it when the angle α between the axis and the centre
// exceeds θ + β, β the angle the grown sphere of radius R subtends from the apex:
// cos α < cos(θ + β), with cos α = a·v/|v|, sin β = R/|v| and cos β = √(|v|² − R²)/|v| — here
// multiplied by |v|, and |v| in the margins bounded by its 1-norm: one square root, no division.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool cone_may_meet(const PacketCone& k, const kernel::Sphere& sphere) {
  if (!k.valid) return true;
  const Vec3 v = sphere.center - k.apex;
  const Real reach = std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);  // ≥ |v|
  const Real grown = sphere.radius + k.spread;
  const Real radius = grown + Real(1e-8) * (reach + grown);
  const Real v2 = dot(v, v), r2 = radius * radius;
  if (!(v2 > r2)) return true;  // the apex inside the grown sphere (or NaN)
  return !(dot(k.axis, v) < k.cos_theta * std::sqrt(v2 - r2) - k.sin_theta * radius - Real(1e-12) * reach);
}

// The two roots of the sphere's quadratic along every lane's ray, t0 ≤ t1, as kernel::intersect
// and kernel::crossings (geometry/sphere.h) compute them: the same operations in the same order,
// written without branches so that the lanes run side by side. A lane whose ray misses the sphere
// gets NaN for both (no comparison with a NaN holds: it is in no interval). False, with t0 and t1
// unset, when no lane's ray meets the sphere (a coherent packet mostly misses a sphere or mostly
// hits it): the roots' square roots and divisions are then skipped. Inactive lanes compute garbage
// that nobody reads.
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool sphere_roots_lanes(const kernel::Sphere& sphere, const PacketRays<N>& r,
                                                               Real* t0, Real* t1) {
  const Real cx = sphere.center.x, cy = sphere.center.y, cz = sphere.center.z;
  const Real r2 = sphere.radius * sphere.radius;
  Real b[N], c[N], discriminant[N];
  unsigned meets = 0;
  for (int i = 0; i < N; ++i) {
    const Real fx = r.ox[i] - cx, fy = r.oy[i] - cy, fz = r.oz[i] - cz;
    b[i] = -(fx * r.dx[i] + fy * r.dy[i] + fz * r.dz[i]);
    const Real lx = fx + r.dx[i] * b[i], ly = fy + r.dy[i] * b[i], lz = fz + r.dz[i] * b[i];
    discriminant[i] = r2 - (lx * lx + ly * ly + lz * lz);
    c[i] = (fx * fx + fy * fy + fz * fz) - r2;
    meets |= unsigned(discriminant[i] >= 0);  // (a NaN discriminant misses, as in kernel::intersect)
  }
  if (meets == 0) return false;
  for (int i = 0; i < N; ++i) {
    const Real d = discriminant[i];
    const Real q = b[i] + std::copysign(std::sqrt(d < 0 ? Real(0) : d), b[i]);
    const Real c_over_q = c[i] / q;  // in every lane (a branch would stop the lanes running together)
    const Real a = q != 0 ? c_over_q : 0;
    const bool swap = a > q;
    t0[i] = d < 0 ? kNaN : swap ? q : a;
    t1[i] = d < 0 ? kNaN : swap ? a : q;
  }
  return true;
}

// kernel::intersect(sphere, ray, t_min, t_max) for every lane, into t[]: the single ray's answers
// bit for bit. False, with t[] unset, when no lane's ray meets the sphere (all kInfinity).
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool intersect_sphere_lanes(const kernel::Sphere& sphere, const PacketRays<N>& r,
                                                                   const Real* t_min, const Real* t_max, Real* t) {
  Real t0[N], t1[N];
  if (!sphere_roots_lanes<N>(sphere, r, t0, t1)) return false;
  for (int i = 0; i < N; ++i) {
    const bool t0_in = (t0[i] > t_min[i]) & (t0[i] < t_max[i]), t1_in = (t1[i] > t_min[i]) & (t1[i] < t_max[i]);
    t[i] = t0_in ? t0[i] : t1_in ? t1[i] : kInfinity;
  }
  return true;
}

// kernel::crossings(sphere, ray, t_min, t_max) for every lane, as two masks: the lanes whose
// first root lies in (t_min, t_max) in `first`, those whose second root does in `second` (a lane
// crosses the sphere as many times as it is in them). False, with the masks unset, when no lane's
// ray meets the sphere (no crossings).
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool sphere_crossings_lanes(const kernel::Sphere& sphere, const PacketRays<N>& r,
                                                                   const Real* t_min, const Real* t_max,
                                                                   std::uint32_t& first, std::uint32_t& second) {
  Real t0[N], t1[N];
  if (!sphere_roots_lanes<N>(sphere, r, t0, t1)) return false;
  std::uint32_t in0 = 0, in1 = 0;
  for (int i = 0; i < N; ++i) {
    in0 |= std::uint32_t((t0[i] > t_min[i]) & (t0[i] < t_max[i])) << i;
    in1 |= std::uint32_t((t1[i] > t_min[i]) & (t1[i] < t_max[i])) << i;
  }
  first = in0, second = in1;
  return true;
}

// The one-leaf sphere loops of nearest_hit and occluded (accel.h) for a packet: sphere by sphere,
// all lanes at once, each lane's far end lowered as it finds nearer hits, exactly as its own loop
// would; spheres no lane's ray can meet (packet_cone) skipped. Here the lanes' nearest sphere hits
// in (t_min[i], t_far[i]): t_far[i] lowered to it and prim[i] the sphere's index (as a Real, so
// that the lanes' update is one width), −1 where there is none.
template <int N>
STRAHL_HOST_DEVICE inline void sphere_leaf_nearest_lanes(const PrimitiveSet& p, std::uint32_t active, const PacketRays<N>& r,
                                                         const Real* t_min, Real* t_far, Real* prim) {
  Real t[N];
  for (int i = 0; i < N; ++i) prim[i] = -1;
  const PacketCone cone = p.sphere_count > 1 ? packet_cone<N>(r, active, t_min) : PacketCone{};
  for (std::uint32_t k = 0; k < p.sphere_count; ++k) {
    if (!cone_may_meet(cone, p.spheres[k])) continue;
    if (!intersect_sphere_lanes<N>(p.spheres[k], r, t_min, t_far, t)) continue;
    for (int i = 0; i < N; ++i) {
      const bool nearer = t[i] < t_far[i];
      t_far[i] = nearer ? t[i] : t_far[i];
      prim[i] = nearer ? Real(k) : prim[i];
    }
  }
}

template <int N>
STRAHL_HOST_DEVICE inline void sphere_leaf_nearest_packet(const PrimitiveSet& p, std::uint32_t active, const PacketRays<N>& r,
                                                          const Real* t_min, const Real* t_max, NearestHit* out) {
  Real t_far[N], prim[N];
  for (int i = 0; i < N; ++i) t_far[i] = t_max[i];
  sphere_leaf_nearest_lanes<N>(p, active, r, t_min, t_far, prim);
  for (std::uint32_t m = active; m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    out[i] = NearestHit{};
    if (prim[i] >= 0) out[i] = NearestHit{std::uint32_t(prim[i]), kernel::TriangleHit{t_far[i], 0, 0}};
  }
}

template <int N>
STRAHL_HOST_DEVICE inline std::uint32_t sphere_leaf_occluded_packet(const PrimitiveSet& p, std::uint32_t active,
                                                                    const PacketRays<N>& r, const Real* t_min,
                                                                    const Real* t_max) {
  Real t0[N], t1[N];
  std::uint32_t m = 0;
  const PacketCone cone = p.sphere_count > 1 ? packet_cone<N>(r, active, t_min) : PacketCone{};
  for (std::uint32_t k = 0; k < p.sphere_count && (active & ~m) != 0; ++k) {
    if (!cone_may_meet(cone, p.spheres[k])) continue;
    if (!sphere_roots_lanes<N>(p.spheres[k], r, t0, t1)) continue;
    for (int i = 0; i < N; ++i) {  // (intersect_sphere_lanes' test: a root inside the segment)
      const bool in = ((t0[i] > t_min[i]) & (t0[i] < t_max[i])) | ((t1[i] > t_min[i]) & (t1[i] < t_max[i]));
      m |= std::uint32_t(in) << i;
    }
  }
  return m & active;
}

// occluded() for each active lane where the structure is one leaf of spheres and other
// primitives (a few spheres beside a triangle or a solid): the spheres side by side
// (sphere_leaf_occluded_packet), then, for the lanes they leave open, the other primitives
// lane by lane with the naive loop's tests — any hit is an answer, so the order does not matter.
template <int N>
STRAHL_HOST_DEVICE inline std::uint32_t one_leaf_occluded_packet(const PrimitiveSet& p, std::uint32_t active,
                                                                 const Ray* rays, const Real* t_min,
                                                                 const Real* t_max) {
  std::uint32_t m =
      p.sphere_count > 0 ? sphere_leaf_occluded_packet<N>(p, active, PacketRays<N>(rays), t_min, t_max) : 0;
  for (std::uint32_t open = active & ~m; open != 0; open &= open - 1) {
    const int i = wide_bvh_detail::lowest_bit(open);
    const Ray& ray = rays[i];
    const kernel::RayShear shear = ray_shear_for(p, ray.direction);
    for (std::uint32_t prim = p.sphere_count; prim < p.size(); ++prim) {
      const bool hit = p.is_triangle(prim) ? intersect_primitive(p, prim, ray, shear, t_min[i], t_max[i]).t < kInfinity
                                           : hits_other(p, prim, ray, t_min[i], t_max[i]);
      if (hit) {
        m |= 1u << i;
        break;
      }
    }
  }
  return m & active;
}

template <int N>
STRAHL_HOST_DEVICE inline void nearest_hit_packet(const AccelView& a, std::uint32_t active, const Ray* rays,
                                                  const Real* t_min, const Real* t_max, NearestHit* out) {
  static_assert(N == 8 || N == 16);
  active &= (1u << N) - 1;
#if defined(STRAHL_HAVE_EMBREE) && !defined(__CUDACC__)
  if (a.kind == AccelKind::Embree) return embree_nearest_hit_packet(a, N, active, rays, t_min, t_max, out);
#endif
  if (a.kind == AccelKind::Bvh && !a.one_leaf) {
    Real t_far[N];
    std::uint32_t prim[N];
    kernel::TriangleHit hit[N];
    for (int i = 0; i < N; ++i) {
      t_far[i] = ((active >> i) & 1u) ? t_max[i] : Real(0);
      prim[i] = 0;
      hit[i] = kernel::TriangleHit{};
    }
    wide_bvh_nearest_packet<N>(a.bvh, a.prims, active, rays, t_min, t_far, prim, hit);
    for (int i = 0; i < N; ++i)
      if ((active >> i) & 1u) out[i] = NearestHit{prim[i], hit[i]};
    return;
  }
  if (is_sphere_leaf(a)) return sphere_leaf_nearest_packet<N>(a.prims, active, PacketRays<N>(rays), t_min, t_max, out);
  for (int i = 0; i < N; ++i)
    if ((active >> i) & 1u) out[i] = nearest_hit(a, rays[i], t_min[i], t_max[i]);
}

// The mask of the active lanes whose ray hits something in (t_min[i], t_max[i]).
template <int N>
STRAHL_HOST_DEVICE inline std::uint32_t occluded_packet(const AccelView& a, std::uint32_t active, const Ray* rays,
                                                        const Real* t_min, const Real* t_max) {
  static_assert(N == 8 || N == 16);
  active &= (1u << N) - 1;
#if defined(STRAHL_HAVE_EMBREE) && !defined(__CUDACC__)
  if (a.kind == AccelKind::Embree) {
    bool out[N] = {};
    embree_occluded_packet(a, N, active, rays, t_min, t_max, out);
    std::uint32_t m = 0;
    for (int i = 0; i < N; ++i)
      if (out[i]) m |= 1u << i;
    return m & active;
  }
#endif
  if (a.kind == AccelKind::Bvh && !a.one_leaf) return wide_bvh_occluded_packet<N>(a.bvh, a.prims, active, rays, t_min, t_max);
  if (is_sphere_leaf(a)) return sphere_leaf_occluded_packet<N>(a.prims, active, PacketRays<N>(rays), t_min, t_max);
  if (a.one_leaf) return one_leaf_occluded_packet<N>(a.prims, active, rays, t_min, t_max);
  std::uint32_t m = 0;
  for (int i = 0; i < N; ++i)
    if (((active >> i) & 1u) && occluded(a, rays[i], t_min[i], t_max[i])) m |= 1u << i;
  return m;
}

}  // namespace strahl
