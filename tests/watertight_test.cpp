// Numerical robustness of the ray–primitive tests (issue 5): rays through the shared edges and
// exact vertices of triangle meshes never slip between the triangles (the watertight test of
// geometry/triangle.h), through every acceleration structure too; rays grazing a sphere hit or
// miss it as their distance from the centre says, at any scale.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/geometry/sphere.h"
#include "strahl/geometry/triangle.h"
#include "test_random.h"

namespace strahl::watertight_test {
namespace {

using test::Random;

// A height field over an n×n grid of quads, each cut into two triangles along a diagonal chosen at
// random, with irregular heights and (x, z) spacing, placed at `offset` and scaled by `scale` (so
// that no coordinate is a round number). Every triangle is listed with its vertices' exact values.
struct Grid {
  int n = 0;
  std::vector<Vec3> vertices;  // (n+1)² of them, row by row
  std::vector<kernel::Triangle> triangles;
  Vec3 at(int i, int j) const { return vertices[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)]; }
};

Grid make_grid(int n, const Vec3& offset, Real scale, std::uint64_t seed) {
  Random rng(seed);
  Grid g;
  g.n = n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Real x = (i + (i > 0 && i < n ? rng.uniform(-0.3, 0.3) : 0)) / n;
      const Real z = (j + (j > 0 && j < n ? rng.uniform(-0.3, 0.3) : 0)) / n;
      const Real y = 0.03 * std::sin(7.3 * x + 1) * std::cos(5.1 * z) + rng.uniform(-0.002, 0.002);
      g.vertices.push_back(offset + Vec3(x, y, z) * scale);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i + 1, j + 1), d = g.at(i, j + 1);
      kernel::Triangle t1, t2;
      if (rng.uniform() < 0.5) {
        t1.v0 = a, t1.v1 = b, t1.v2 = c;
        t2.v0 = a, t2.v1 = c, t2.v2 = d;
      } else {
        t1.v0 = a, t1.v1 = b, t1.v2 = d;
        t2.v0 = b, t2.v1 = c, t2.v2 = d;
      }
      g.triangles.push_back(t1);
      g.triangles.push_back(t2);
    }
  return g;
}

bool hits_any(const std::vector<kernel::Triangle>& triangles, const Ray& ray) {
  const kernel::RayShear shear = kernel::ray_shear(ray.direction);
  for (const kernel::Triangle& t : triangles)
    if (kernel::intersect(t, ray, shear, 0, kInfinity).t < kInfinity) return true;
  return false;
}

// A ray from above (within 50° of straight down) aimed at `target`, starting `distance` away.
Ray ray_at(Random& rng, const Vec3& target, Real distance) {
  Vec3 d = rng.direction();
  if (d.y > 0) d.y = -d.y;
  if (d.y > -0.65) d = normalize(Vec3(d.x, -0.65, d.z));
  return Ray{target - d * distance, d};
}

// Targets: every interior vertex, points on every interior edge (its midpoint, and points at
// random fractions along it), each as computed in floating point, so some lie a rounding error
// off the edge on either side.
std::vector<Vec3> edge_and_vertex_targets(const Grid& g, Random& rng) {
  std::vector<Vec3> targets;
  for (int j = 1; j < g.n; ++j)
    for (int i = 1; i < g.n; ++i) targets.push_back(g.at(i, j));
  for (const kernel::Triangle& t : g.triangles) {
    const Vec3 v[3] = {t.v0, t.v1, t.v2};
    for (int e = 0; e < 3; ++e) {
      const Vec3 a = v[e], b = v[(e + 1) % 3];
      const Vec3 mid = (a + b) * 0.5;
      const Vec3 lo = g.at(0, 0), hi = g.at(g.n, g.n);
      const auto interior = [&](const Vec3& p) { return p.x > lo.x && p.x < hi.x && p.z > lo.z && p.z < hi.z; };
      if (!interior(mid)) continue;  // a boundary edge: nothing on its other side
      targets.push_back(mid);
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = a + (b - a) * rng.uniform();
        if (interior(p)) targets.push_back(p);
      }
    }
  }
  return targets;
}

