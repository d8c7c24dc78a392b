#include "strahl/scene/polygon.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace strahl {

namespace {

struct Point2 {
  double x, y;
};

// Twice the signed area of (o, a, b): > 0 when o → a → b turns left (counter-clockwise).
double turn(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// p inside or on the counter-clockwise triangle (a, b, c).
bool in_triangle(const Point2& p, const Point2& a, const Point2& b, const Point2& c) {
  return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

void fan(std::size_t n, std::vector<PolygonTriangle>& out) {
  for (std::uint32_t i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
}

// The polygon projected on the plane of the two axes other than its normal's largest one,
// counter-clockwise. Empty when the polygon has no area (then any split is as good).
std::vector<Point2> project(std::span<const Vec3> c) {
  Vec3 normal(0);  // Newell's normal: twice the vector area
  for (std::size_t i = 1; i + 1 < c.size(); ++i) normal += cross(c[i] - c[0], c[i + 1] - c[0]);
  const Vec3 a(std::fabs(normal.x), std::fabs(normal.y), std::fabs(normal.z));
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  if (!(a[axis] > 0) || !std::isfinite(a[axis])) return {};
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) is right-handed
  const double flip = normal[axis] > 0 ? 1 : -1;
  std::vector<Point2> p(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) p[i] = {double(c[i][u] - c[0][u]), double(c[i][v] - c[0][v]) * flip};
  return p;
}

// How far a coordinate may be off: rounding to float (a relative 2^-24, doubled for margin).
double precision(std::span<const Vec3> c) {
  double extent = 0;
  for (const Vec3& q : c) extent = std::max({extent, double(std::fabs(q.x)), double(std::fabs(q.y)), double(std::fabs(q.z))});
  return extent * 0x1p-23;
}

// Does a → b → d turn right by more than moving the corners by `delta` could explain?
bool reflex_corner(const Point2& a, const Point2& b, const Point2& d, double delta) {
  const double e1x = b.x - a.x, e1y = b.y - a.y, e2x = d.x - b.x, e2y = d.y - b.y;
  return e1x * e2y - e1y * e2x < -4 * delta * (std::hypot(e1x, e1y) + std::hypot(e2x, e2y));
}

// Convex up to the precision of the input: no corner is reflex, and the corners go round once
// (a star polygon whose corners all turn left goes round several times).
bool is_convex(const std::vector<Point2>& p, double delta) {
  const std::size_t n = p.size();
  double turning = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& a = p[(i + n - 1) % n];
    const Point2& b = p[i];
    const Point2& d = p[(i + 1) % n];
    if (reflex_corner(a, b, d, delta)) return false;
    const double e1x = b.x - a.x, e1y = b.y - a.y, e2x = d.x - b.x, e2y = d.y - b.y;
    turning += std::atan2(e1x * e2y - e1y * e2x, e1x * e2x + e1y * e2y);
  }
  return std::fabs(turning - 2 * std::numbers::pi) < 1;
}

// Ear clipping over a circular list of the remaining corners. A corner is an ear when it turns
// left and no reflex corner lies in the triangle it cuts off; only reflex corners can lie there
// in a simple polygon, so only they are tested. When no corner is an ear (a self-intersecting or
// non-planar polygon), the current one is cut off anyway, so the loop always ends.
bool ear_clip(const std::vector<Point2>& p, double delta, std::vector<PolygonTriangle>& out, std::uint64_t max_steps) {
  const auto n = std::uint32_t(p.size());
  std::vector<std::uint32_t> next(n), prev(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    next[i] = (i + 1) % n;
    prev[i] = (i + n - 1) % n;
  }
  std::vector<char> removed(n, 0), reflex(n, 0);
  std::vector<std::uint32_t> reflex_list;
  const auto update = [&](std::uint32_t i) {
    reflex[i] = reflex_corner(p[prev[i]], p[i], p[next[i]], delta);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    update(i);
    if (reflex[i]) reflex_list.push_back(i);
  }
  std::uint64_t steps = 0;
  const auto is_ear = [&](std::uint32_t i) {
    if (reflex[i]) return false;
    const std::uint32_t a = prev[i], b = next[i];
    std::size_t live = 0;
    for (const std::uint32_t r : reflex_list) {
      if (removed[r] || !reflex[r]) continue;
      ++live;
      ++steps;
      if (r != a && r != b && in_triangle(p[r], p[a], p[i], p[b])) return false;
    }
    // Corners only ever stop being reflex: drop the stale entries once they dominate.
    if (reflex_list.size() > 2 * live + 64)
      std::erase_if(reflex_list, [&](std::uint32_t r) { return removed[r] || !reflex[r]; });
    return true;
  };
  std::uint32_t remaining = n, i = 0, misses = 0;
  while (remaining > 3) {
    if (steps > max_steps) return false;
    if (is_ear(i) || misses > remaining) {
      const std::uint32_t a = prev[i], b = next[i];
      out.push_back({a, i, b});
      removed[i] = 1;
      next[a] = b;
      prev[b] = a;
      --remaining;
      update(a);
      update(b);
      i = a;  // the corner before may have become an ear
      misses = 0;
    } else {
      i = next[i];
      ++misses;
    }
  }
  out.push_back({prev[i], i, next[i]});
  return true;
}

}  // namespace

bool triangulate_polygon(std::span<const Vec3> corners, std::vector<PolygonTriangle>& triangles,
                         std::uint64_t max_steps) {
  const std::size_t n = corners.size();
  if (n < 3) return true;
  if (n == 3) {
    triangles.push_back({0, 1, 2});
    return true;
  }
  const std::vector<Point2> p = project(corners);
  if (p.empty()) {  // no area: dropped as zero-area faces later, however it is split
    fan(n, triangles);
    return true;
  }
  const double delta = precision(corners);
  if (is_convex(p, delta)) {
    if (n == 4) {  // along the shorter diagonal
      if (length_squared(corners[2] - corners[0]) < length_squared(corners[3] - corners[1]))
        triangles.insert(triangles.end(), {PolygonTriangle{0, 1, 2}, PolygonTriangle{0, 2, 3}});
      else
        triangles.insert(triangles.end(), {PolygonTriangle{0, 1, 3}, PolygonTriangle{1, 2, 3}});
      return true;
    }
    fan(n, triangles);
    return true;
  }
  const std::size_t before = triangles.size();
  if (ear_clip(p, delta, triangles, max_steps)) return true;
  triangles.resize(before);
  return false;
}

}  // namespace strahl
