#pragma once
// Four spheres side by side for the one-leaf sphere queries (accel/accel.h, the lecture's
// scenes: a handful of spheres tested by every mirror, glass and shadow ray): their centres and
// radii as 4-wide arrays, and the robust test of geometry/sphere.h run on all four at once with
// AVX (__m256d). Every lane performs exactly kernel::intersect()'s IEEE operations in its order
// (f = o − c, b = −f·d, l = f + d·b, r², D = r² − l·l, C = f·f − r², q = b + copysign(√D, b),
// t0 = C/q, t1 = q), so its t is bit for bit the scalar test's (the build has
// -ffp-contract=off; tests/sphere_test.cpp checks it). Without AVX (the sanitizer build, device
// code) the same functions call kernel::intersect() lane by lane.
//
// A quad is tested against the whole interval (t_min, t_max): a scalar loop that narrows t_max to
// the nearest hit so far finds the same nearest sphere (a root beyond the narrowed t_max is beyond
// the nearest one), so sphere_leaf_nearest() answers as the one-by-one loop did.
//
// Lanes past the last sphere have NaN radii: D is NaN and they never meet a ray. Where D < 0 the
// square root is NaN too, and every comparison with the roots is false: no hit, no crossing.

#include <cstdint>
#include <limits>
#include <vector>

#include "strahl/geometry/sphere.h"

// STRAHL_PORTABLE_KERNELS: the portable path on an AVX host too (tests/portable compares them).
#if !defined(__CUDACC__) && defined(__AVX__) && !defined(STRAHL_PORTABLE_KERNELS)
#include <immintrin.h>
#define STRAHL_SPHERE_QUAD_AVX 1
#endif

