#pragma once
// Four triangles side by side for the leaves of the acceleration structures: their vertices in
// double, structure of arrays (one 4-wide array per vertex and coordinate), and the watertight
// test of geometry/triangle.h run on all four at once with AVX (__m256d). Every lane performs
// exactly the IEEE operations of kernel::intersect(), in the same order (shear_triangle(), the
// inside test, det = u + v + w, inv_det = 1/det, sheared_distance(), b1 = v·inv_det,
// b2 = w·inv_det), so each lane's t, b1, b2 are bit for bit those of the scalar test (the build
// has -ffp-contract=off; tests/triangle_block_test.cpp checks it). Without AVX (the sanitizer
// build, device code) the same functions call kernel::intersect() lane by lane.
//
// Use:
//   host, building:  TriangleBlock b;  clear(b);  set_triangle(b, lane, v0, v1, v2, prim);  ...
//                    (lanes left clear hold NaN vertices and never hit; prim = kTriangleBlockEmpty)
//   per ray:         const TriangleBlockRay br = triangle_block_ray(ray, kernel::ray_shear(ray.direction));
//   per block:       TriangleHit h; const int lane = intersect_nearest(b, br, t_min, t_max, h);
//                    // lane ≥ 0: h is lane's hit, the nearest in (t_min, t_max), the lowest lane
//                    // among equal t (what a scalar loop over the lanes with `h.t < t_far` finds)
//                    if (intersect_any(b, br, t_min, t_max)) ...
// A lane may also hold something that is not a triangle (a sphere or a solid: the structures
// test those from the primitive set's arrays, accel/primitive.h intersect_other()): its vertices
// stay NaN, its bit is set in `other`, and the caller tests it itself.

#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "strahl/accel/primitive.h"
#include "strahl/geometry/triangle.h"

// STRAHL_PORTABLE_KERNELS: the portable path on an AVX host too (tests/portable compares them).
#if !defined(__CUDACC__) && defined(__AVX__) && !defined(STRAHL_PORTABLE_KERNELS)
#include <immintrin.h>
#define STRAHL_TRIANGLE_BLOCK_AVX 1
#endif

