#include "strahl/accel/spatial.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <limits>

namespace strahl {

namespace {

void set_component(Vec3& v, int axis, Real x) { (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = x; }

// Sutherland–Hodgman: the part of the convex polygon in[0..n) on one side of the plane
// x[axis] = pos. At most n + 1 vertices.
int clip_polygon(const Vec3* in, int n, Vec3* out, int axis, Real pos, bool keep_below) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3& a = in[i];
    const Vec3& b = in[(i + 1) % n];
    const Real da = keep_below ? pos - a[axis] : a[axis] - pos;
    const Real db = keep_below ? pos - b[axis] : b[axis] - pos;
    if (da >= 0) out[m++] = a;
    if ((da >= 0) != (db >= 0)) {
      Vec3 p = a + (b - a) * (da / (da - db));
      set_component(p, axis, pos);
      out[m++] = p;
    }
  }
  return m;
}

// Plain comparisons: std::fmin/fmax (what min/max of Vec3 use, for NaN) are library calls.
Real lesser(Real a, Real b) { return a < b ? a : b; }
Real greater(Real a, Real b) { return a > b ? a : b; }

Bounds intersection(const Bounds& a, const Bounds& b) {
  Bounds r;
  r.lo = {greater(a.lo.x, b.lo.x), greater(a.lo.y, b.lo.y), greater(a.lo.z, b.lo.z)};
  r.hi = {lesser(a.hi.x, b.hi.x), lesser(a.hi.y, b.hi.y), lesser(a.hi.z, b.hi.z)};
  if (r.lo.x > r.hi.x || r.lo.y > r.hi.y || r.lo.z > r.hi.z) return Bounds{};
  return r;
}

void extend(Bounds& b, const Vec3& p) {
  b.lo = {lesser(b.lo.x, p.x), lesser(b.lo.y, p.y), lesser(b.lo.z, p.z)};
  b.hi = {greater(b.hi.x, p.x), greater(b.hi.y, p.y), greater(b.hi.z, p.z)};
}

bool inside(const Bounds& a, const Bounds& b) {
  return a.lo.x >= b.lo.x && a.lo.y >= b.lo.y && a.lo.z >= b.lo.z && a.hi.x <= b.hi.x && a.hi.y <= b.hi.y &&
         a.hi.z <= b.hi.z;
}

}  // namespace

std::uint32_t append_leaf(const PrimitiveSet& prims, const std::uint32_t* list, std::uint32_t count,
                          LargeArray<SpatialLeaf>& out) {
  const std::uint32_t blocks = (count + kernel::kTriangleBlockWidth - 1) / kernel::kTriangleBlockWidth;
  const std::size_t first = out.size();
  out.resize(first + blocks);
  for (std::uint32_t b = 0; b < blocks; ++b) kernel::clear(out[first + b]);
  for (std::uint32_t i = 0; i < count; ++i) {
    SpatialLeaf& block = out[first + i / kernel::kTriangleBlockWidth];
    const int lane = int(i % kernel::kTriangleBlockWidth);
    const std::uint32_t prim = list[i];
    if (!prims.is_triangle(prim)) {
      kernel::set_other(block, lane, prim);
    } else {
      const kernel::Triangle& t = prims.triangles[prim - prims.sphere_count];
      kernel::set_triangle(block, lane, t.v0, t.v1, t.v2, prim);
    }
  }
  return blocks;
}

int rope_side(int axis, float plane, int f, const float (&face)[6]) {
  if (axis == f / 2) {
    const bool beyond_upper = f % 2 != 0;  // the face is the leaf's upper one: the far side lies above
    return beyond_upper ? plane <= face[f] : !(plane >= face[f]);
  }
  const float lo = face[2 * axis], hi = face[2 * axis + 1];
  if (plane >= hi && !(plane <= lo)) return 0;
  if (plane <= lo && !(plane >= hi)) return 1;
  return -1;
}

void unbounded_faces(float (&face)[6], std::uint32_t (&rope)[6]) {
  for (int f = 0; f < 6; ++f) {
    face[f] = f % 2 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
    rope[f] = kNoRope;
  }
}

Real bounds_padding(const Bounds& scene) {
  if (scene.empty()) return Real(1e-300);
  const Vec3 lo(std::fabs(scene.lo.x), std::fabs(scene.lo.y), std::fabs(scene.lo.z));
  const Vec3 hi(std::fabs(scene.hi.x), std::fabs(scene.hi.y), std::fabs(scene.hi.z));
  const Real pad = kBoundsPadding * max_component(max(lo, hi));
  return pad > Real(1e-300) ? pad : Real(1e-300);
}

Bounds padded(const Bounds& b, Real pad) {
  Bounds r;
  r.lo = b.lo - Vec3(pad);
  r.hi = b.hi + Vec3(pad);
  return r;
}

bool overlaps(const Bounds& a, const Bounds& b) {
  return a.lo.x <= b.hi.x && a.hi.x >= b.lo.x && a.lo.y <= b.hi.y && a.hi.y >= b.lo.y && a.lo.z <= b.hi.z &&
         a.hi.z >= b.lo.z;
}

Bounds clipped_bounds(const PrimitiveSet& prims, std::uint32_t prim, const Bounds& node_box, Real pad) {
  const Bounds box = padded(node_box, pad);
  const Bounds whole = primitive_bounds(prims, prim);
  if (inside(whole, box)) return padded(whole, pad);
  Bounds b;
  if (!prims.is_triangle(prim)) {
    b = intersection(whole, box);
  } else {
    const kernel::Triangle& t = prims.triangles[prim - prims.sphere_count];
    Vec3 poly[2][16] = {{t.v0, t.v1, t.v2}};
    int n = 3, cur = 0;
    for (int axis = 0; axis < 3 && n > 0; ++axis) {
      n = clip_polygon(poly[cur], n, poly[1 - cur], axis, box.lo[axis], false);
      cur = 1 - cur;
      n = clip_polygon(poly[cur], n, poly[1 - cur], axis, box.hi[axis], true);
      cur = 1 - cur;
    }
    for (int i = 0; i < n; ++i) extend(b, poly[cur][i]);
    if (!b.empty()) b = intersection(b, box);  // the clipped points lie on its faces up to rounding
  }
  return b.empty() ? b : padded(b, pad);
}

PaddedBounds padded_primitive_bounds(const PrimitiveSet& prims) {
  const std::uint32_t n = prims.size();
  PaddedBounds out;
  out.prims.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, 1024), [&](const auto& r) {
    for (std::uint32_t i = r.begin(); i != r.end(); ++i) out.prims[i] = primitive_bounds(prims, i);
  });
  Bounds scene;
  for (const Bounds& b : out.prims) {
    scene.extend(b.lo);
    scene.extend(b.hi);
  }
  out.pad = bounds_padding(scene);
  for (Bounds& b : out.prims) b = padded(b, out.pad);
  out.scene = padded(scene, out.pad);
  return out;
}

}  // namespace strahl
