// The 4-wide triangle test of accel/triangle_block.h against the scalar watertight test of
// geometry/triangle.h: every lane's t, b1 and b2 bit for bit, the nearest lane (the lowest among
// equal t) and the any-hit answer, on random, degenerate, edge- and vertex-through, huge and tiny
// triangles and rays. The Release build runs the AVX path, the sanitizer build (no -march=native)
// the scalar fallback; both must give exactly kernel::intersect()'s numbers.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "strahl/accel/triangle_block.h"
#include "test_random.h"

namespace strahl::triangle_block_test {
namespace {

using test::Random;

struct Tri {
  Vec3 v0, v1, v2;
};

std::uint64_t bits(Real x) { return std::bit_cast<std::uint64_t>(x); }

// The scalar test's answer for one triangle.
kernel::TriangleHit scalar(const Tri& t, const Ray& ray, Real t_min, Real t_max) {
  return kernel::intersect(t.v0, t.v1, t.v2, ray, kernel::ray_shear(ray.direction), t_min, t_max);
}

void expect_same(const kernel::TriangleHit& a, const kernel::TriangleHit& b, const char* what) {
  EXPECT_EQ(bits(a.t), bits(b.t)) << what << ": t " << a.t << " vs " << b.t;
  EXPECT_EQ(bits(a.b1), bits(b.b1)) << what << ": b1 " << a.b1 << " vs " << b.b1;
  EXPECT_EQ(bits(a.b2), bits(b.b2)) << what << ": b2 " << a.b2 << " vs " << b.b2;
}

// Checks the block test against the scalar one for four triangles (n < 4: the rest empty) and a
// ray: each triangle alone in every lane, then all of them together (nearest and any-hit), also
// with t_max lowered to each hit's t and just above it.
void check(const std::vector<Tri>& tris, const Ray& ray, Real t_min, Real t_max, std::size_t& hits) {
  const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, kernel::ray_shear(ray.direction));
  for (const Tri& t : tris) {
    const kernel::TriangleHit want = scalar(t, ray, t_min, t_max);
    for (int lane = 0; lane < kernel::kTriangleBlockWidth; ++lane) {
      kernel::TriangleBlock b;
      kernel::clear(b);
      kernel::set_triangle(b, lane, t.v0, t.v1, t.v2, 7);
      kernel::TriangleHit got;
      const int l = kernel::intersect_nearest(b, br, t_min, t_max, got);
      EXPECT_EQ(kernel::intersect_any(b, br, t_min, t_max), want.t < kInfinity);
      if (want.t < kInfinity) {
        ++hits;
        ASSERT_EQ(l, lane);
        expect_same(got, want, "single lane");
      } else {
        EXPECT_EQ(l, -1);
      }
    }
  }
  kernel::TriangleBlock b;
  kernel::clear(b);
  for (std::size_t k = 0; k < tris.size(); ++k)
    kernel::set_triangle(b, int(k), tris[k].v0, tris[k].v1, tris[k].v2, std::uint32_t(k));
  std::vector<Real> limits{t_max};
  for (const Tri& t : tris) {
    const Real h = scalar(t, ray, t_min, t_max).t;
    if (h < kInfinity) limits.insert(limits.end(), {h, std::nextafter(h, kInfinity)});
  }
  for (const Real limit : limits) {
    // The scalar loop a leaf used to run: strict <, lanes in order.
    int want_lane = -1;
    kernel::TriangleHit want;
    Real t_far = limit;
    for (std::size_t k = 0; k < tris.size(); ++k) {
      const kernel::TriangleHit h = scalar(tris[k], ray, t_min, t_far);
      if (h.t < t_far) {
        t_far = h.t;
        want = h;
        want_lane = int(k);
      }
    }
    kernel::TriangleHit got;
    const int l = kernel::intersect_nearest(b, br, t_min, limit, got);
    ASSERT_EQ(l, want_lane);
    if (l >= 0) {
      expect_same(got, want, "block");
      EXPECT_EQ(b.prim[l], std::uint32_t(l));
    }
    EXPECT_EQ(kernel::intersect_any(b, br, t_min, limit), want_lane >= 0);
  }
}

constexpr Real kScales[] = {1.0, 3.7e-6, 2.9e5, 1.3e-3, 4.1e3};

TEST(TriangleBlock, RandomTrianglesAndRaysAtManyScalesMatchTheScalarTestBitForBit) {
  Random rng(1);
  std::size_t hits = 0;
  for (const Real scale : kScales)
    for (int round = 0; round < 400; ++round) {
      const Vec3 centre = rng.point(-50, 50) * scale;
      std::vector<Tri> tris;
      const int n = 1 + rng.below(4);
      for (int k = 0; k < n; ++k) {
        const Vec3 p = centre + rng.point(-1, 1) * scale;
        tris.push_back({p, p + rng.direction() * scale, p + rng.direction() * scale});
      }
      // Rays from around the triangles aimed at one of them (a point inside, near an edge or
      // outside), and a few in arbitrary directions.
      for (int r = 0; r < 8; ++r) {
        const Tri& t = tris[std::size_t(rng.below(n))];
        const Real b1 = rng.uniform(-0.2, 1.0), b2 = rng.uniform(-0.2, 1.0 - b1 + 0.1);
        const Vec3 target = t.v0 + (t.v1 - t.v0) * b1 + (t.v2 - t.v0) * b2;
        const Vec3 origin = centre + rng.point(-4, 4) * scale;
        const Vec3 d = r < 6 ? normalize(target - origin) : rng.direction();
        check(tris, Ray{origin, d}, r == 7 ? Real(0.5) * scale : Real(0), kInfinity, hits);
      }
    }
  EXPECT_GT(hits, 5000u);  // the comparison covered hits, not only misses
}

TEST(TriangleBlock, RaysThroughSharedEdgesAndVerticesMatchBitForBit) {
  // A fan of triangles around a centre vertex, rays through the centre, through points on the
  // shared edges (as computed in floating point, so a rounding error on either side) and through
  // the rim vertices: the cases the watertight test is made for.
  Random rng(2);
  std::size_t hits = 0;
  for (const Real scale : kScales) {
    const Vec3 centre = Vec3(0.37, 0.11, -0.23) * scale + Vec3(-1234.567, 89.01, 4321.0987) * (scale < 1 ? 0 : 1);
    std::vector<Vec3> rim;
    for (int i = 0; i < 8; ++i) {
      const Real a = 2 * kPi * (i + rng.uniform(-0.3, 0.3)) / 8;
      rim.push_back(centre + Vec3(std::cos(a), 0.1 * std::sin(3 * a), std::sin(a)) * scale);
    }
    std::vector<Tri> fan;
    for (int i = 0; i < 8; ++i) fan.push_back({centre, rim[std::size_t(i)], rim[std::size_t((i + 1) % 8)]});
    for (int group = 0; group < 2; ++group) {
      const std::vector<Tri> tris(fan.begin() + group * 4, fan.begin() + group * 4 + 4);
      std::vector<Vec3> targets{centre};
      for (const Tri& t : tris) {
        targets.push_back(t.v1);
        targets.push_back(t.v2);
        targets.push_back((t.v0 + t.v1) * 0.5);
        for (int k = 0; k < 4; ++k) targets.push_back(t.v0 + (t.v1 - t.v0) * rng.uniform());
      }
      for (const Vec3& target : targets)
        for (int k = 0; k < 6; ++k) {
          Vec3 d = rng.direction();
          if (d.y > -0.3) d = normalize(Vec3(d.x, -0.3 - std::fabs(d.y), d.z));
          check(tris, Ray{target - d * (scale * rng.uniform(0.5, 5)), d}, 0, kInfinity, hits);
        }
    }
  }
  EXPECT_GT(hits, 1000u);
}

TEST(TriangleBlock, DegenerateTrianglesAndAxisParallelRaysMatchBitForBit) {
  Random rng(3);
  std::size_t hits = 0;
  for (const Real scale : kScales)
    for (int round = 0; round < 200; ++round) {
      const Vec3 p = rng.point(-2, 2) * scale, q = rng.point(-2, 2) * scale, r = rng.point(-2, 2) * scale;
      std::vector<Tri> tris = {
          {p, q, r},                         // ordinary
          {p, p, q},                         // two coincident vertices
          {p, q, p + (q - p) * 0.5},         // collinear
          {p, p, p},                         // a point
      };
      if (round % 2 == 1) tris[3] = tris[0];  // a duplicate: the tie goes to the lower lane
      // Axis-parallel directions with ±0 components, rays lying in the first triangle's plane,
      // rays from the vertices, rays from inside the triangle's plane.
      const Vec3 axes[] = {{1, 0, 0}, {-0.0, 1, 0}, {0, -0.0, -1}, {-1, -0.0, 0.0}};
      const Vec3 target = p + (q - p) * 0.3 + (r - p) * 0.3;
      for (const Vec3& a : axes) check(tris, Ray{target - a * (3 * scale), a}, 0, kInfinity, hits);
      const Vec3 in_plane = normalize(q - p);
      check(tris, Ray{p - in_plane * scale, in_plane}, 0, kInfinity, hits);
      check(tris, Ray{p, rng.direction()}, 0, kInfinity, hits);
      check(tris, Ray{p, rng.direction()}, -scale, kInfinity, hits);  // t_min < 0: t = 0 counts
      const Vec3 d = rng.direction();
      check(tris, Ray{target - d * scale, d}, 0, scale, hits);  // t_max exactly at the hit, more or less
    }
  EXPECT_GT(hits, 1000u);
}

TEST(TriangleBlock, EmptyAndOtherLanesNeverHit) {
  kernel::TriangleBlock b;
  kernel::clear(b);
  kernel::set_triangle(b, 1, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 42);
  kernel::set_other(b, 2, 5);
  EXPECT_EQ(b.other, 4u);
  EXPECT_EQ(b.triangles, 2u);
  EXPECT_EQ(b.prim[0], kernel::kTriangleBlockEmpty);
  const Vec3 dirs[] = {{0, 0, 1}, {0, 0, -1}, {0.6, 0, 0.8}, {0, 1, 0}};
  for (const Vec3& d : dirs) {
    const Ray ray{-d * 2, d};
    const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, kernel::ray_shear(d));
    kernel::TriangleHit h;
    const int lane = kernel::intersect_nearest(b, br, -kInfinity, kInfinity, h);
    if (d.z != 0) {
      EXPECT_EQ(lane, 1);
      EXPECT_NEAR(h.t, 2.0, 1e-12);
    } else {
      EXPECT_EQ(lane, -1);  // in the triangle's plane
    }
  }
  kernel::clear(b);
  const Ray ray{{0, 0, -1}, {0, 0, 1}};
  const kernel::TriangleBlockRay br = kernel::triangle_block_ray(ray, kernel::ray_shear(ray.direction));
  kernel::TriangleHit h;
  EXPECT_EQ(kernel::intersect_nearest(b, br, -kInfinity, kInfinity, h), -1);
  EXPECT_FALSE(kernel::intersect_any(b, br, -kInfinity, kInfinity));
}

}  // namespace
}  // namespace strahl::triangle_block_test