namespace strahl::kernel {

inline constexpr int kTriangleBlockWidth = 4;
inline constexpr std::uint32_t kTriangleBlockEmpty = ~std::uint32_t(0);

// 320 bytes: five cache lines.
struct alignas(64) TriangleBlock {
  Real v[3][3][kTriangleBlockWidth];          // [vertex 0..2][axis x, y, z][lane]
  std::uint32_t prim[kTriangleBlockWidth];    // the lane's primitive id, kTriangleBlockEmpty when empty
  std::uint32_t other;                        // bit per lane: not a triangle (vertices NaN), the caller's
  std::uint32_t triangles;                    // bit per lane holding a triangle (0: the test is skipped)
  std::uint32_t pad[2];
};
// No member initialisers: a default-initialised block is left as it is (clear() fills it), so
// the leaf array's resize() touches no memory and the leaves' first writes (and page faults) fall
// in the parallel fill (accel/wide_bvh.cpp).
static_assert(std::is_trivially_default_constructible_v<TriangleBlock>);
static_assert(sizeof(TriangleBlock) == 320);

// Host side: every lane empty (NaN vertices: such a lane never hits).
inline void clear(TriangleBlock& b) {
  for (auto& vertex : b.v)
    for (auto& axis : vertex)
      for (Real& x : axis) x = std::numeric_limits<Real>::quiet_NaN();
  for (std::uint32_t& p : b.prim) p = kTriangleBlockEmpty;
  b.other = 0;
  b.triangles = 0;
  b.pad[0] = b.pad[1] = 0;
}

inline void set_triangle(TriangleBlock& b, int lane, const Vec3& v0, const Vec3& v1, const Vec3& v2,
                         std::uint32_t prim) {
  const Vec3* v[3] = {&v0, &v1, &v2};
  for (int k = 0; k < 3; ++k) {
    b.v[k][0][lane] = v[k]->x;
    b.v[k][1][lane] = v[k]->y;
    b.v[k][2][lane] = v[k]->z;
  }
  b.prim[lane] = prim;
  b.other &= ~(1u << lane);
  b.triangles |= 1u << lane;
}

// A lane the triangle test skips (NaN vertices) but that stands for `prim` (a sphere, say).
inline void set_other(TriangleBlock& b, int lane, std::uint32_t prim) {
  for (auto& vertex : b.v)
    for (auto& axis : vertex) axis[lane] = std::numeric_limits<Real>::quiet_NaN();
  b.prim[lane] = prim;
  b.other |= 1u << lane;
  b.triangles &= ~(1u << lane);
}

STRAHL_HOST_DEVICE inline Vec3 vertex(const TriangleBlock& b, int k, int lane) {
  return {b.v[k][0][lane], b.v[k][1][lane], b.v[k][2][lane]};
}

// What the block test needs of a ray, computed once per ray: the ray and its shear (for the scalar
// path) and the origin's components in the shear's axis order.
struct TriangleBlockRay {
  Ray ray;
  RayShear shear;
  Real o[3];  // origin[kx], origin[ky], origin[kz]
};

STRAHL_HOST_DEVICE inline TriangleBlockRay triangle_block_ray(const Ray& ray, const RayShear& s) {
  TriangleBlockRay r;
  r.ray = ray;
  r.shear = s;
  r.o[0] = ray.origin[s.kx];
  r.o[1] = ray.origin[s.ky];
  r.o[2] = ray.origin[s.kz];
  return r;
}

#if defined(STRAHL_TRIANGLE_BLOCK_AVX)
namespace triangle_block_detail {

// The four lanes' t, and the mask of lanes hit in (t_min, t_max); u·inv_det etc. on request.
struct Lanes {
  __m256d t, v, w, inv_det;
  int mask;
};

inline Lanes test(const TriangleBlock& b, const TriangleBlockRay& r, Real t_min, Real t_max) {
  const RayShear& s = r.shear;
  const double* base = &b.v[0][0][0];
  const auto load = [&](int vertex, int axis) { return _mm256_load_pd(base + (vertex * 3 + axis) * 4); };
  const __m256d ox = _mm256_set1_pd(r.o[0]), oy = _mm256_set1_pd(r.o[1]), oz = _mm256_set1_pd(r.o[2]);
  const __m256d sx = _mm256_set1_pd(s.sx), sy = _mm256_set1_pd(s.sy), sz = _mm256_set1_pd(s.sz);
  // shear_triangle(): a = v0 − o (the components kx, ky, kz of it), ax = a[kx] − sx·a[kz], ...
  const __m256d a_x = _mm256_sub_pd(load(0, s.kx), ox), a_y = _mm256_sub_pd(load(0, s.ky), oy),
                a_z = _mm256_sub_pd(load(0, s.kz), oz);
  const __m256d b_x = _mm256_sub_pd(load(1, s.kx), ox), b_y = _mm256_sub_pd(load(1, s.ky), oy),
                b_z = _mm256_sub_pd(load(1, s.kz), oz);
  const __m256d c_x = _mm256_sub_pd(load(2, s.kx), ox), c_y = _mm256_sub_pd(load(2, s.ky), oy),
                c_z = _mm256_sub_pd(load(2, s.kz), oz);
  const __m256d ax = _mm256_sub_pd(a_x, _mm256_mul_pd(sx, a_z)), ay = _mm256_sub_pd(a_y, _mm256_mul_pd(sy, a_z));
  const __m256d bx = _mm256_sub_pd(b_x, _mm256_mul_pd(sx, b_z)), by = _mm256_sub_pd(b_y, _mm256_mul_pd(sy, b_z));
  const __m256d cx = _mm256_sub_pd(c_x, _mm256_mul_pd(sx, c_z)), cy = _mm256_sub_pd(c_y, _mm256_mul_pd(sy, c_z));
  const __m256d u = _mm256_sub_pd(_mm256_mul_pd(cx, by), _mm256_mul_pd(cy, bx));
  const __m256d v = _mm256_sub_pd(_mm256_mul_pd(ax, cy), _mm256_mul_pd(ay, cx));
  const __m256d w = _mm256_sub_pd(_mm256_mul_pd(bx, ay), _mm256_mul_pd(by, ax));
  // Outside when some edge function is < 0 and some is > 0 (ordered compares: NaN is neither).
  const __m256d zero = _mm256_setzero_pd();
  const __m256d negative =
      _mm256_or_pd(_mm256_cmp_pd(u, zero, _CMP_LT_OQ),
                   _mm256_or_pd(_mm256_cmp_pd(v, zero, _CMP_LT_OQ), _mm256_cmp_pd(w, zero, _CMP_LT_OQ)));
  const __m256d positive =
      _mm256_or_pd(_mm256_cmp_pd(u, zero, _CMP_GT_OQ),
                   _mm256_or_pd(_mm256_cmp_pd(v, zero, _CMP_GT_OQ), _mm256_cmp_pd(w, zero, _CMP_GT_OQ)));
  const __m256d det = _mm256_add_pd(_mm256_add_pd(u, v), w);
  // Lanes that may hit: inside, det ≠ 0 and not NaN (a NaN det, an empty lane's, would give a NaN t,
  // rejected below anyway). Most blocks a ray meets have none: they need no division.
  const __m256d inside = _mm256_andnot_pd(_mm256_and_pd(negative, positive), _mm256_cmp_pd(det, zero, _CMP_NEQ_OQ));
  if (_mm256_movemask_pd(inside) == 0) return {zero, zero, zero, zero, 0};
  const __m256d inv_det = _mm256_div_pd(_mm256_set1_pd(1.0), det);
  // sheared_distance(): az = sz·a[kz], ..., t = (u·az + v·bz + w·cz)·inv_det.
  const __m256d az = _mm256_mul_pd(sz, a_z), bz = _mm256_mul_pd(sz, b_z), cz = _mm256_mul_pd(sz, c_z);
  const __m256d t = _mm256_mul_pd(
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(u, az), _mm256_mul_pd(v, bz)), _mm256_mul_pd(w, cz)), inv_det);
  // Hit: inside, det ≠ 0 (ordered: NaN det gives NaN t, rejected below), t_min < t < t_max.
  const __m256d in_range = _mm256_and_pd(_mm256_cmp_pd(t, _mm256_set1_pd(t_min), _CMP_GT_OQ),
                                         _mm256_cmp_pd(t, _mm256_set1_pd(t_max), _CMP_LT_OQ));
  const __m256d hit = _mm256_and_pd(inside, in_range);
  return {t, v, w, inv_det, _mm256_movemask_pd(hit)};
}

}  // namespace triangle_block_detail
#endif

