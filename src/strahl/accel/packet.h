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
  std::uint32_t m = 0;
  for (int i = 0; i < N; ++i)
    if (((active >> i) & 1u) && occluded(a, rays[i], t_min[i], t_max[i])) m |= 1u << i;
  return m;
}

}  // namespace strahl