namespace strahl::kernel {

inline constexpr int kSphereQuadWidth = 4;

// 128 bytes: two cache lines.
struct alignas(32) SphereQuad {
  Real cx[kSphereQuadWidth], cy[kSphereQuadWidth], cz[kSphereQuadWidth], radius[kSphereQuadWidth];
};
static_assert(sizeof(SphereQuad) == 128);

STRAHL_HOST_DEVICE constexpr std::uint32_t sphere_quad_count(std::uint32_t spheres) {
  return (spheres + kSphereQuadWidth - 1) / kSphereQuadWidth;
}

// Host side: spheres[0 … count) four by four, the last quad's unused lanes NaN.
inline std::vector<SphereQuad> sphere_quads(const Sphere* spheres, std::uint32_t count) {
  std::vector<SphereQuad> quads(sphere_quad_count(count));
  for (SphereQuad& q : quads)
    for (int k = 0; k < kSphereQuadWidth; ++k) q.cx[k] = q.cy[k] = q.cz[k] = q.radius[k] = std::numeric_limits<Real>::quiet_NaN();
  for (std::uint32_t i = 0; i < count; ++i) {
    SphereQuad& q = quads[i / kSphereQuadWidth];
    const std::uint32_t k = i % kSphereQuadWidth;
    q.cx[k] = spheres[i].center.x;
    q.cy[k] = spheres[i].center.y;
    q.cz[k] = spheres[i].center.z;
    q.radius[k] = spheres[i].radius;
  }
  return quads;
}

// Lane k as a sphere (the portable paths test it with the scalar functions).
STRAHL_HOST_DEVICE inline Sphere quad_sphere(const SphereQuad& s, int k) {
  Sphere sphere;
  sphere.center = Vec3(s.cx[k], s.cy[k], s.cz[k]);
  sphere.radius = s.radius[k];
  return sphere;
}

#if defined(STRAHL_SPHERE_QUAD_AVX)
namespace sphere_quad_detail {

// The roots t0 = C/q (0 where q = 0) and t1 = q of the four spheres, unordered; false (and no
// roots) where no sphere's discriminant is ≥ 0: the ray misses all four.
STRAHL_FORCE_INLINE bool roots(const SphereQuad& s, const Ray& ray, __m256d& t0, __m256d& t1) {
  const __m256d dx = _mm256_set1_pd(ray.direction.x), dy = _mm256_set1_pd(ray.direction.y),
                dz = _mm256_set1_pd(ray.direction.z);
  const __m256d fx = _mm256_sub_pd(_mm256_set1_pd(ray.origin.x), _mm256_load_pd(s.cx));
  const __m256d fy = _mm256_sub_pd(_mm256_set1_pd(ray.origin.y), _mm256_load_pd(s.cy));
  const __m256d fz = _mm256_sub_pd(_mm256_set1_pd(ray.origin.z), _mm256_load_pd(s.cz));
  const __m256d sign = _mm256_set1_pd(-0.0);
  const __m256d f_dot_d = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(fx, dx), _mm256_mul_pd(fy, dy)), _mm256_mul_pd(fz, dz));
  const __m256d b = _mm256_xor_pd(f_dot_d, sign);
  const __m256d lx = _mm256_add_pd(fx, _mm256_mul_pd(dx, b));
  const __m256d ly = _mm256_add_pd(fy, _mm256_mul_pd(dy, b));
  const __m256d lz = _mm256_add_pd(fz, _mm256_mul_pd(dz, b));
  const __m256d r = _mm256_load_pd(s.radius);
  const __m256d r2 = _mm256_mul_pd(r, r);
  const __m256d l_dot_l = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(lx, lx), _mm256_mul_pd(ly, ly)), _mm256_mul_pd(lz, lz));
  const __m256d discriminant = _mm256_sub_pd(r2, l_dot_l);
  if (_mm256_movemask_pd(_mm256_cmp_pd(discriminant, _mm256_setzero_pd(), _CMP_GE_OQ)) == 0) return false;
  const __m256d f_dot_f = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(fx, fx), _mm256_mul_pd(fy, fy)), _mm256_mul_pd(fz, fz));
  const __m256d c = _mm256_sub_pd(f_dot_f, r2);
  // copysign(√D, b): the root's magnitude with b's sign bit.
  const __m256d root = _mm256_or_pd(_mm256_andnot_pd(sign, _mm256_sqrt_pd(discriminant)), _mm256_and_pd(sign, b));
  const __m256d q = _mm256_add_pd(b, root);
  const __m256d nonzero = _mm256_cmp_pd(q, _mm256_setzero_pd(), _CMP_NEQ_UQ);  // q != 0 (true for NaN)
  t0 = _mm256_and_pd(nonzero, _mm256_div_pd(c, q));
  t1 = q;
  return true;
}

STRAHL_FORCE_INLINE __m256d inside(__m256d t, __m256d t_min, __m256d t_max) {
  return _mm256_and_pd(_mm256_cmp_pd(t, t_min, _CMP_GT_OQ), _mm256_cmp_pd(t, t_max, _CMP_LT_OQ));
}

// Each sphere's nearest root in (t_min, t_max), kInfinity where it has none; returns the mask of
// the lanes that have one.
STRAHL_FORCE_INLINE int nearest_roots(const SphereQuad& s, const Ray& ray, Real t_min, Real t_max, __m256d& root) {
  __m256d t0, t1;
  root = _mm256_set1_pd(kInfinity);
  if (!roots(s, ray, t0, t1)) return 0;
  // if (t0 > t1) swap: the comparison is false for NaN, which leaves the pair as it is.
  const __m256d swap = _mm256_cmp_pd(t0, t1, _CMP_GT_OQ);
  const __m256d near = _mm256_blendv_pd(t0, t1, swap), far = _mm256_blendv_pd(t1, t0, swap);
  const __m256d lo = _mm256_set1_pd(t_min), hi = _mm256_set1_pd(t_max);
  const __m256d near_in = inside(near, lo, hi), far_in = inside(far, lo, hi);
  root = _mm256_blendv_pd(_mm256_blendv_pd(root, far, far_in), near, near_in);
  return _mm256_movemask_pd(_mm256_or_pd(near_in, far_in));
}

}  // namespace sphere_quad_detail
#endif