// The nearest hit among the block's triangles in (t_min, t_max): returns its lane (the lowest
// among equal t) and sets `hit`, or returns −1 and leaves `hit` alone.
STRAHL_HOST_DEVICE inline int intersect_nearest(const TriangleBlock& b, const TriangleBlockRay& r, Real t_min,
                                                Real t_max, TriangleHit& hit) {
  if (b.triangles == 0) return -1;  // spheres only (the lecture's scene)
#if defined(STRAHL_TRIANGLE_BLOCK_AVX)
  const triangle_block_detail::Lanes l = triangle_block_detail::test(b, r, t_min, t_max);
  if (l.mask == 0) return -1;
  alignas(32) double t[4];
  _mm256_store_pd(t, l.t);
  int lane = __builtin_ctz(unsigned(l.mask));
  for (int k = lane + 1; k < kTriangleBlockWidth; ++k)
    if (((l.mask >> k) & 1) && t[k] < t[lane]) lane = k;
  alignas(32) double b1[4], b2[4];
  _mm256_store_pd(b1, _mm256_mul_pd(l.v, l.inv_det));
  _mm256_store_pd(b2, _mm256_mul_pd(l.w, l.inv_det));
  hit = {t[lane], b1[lane], b2[lane]};
  return lane;
#else
  int lane = -1;
  for (int k = 0; k < kTriangleBlockWidth; ++k) {
    const TriangleHit h = intersect(vertex(b, 0, k), vertex(b, 1, k), vertex(b, 2, k), r.ray, r.shear, t_min, t_max);
    if (h.t < t_max) {
      t_max = h.t;
      hit = h;
      lane = k;
    }
  }
  return lane;
#endif
}

