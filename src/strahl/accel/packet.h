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

// The rays of a packet as plain arrays, one per coordinate, for loops over the lanes that the
// compiler turns into SIMD (and the GPU runs as they are).
template <int N>
struct PacketRays {
  Real ox[N], oy[N], oz[N], dx[N], dy[N], dz[N];

  STRAHL_HOST_DEVICE explicit PacketRays(const Ray* rays) {
    for (int i = 0; i < N; ++i) {
      ox[i] = rays[i].origin.x, oy[i] = rays[i].origin.y, oz[i] = rays[i].origin.z;
      dx[i] = rays[i].direction.x, dy[i] = rays[i].direction.y, dz[i] = rays[i].direction.z;
    }
  }
};

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

// kernel::crossings(sphere, ray, t_min, t_max) for every lane, into n[]: 0, 1 or 2. False, with
// n[] unset, when no lane's ray meets the sphere (all 0).
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool sphere_crossings_lanes(const kernel::Sphere& sphere, const PacketRays<N>& r,
                                                                   const Real* t_min, const Real* t_max, int* n) {
  Real t0[N], t1[N];
  if (!sphere_roots_lanes<N>(sphere, r, t0, t1)) return false;
  for (int i = 0; i < N; ++i)
    n[i] = int((t0[i] > t_min[i]) & (t0[i] < t_max[i])) + int((t1[i] > t_min[i]) & (t1[i] < t_max[i]));
  return true;
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
  if (is_sphere_leaf(a)) {
    // One leaf of spheres (nearest_hit's loop): sphere by sphere, all lanes at once, each lane's
    // far end lowered as it finds nearer hits, exactly as its own loop would.
    const PacketRays<N> r(rays);
    // (the sphere's index kept as a Real beside t, so that the lanes' update is one width)
    Real t_far[N], t[N], prim[N];
    for (int i = 0; i < N; ++i) t_far[i] = t_max[i], prim[i] = 0;
    for (std::uint32_t k = 0; k < a.prims.sphere_count; ++k) {
      if (!intersect_sphere_lanes<N>(a.prims.spheres[k], r, t_min, t_far, t)) continue;
      for (int i = 0; i < N; ++i) {
        const bool nearer = t[i] < t_far[i];
        t_far[i] = nearer ? t[i] : t_far[i];
        prim[i] = nearer ? Real(k) : prim[i];
      }
    }
    for (std::uint32_t m = active; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      out[i] = NearestHit{};
      if (t_far[i] < t_max[i]) out[i] = NearestHit{std::uint32_t(prim[i]), kernel::TriangleHit{t_far[i], 0, 0}};
    }
    return;
  }
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
  if (is_sphere_leaf(a)) {  // as nearest_hit_packet: all lanes, sphere by sphere
    const PacketRays<N> r(rays);
    Real t0[N], t1[N];
    std::uint32_t m = 0;
    for (std::uint32_t k = 0; k < a.prims.sphere_count && (active & ~m) != 0; ++k) {
      if (!sphere_roots_lanes<N>(a.prims.spheres[k], r, t0, t1)) continue;
      for (int i = 0; i < N; ++i) {  // (intersect_sphere_lanes' test: a root inside the segment)
        const bool in = ((t0[i] > t_min[i]) & (t0[i] < t_max[i])) | ((t1[i] > t_min[i]) & (t1[i] < t_max[i]));
        m |= std::uint32_t(in) << i;
      }
    }
    return m & active;
  }
  std::uint32_t m = 0;
  for (int i = 0; i < N; ++i)
    if (((active >> i) & 1u) && occluded(a, rays[i], t_min[i], t_max[i])) m |= 1u << i;
  return m;
}

}  // namespace strahl