struct Placement {
  Vec3 offset;
  Real scale;
};
constexpr Placement kPlacements[] = {
    {{0.1, -0.2, 0.3}, 1.0},
    {{-1234.567, 89.01, 4321.0987}, 0.37},  // far from the origin: large, inexact coordinates
    {{3.3e4, -1.7e4, 2.9e4}, 1.3e3},       // big
    {{1.1e-3, 2.7e-3, -0.9e-3}, 3.1e-3},   // small
};

TEST(Watertight, RaysThroughSharedEdgesAndVerticesOfAGridNeverSlipThrough) {
  for (const Placement& pl : kPlacements) {
    const Grid g = make_grid(12, pl.offset, pl.scale, 7);
    Random rng(11);
    std::size_t rays = 0, slipped = 0;
    for (const Vec3& target : edge_and_vertex_targets(g, rng))
      for (int k = 0; k < 8; ++k) {
        const Ray ray = ray_at(rng, target, pl.scale * rng.uniform(0.5, 5));
        ++rays;
        if (!hits_any(g.triangles, ray)) ++slipped;
      }
    EXPECT_GT(rays, 10000u);
    EXPECT_EQ(slipped, 0u) << "of " << rays << " rays, at offset " << pl.offset.x << " scale " << pl.scale;
  }
}

TEST(Watertight, RaysThroughTheCentreOfAFanNeverSlipThrough) {
  // A fan of k triangles around one centre vertex, all sharing it and each sharing an edge with
  // the next: every ray through the centre (in any direction not lying in the fan's plane) hits.
  Random rng(5);
  for (int k : {3, 5, 7, 16, 61}) {
    for (const Placement& pl : kPlacements) {
      const Vec3 centre = pl.offset + Vec3(0.37, 0.11, -0.23) * pl.scale;
      std::vector<Vec3> rim;
      for (int i = 0; i < k; ++i) {
        // Gaps between rim points stay below 180° and heights vary smoothly around the rim, so
        // the fan surrounds its centre in the view along every ray (no triangle folds over).
        const Real phi = 2 * kPi * (i + rng.uniform(-0.15, 0.15)) / k;
        rim.push_back(centre + Vec3(std::cos(phi), 0.1 * std::sin(2 * phi + 0.4), std::sin(phi)) * pl.scale);
      }
      std::vector<kernel::Triangle> fan;
      for (int i = 0; i < k; ++i) {
        kernel::Triangle t;
        t.v0 = centre, t.v1 = rim[std::size_t(i)], t.v2 = rim[std::size_t((i + 1) % k)];
        fan.push_back(t);
      }
      for (int r = 0; r < 2000; ++r) {
        const Ray ray = ray_at(rng, centre, pl.scale * rng.uniform(0.1, 10));
        EXPECT_TRUE(hits_any(fan, ray)) << k << " triangles, offset " << pl.offset.x << ", ray " << r;
      }
    }
  }
}

TEST(Watertight, EveryAcceleratorFindsTheGridBehindEdgesAndVertices) {
  // The same through each structure's nearest_hit and occluded: their box tests must not cull a
  // triangle the ray meets exactly at an edge or vertex.
  for (const Placement& pl : kPlacements) {
    const Grid g = make_grid(24, pl.offset, pl.scale, 3);
    const PrimitiveSet prims{nullptr, 0, g.triangles.data(), std::uint32_t(g.triangles.size()), nullptr, 0, {}};
    Random rng(17);
    const std::vector<Vec3> targets = edge_and_vertex_targets(g, rng);
    for (AccelKind kind : accel_kinds()) {
#if defined(STRAHL_HAVE_EMBREE)
      if (kind == AccelKind::Embree) continue;  // float traversal: not watertight (see embree_accel.h)
#endif
      const Accel accel = build_accel(kind, prims);
      const AccelView view = accel.view(prims);
      std::size_t missed = 0, unoccluded = 0;
      Random ray_rng(19);
      for (const Vec3& target : targets) {
        const Ray ray = ray_at(ray_rng, target, pl.scale * ray_rng.uniform(0.5, 5));
        if (!(nearest_hit(view, ray, 0, kInfinity).hit.t < kInfinity)) ++missed;
        if (!occluded(view, ray, 0, kInfinity)) ++unoccluded;
      }
      EXPECT_EQ(missed, 0u) << accel_name(kind) << ", offset " << pl.offset.x;
      EXPECT_EQ(unoccluded, 0u) << accel_name(kind) << ", offset " << pl.offset.x;
    }
  }
}