// t[k]: what kernel::intersect(sphere k, ray, t_min, t_max) returns — the nearest root in
// (t_min, t_max), or kInfinity.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void intersect(const SphereQuad& s, const Ray& ray, Real t_min, Real t_max,
                                                      Real* t) {
#if defined(STRAHL_SPHERE_QUAD_AVX)
  __m256d root;
  sphere_quad_detail::nearest_roots(s, ray, t_min, t_max, root);
  _mm256_storeu_pd(t, root);
#else
  for (int k = 0; k < kSphereQuadWidth; ++k) {
    t[k] = intersect(quad_sphere(s, k), ray, t_min, t_max);
  }
#endif
}

// The nearest of the four spheres' roots in (t_min, t_max): returns its lane (the lowest among
// equal t: what a loop over the lanes with `t < t_max`, narrowing t_max, finds) and sets t, or
// returns −1 and leaves t alone.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE int intersect_nearest(const SphereQuad& s, const Ray& ray, Real t_min, Real t_max,
                                                             Real& t) {
#if defined(STRAHL_SPHERE_QUAD_AVX)
  __m256d nearest;
  const int mask = sphere_quad_detail::nearest_roots(s, ray, t_min, t_max, nearest);
  if (mask == 0) return -1;
  alignas(32) Real root[kSphereQuadWidth];
  _mm256_store_pd(root, nearest);
  int lane = __builtin_ctz(unsigned(mask));
  for (int k = lane + 1; k < kSphereQuadWidth; ++k)
    if (((mask >> k) & 1) && root[k] < root[lane]) lane = k;
  t = root[lane];
  return lane;
#else
  int lane = -1;
  for (int k = 0; k < kSphereQuadWidth; ++k) {
    const Real root = intersect(quad_sphere(s, k), ray, t_min, t_max);
    if (root < t_max) {
      t_max = t = root;
      lane = k;
    }
  }
  return lane;
#endif
}

// Does any of the four spheres have a root in (t_min, t_max)?
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool intersect_any(const SphereQuad& s, const Ray& ray, Real t_min, Real t_max) {
#if defined(STRAHL_SPHERE_QUAD_AVX)
  using namespace sphere_quad_detail;
  __m256d t0, t1;
  if (!roots(s, ray, t0, t1)) return false;
  const __m256d lo = _mm256_set1_pd(t_min), hi = _mm256_set1_pd(t_max);
  return _mm256_movemask_pd(_mm256_or_pd(inside(t0, lo, hi), inside(t1, lo, hi))) != 0;
#else
  Real t[kSphereQuadWidth];
  intersect(s, ray, t_min, t_max, t);
  return t[0] < kInfinity || t[1] < kInfinity || t[2] < kInfinity || t[3] < kInfinity;
#endif
}

// n[k]: what kernel::crossings(sphere k, ray, t_min, t_max) returns — 0, 1 or 2.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void crossings(const SphereQuad& s, const Ray& ray, Real t_min, Real t_max, int* n) {
#if defined(STRAHL_SPHERE_QUAD_AVX)
  using namespace sphere_quad_detail;
  __m256d t0, t1;
  if (!roots(s, ray, t0, t1)) {
    for (int k = 0; k < kSphereQuadWidth; ++k) n[k] = 0;
    return;
  }
  const __m256d lo = _mm256_set1_pd(t_min), hi = _mm256_set1_pd(t_max);
  const int first = _mm256_movemask_pd(inside(t0, lo, hi)), second = _mm256_movemask_pd(inside(t1, lo, hi));
  for (int k = 0; k < kSphereQuadWidth; ++k) n[k] = ((first >> k) & 1) + ((second >> k) & 1);
#else
  for (int k = 0; k < kSphereQuadWidth; ++k) {
    n[k] = crossings(quad_sphere(s, k), ray, t_min, t_max);
  }
#endif
}

}  // namespace strahl::kernel
