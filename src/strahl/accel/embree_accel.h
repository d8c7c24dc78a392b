#pragma once
// Intel Embree 3 as one of the interchangeable acceleration structures (AccelKind::Embree), built
// only where CMake found Embree (STRAHL_HAVE_EMBREE). Host-only: kernels call the functions below
// from accel.h's nearest_hit / occluded / for_each_crossing under
// `#if defined(STRAHL_HAVE_EMBREE) && !defined(__CUDACC__)`; everywhere else an Embree view falls
// back to the naive loop (slow but correct).
//
// This header includes no Embree header: the scene and device are held as opaque pointers, so
// that accel.h (and everything including it) does not depend on <embree3/rtcore.h>.
//
// Geometry: the triangles are one Embree triangle mesh (3 float vertices per triangle, no vertex
// sharing; Embree primID = triangle index); the spheres are one Embree user geometry whose
// intersection callback runs strahl's own double-precision sphere test on the original ray, so
// sphere hits are bit-identical to the naive loop's. Build quality: medium.
//
// Precision: Embree traverses and intersects triangles in float, so which triangle is hit is
// decided in float (edges rounded to float: rays grazing an edge may get the neighbour, or pass
// between). Two measures keep secondary rays, which start a relative 1e-9 (kRayEpsilon) off the
// surface they leave — far below float resolution — from hitting that surface:
//   * the nearest hit's t, b1, b2 are recomputed in double for the triangle Embree found
//     (strahl's Möller–Trumbore), so the hit point lies on the triangle to double precision;
//   * a filter function hands every triangle hit nearer than kEmbreeCheckDistance·(1 +
//     |origin|_max) to strahl's double-precision test, which rejects it when it sees no hit in
//     (t_min, ∞). Beyond that distance (a self-hit there needs a ray within ~1e-4 of grazing)
//     Embree's float answer stands.

#include <cstddef>
#include <cstdint>

#include "strahl/math/config.h"

namespace strahl {

struct AccelBuildStats;
struct AccelView;
struct NearestHit;
struct PrimitiveSet;
struct Ray;

// Triangle hits nearer than this, relative to the ray origin's largest coordinate (plus 1), are
// confirmed by strahl's double-precision test (float self-intersection; see above).
inline constexpr Real kEmbreeCheckDistance = Real(1e-3);

// Owns a committed RTCScene and a reference to its RTCDevice. Copies share the (immutable)
// scene by Embree's reference counting; moves transfer it.
class EmbreeAccel {
 public:
  EmbreeAccel() = default;
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel& other);
  EmbreeAccel& operator=(const EmbreeAccel& other);
  EmbreeAccel(EmbreeAccel&& other) noexcept;
  EmbreeAccel& operator=(EmbreeAccel&& other) noexcept;

  // The RTCScene, or null when nothing was built (or there are no primitives).
  void* scene() const { return scene_; }

 private:
  friend EmbreeAccel build_embree(const PrimitiveSet& prims, AccelBuildStats* stats);
  void release() noexcept;
  void* device_ = nullptr;  // RTCDevice
  void* scene_ = nullptr;   // RTCScene
};

// Builds the Embree scene over the primitives (medium quality, on the calling thread's TBB arena).
// Throws std::runtime_error when Embree reports an error. stats->bytes is what Embree allocated
// for the scene, as its memory monitor reports it: the BVH and Embree's own copies of the
// vertices (and of the triangles in its leaves).
EmbreeAccel build_embree(const PrimitiveSet& prims, AccelBuildStats* stats = nullptr);

// The three queries of accel.h, answered by rtcIntersect1 / rtcOccluded1. `a.kind` must be
// AccelKind::Embree.
NearestHit embree_nearest_hit(const AccelView& a, const Ray& ray, Real t_min, Real t_max);
bool embree_occluded(const AccelView& a, const Ray& ray, Real t_min, Real t_max);
// Packets of n = 8 or 16 rays, traced together by rtcIntersect8/16 / rtcOccluded8/16 (coherent
// mode): lane i takes part when bit i of `active` is set, and only those lanes' out[i] are
// written, with what the single-ray queries above answer (the same filter and double refinement;
// Embree's packet kernels may still decide a grazing ray in float differently). Any other n
// throws std::invalid_argument. rtcIntersect16 runs on any CPU, but natively only where
// embree_native_packet_width() is 16 (AVX-512).
inline constexpr int kEmbreeMaxPacket = 16;
void embree_nearest_hit_packet(const AccelView& a, int n, std::uint32_t active, const Ray* rays, const Real* t_min,
                               const Real* t_max, NearestHit* out);
void embree_occluded_packet(const AccelView& a, int n, std::uint32_t active, const Ray* rays, const Real* t_min,
                            const Real* t_max, bool* out);
// 16, 8 or 1: the widest packet this CPU's Embree kernels run natively.
int embree_native_packet_width();

// Calls cross(state, prim, 1) for every surface crossing in (t_min, t_max), nearest first, until
// it returns true: repeated rtcIntersect1, each starting past the previous hit.
using EmbreeCrossFn = bool (*)(void* state, std::uint32_t prim, int crossings);
void embree_for_each_crossing(const AccelView& a, const Ray& ray, Real t_min, Real t_max, EmbreeCrossFn cross,
                              void* state);

}  // namespace strahl