TEST(Watertight, ExactVertexAndEdgeHitsOfAnAxisAlignedSquare) {
  // Two triangles of the square [0,1]² at z = 0; rays straight down (and tilted) through the
  // corners, the edge midpoints and the shared diagonal's points, all exactly representable.
  std::vector<kernel::Triangle> quad(2);
  quad[0].v0 = {0, 0, 0}, quad[0].v1 = {1, 0, 0}, quad[0].v2 = {1, 1, 0};
  quad[1].v0 = {0, 0, 0}, quad[1].v1 = {1, 1, 0}, quad[1].v2 = {0, 1, 0};
  for (const Vec3& d : {Vec3(0, 0, -1), normalize(Vec3(0.25, 0.5, -1)), normalize(Vec3(-0.5, 0.125, -1))})
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const Vec3 target(i / 8.0, j / 8.0, 0);
        const Ray ray{target - d * 4.0, d};
        EXPECT_TRUE(hits_any(quad, ray)) << target.x << ", " << target.y;
      }
}

TEST(Watertight, GrazingRaysHitASphereJustInsideItsRadiusAndMissJustOutside) {
  Random rng(23);
  for (const Placement& pl : kPlacements) {
    const kernel::Sphere s{pl.offset, 0.7 * pl.scale, 0};
    for (int k = 0; k < 2000; ++k) {
      // A tangent direction at a random point of the sphere, and the ray along it pushed a
      // relative 1e-6 inwards or outwards; it starts well before the tangent point.
      const Vec3 n = rng.direction();
      Vec3 tangent = normalize(cross(n, rng.direction()));
      const bool inside = k % 2 == 0;
      const Vec3 p = s.center + n * (s.radius * (inside ? 1 - 1e-6 : 1 + 1e-6));
      const Ray ray{p - tangent * (s.radius * rng.uniform(1.5, 20)), tangent};
      const Real t = kernel::intersect(s, ray, 0, kInfinity);
      if (inside) {
        ASSERT_LT(t, kInfinity) << "offset " << pl.offset.x << ", ray " << k;
        // The hit lies on the sphere (to a relative 1e-9 of its radius)...
        EXPECT_NEAR(length(ray.at(t) - s.center), s.radius, 1e-9 * s.radius);
        // ...and the ray crosses it twice, close to the tangent point on both sides.
        EXPECT_EQ(kernel::crossings(s, ray, 0, kInfinity), 2);
      } else {
        EXPECT_EQ(t, kInfinity) << "offset " << pl.offset.x << ", ray " << k;
        EXPECT_EQ(kernel::crossings(s, ray, 0, kInfinity), 0);
      }
    }
  }
}

TEST(Watertight, TinySphereFarAwayIsHitThroughItsCentreAndRim) {
  // A sphere of radius 1e-3 a thousand units away: the quadratic's textbook form loses it to
  // cancellation; the robust form hits it through the centre and at 0.999 of its radius.
  const kernel::Sphere s{{1000, 0, 0}, 1e-3, 0};
  const Ray through{{0, 0, 0}, {1, 0, 0}};
  EXPECT_NEAR(kernel::intersect(s, through, 0, kInfinity), 1000 - 1e-3, 1e-9);
  const Ray rim{{0, 0.999e-3, 0}, {1, 0, 0}};
  const Real t = kernel::intersect(s, rim, 0, kInfinity);
  ASSERT_LT(t, kInfinity);
  EXPECT_NEAR(length(rim.at(t) - s.center), s.radius, 1e-12);
  EXPECT_EQ(kernel::intersect(s, Ray{{0, 1.001e-3, 0}, {1, 0, 0}}, 0, kInfinity), kInfinity);
}

}  // namespace
}  // namespace strahl::watertight_test