// Is any of the block's triangles hit in (t_min, t_max)?
STRAHL_HOST_DEVICE inline bool intersect_any(const TriangleBlock& b, const TriangleBlockRay& r, Real t_min,
                                             Real t_max) {
  if (b.triangles == 0) return false;
#if defined(STRAHL_TRIANGLE_BLOCK_AVX)
  return triangle_block_detail::test(b, r, t_min, t_max).mask != 0;
#else
  for (int k = 0; k < kTriangleBlockWidth; ++k)
    if (intersect(vertex(b, 0, k), vertex(b, 1, k), vertex(b, 2, k), r.ray, r.shear, t_min, t_max).t < kInfinity)
      return true;
  return false;
#endif
}

// ---- runs of blocks (the leaves of every structure) ----

// The nearest hit among `count` consecutive blocks in (t_min, t_far), their spheres and solids
// (the `other` lanes, tested from the primitive set's arrays) included: lowers t_far and sets prim and hit
// when one is found. Within a block the answer is what a scalar loop over the lanes in order with
// `t < t_far` gives: the nearest, the lowest lane among equal t.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void blocks_nearest(const TriangleBlock* first, std::uint32_t count,
                                                           const PrimitiveSet& prims, const TriangleBlockRay& br,
                                                           Real t_min, Real& t_far, std::uint32_t& prim,
                                                           TriangleHit& hit) {
  for (std::uint32_t i = 0; i < count; ++i) {
    const TriangleBlock& b = first[i];
    TriangleHit h;
    int lane = intersect_nearest(b, br, t_min, t_far, h);
    if (b.other != 0) {
      for (int k = 0; k < kTriangleBlockWidth; ++k) {
        if (((b.other >> k) & 1u) == 0) continue;
        const std::uint32_t p = b.prim[k];
        const TriangleHit o = prims.is_sphere(p) ? TriangleHit{intersect(prims.spheres[p], br.ray, t_min, t_far), 0, 0}
                                                 : intersect_other(prims, p, br.ray, t_min, t_far);
        if (o.t < kInfinity && (lane < 0 || o.t < h.t || (o.t == h.t && k < lane))) {
          lane = k;
          h = o;
        }
      }
    }
    if (lane >= 0) {
      t_far = h.t;
      prim = b.prim[lane];
      hit = h;
    }
  }
}

// Is any primitive of `count` consecutive blocks (spheres and solids included) hit in (t_min, t_far)?
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE bool blocks_any(const TriangleBlock* first, std::uint32_t count,
                                                       const PrimitiveSet& prims, const TriangleBlockRay& br, Real t_min,
                                                       Real t_far) {
  for (std::uint32_t i = 0; i < count; ++i) {
    const TriangleBlock& b = first[i];
    if (intersect_any(b, br, t_min, t_far)) return true;
    if (b.other != 0)
      for (int k = 0; k < kTriangleBlockWidth; ++k)
        if (((b.other >> k) & 1u) &&
            (prims.is_sphere(b.prim[k]) ? intersect(prims.spheres[b.prim[k]], br.ray, t_min, t_far) < kInfinity
                                        : any_crossing(prims.shapes, prims.solid(b.prim[k]), br.ray, t_min, t_far)))
          return true;
  }
  return false;
}

}  // namespace strahl::kernel
