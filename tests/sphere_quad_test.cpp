// Four spheres side by side (geometry/sphere_quad.h) against kernel::intersect() and
// kernel::crossings() one sphere at a time: the same t and the same crossing counts, bit for bit,
// for random spheres and rays at many scales, rays from inside, grazing rays, interval ends on the
// roots themselves, axis-parallel rays with ±0 components and the NaN lanes past the last sphere;
// and the one-leaf queries of the scene (closest_hit, transmittance) against the spheres one by
// one, in scenes of 1 to 9 spheres.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/geometry/sphere_quad.h"
#include "strahl/render/intersect_scene.h"
#include "test_helpers.h"
#include "test_random.h"

namespace strahl::sphere_quad_test {
namespace {

std::uint64_t bits(Real x) { return std::bit_cast<std::uint64_t>(x); }

// The nearest of spheres[0 … n) in (t_min, t_max) one by one, as the scalar loop finds it.
int scalar_nearest(const std::vector<kernel::Sphere>& spheres, const Ray& ray, Real t_min, Real& t_max) {
  int nearest = -1;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Real t = kernel::intersect(spheres[i], ray, t_min, t_max);
    if (t < t_max) {
      t_max = t;
      nearest = int(i);
    }
  }
  return nearest;
}

// Every query of the quads against the spheres one by one, for one ray and interval.
void expect_same(const std::vector<kernel::Sphere>& spheres, const Ray& ray, Real t_min, Real t_max) {
  const std::vector<kernel::SphereQuad> quads = kernel::sphere_quads(spheres.data(), std::uint32_t(spheres.size()));
  ASSERT_EQ(quads.size(), kernel::sphere_quad_count(std::uint32_t(spheres.size())));
  Real t_far = t_max;
  int nearest = -1;
  for (std::size_t j = 0; j < quads.size(); ++j) {
    Real t[kernel::kSphereQuadWidth];
    int n[kernel::kSphereQuadWidth];
    kernel::intersect(quads[j], ray, t_min, t_max, t);
    kernel::crossings(quads[j], ray, t_min, t_max, n);
    bool any = false;
    for (int k = 0; k < kernel::kSphereQuadWidth; ++k) {
      const std::size_t i = j * kernel::kSphereQuadWidth + std::size_t(k);
      if (i < spheres.size()) {
        EXPECT_EQ(bits(t[k]), bits(kernel::intersect(spheres[i], ray, t_min, t_max))) << "sphere " << i;
        EXPECT_EQ(n[k], kernel::crossings(spheres[i], ray, t_min, t_max)) << "sphere " << i;
      } else {  // a NaN lane: never hit, never crossed
        EXPECT_EQ(t[k], kInfinity);
        EXPECT_EQ(n[k], 0);
      }
      any = any || t[k] < kInfinity;
    }
    EXPECT_EQ(kernel::intersect_any(quads[j], ray, t_min, t_max), any);
    Real t_lane = -1;
    const int lane = kernel::intersect_nearest(quads[j], ray, t_min, t_far, t_lane);
    if (lane >= 0) {
      nearest = int(j) * kernel::kSphereQuadWidth + lane;
      t_far = t_lane;
    } else {
      EXPECT_EQ(t_lane, -1);  // left alone
    }
  }
  Real scalar_far = t_max;
  EXPECT_EQ(nearest, scalar_nearest(spheres, ray, t_min, scalar_far));
  EXPECT_EQ(bits(t_far), bits(scalar_far));
}

TEST(SphereQuad, RandomSpheresAndRaysAtManyScalesMatchTheScalarTestBitForBit) {
  test::Random rng(11);
  for (int scene = 0; scene < 200; ++scene) {
    const Real scale = rng.log_uniform(1e-3, 1e4);
    const Vec3 offset = scene % 4 == 3 ? rng.point(-1e5, 1e5) : Vec3(0);
    std::vector<kernel::Sphere> spheres(std::size_t(1 + rng.below(9)));
    for (kernel::Sphere& s : spheres) {
      s.center = offset + rng.point(-1, 1) * scale;
      s.radius = rng.uniform(0.05, 0.8) * scale;
    }
    for (int r = 0; r < 50; ++r) {
      Ray ray;
      // From outside, from inside a sphere (its centre or near it), towards a centre, grazing.
      const kernel::Sphere& s = spheres[std::size_t(rng.below(int(spheres.size())))];
      switch (r % 4) {
        case 0: ray.origin = offset + rng.point(-3, 3) * scale; ray.direction = rng.direction(); break;
        case 1: ray.origin = s.center + rng.direction() * (s.radius * rng.uniform(0, 0.99)); ray.direction = rng.direction(); break;
        case 2: ray.origin = offset + rng.point(-3, 3) * scale; ray.direction = normalize(s.center - ray.origin); break;
        default: {  // at the silhouette: aimed at a point on the surface, perpendicular to its normal
          const Vec3 n = rng.direction();
          ray.origin = s.center + n * s.radius + normalize(cross(n, rng.direction())) * (-2 * scale);
          ray.direction = normalize(s.center + n * s.radius - ray.origin);
        }
      }
      expect_same(spheres, ray, 0, kInfinity);
      expect_same(spheres, ray, 1e-9 * scale, rng.uniform(0, 4) * scale);
    }
  }
}

TEST(SphereQuad, IntervalEndsOnTheRootsAndAxisParallelRaysMatchBitForBit) {
  std::vector<kernel::Sphere> spheres;
  for (int i = 0; i < 7; ++i) spheres.push_back({Vec3(0, 0, -3.0 * (i + 1)), 1.0 + 0.1 * i, std::uint32_t(i)});
  for (const Vec3 d : {Vec3(0, 0, -1), Vec3(0.0, -0.0, -1), Vec3(-0.0, 0.0, 1), Vec3(1, 0, 0), Vec3(0, -0.0, 1)}) {
    const Ray ray{{0, 0, 0}, d};
    for (const kernel::Sphere& s : spheres) {
      const Real t0 = -s.center.z - s.radius, t1 = -s.center.z + s.radius;  // near and far root
      for (const Real t_min : {Real(0), t0, t1, std::nextafter(t0, Real(0))})
        for (const Real t_max : {kInfinity, t0, t1, std::nextafter(t1, kInfinity)}) expect_same(spheres, ray, t_min, t_max);
    }
  }
  // Through two touching spheres' common point, and along a sphere's tangent.
  const std::vector<kernel::Sphere> touching{{Vec3(-1, 0, -5), 1, 0}, {Vec3(1, 0, -5), 1, 1}};
  expect_same(touching, Ray{{0, 0, 0}, {0, 0, -1}}, 0, kInfinity);
  expect_same(touching, Ray{{-3, 1, -5}, {1, 0, 0}}, 0, kInfinity);
}

TEST(SphereQuad, EqualRootsGoToTheLowestSphereAsInTheScalarLoop) {
  // The same sphere four times, and twice in the next quad: every lane has the same t.
  const std::vector<kernel::Sphere> same(6, kernel::Sphere{Vec3(0, 0, -5), 1, 0});
  const std::vector<kernel::SphereQuad> quads = kernel::sphere_quads(same.data(), 6);
  Real t = kInfinity;
  EXPECT_EQ(kernel::intersect_nearest(quads[0], Ray{{0, 0, 0}, {0, 0, -1}}, 0, t, t), 0);
  EXPECT_EQ(t, 4);
  EXPECT_EQ(kernel::intersect_nearest(quads[1], Ray{{0, 0, 0}, {0, 0, -1}}, 0, t, t), -1);  // not nearer
  expect_same(same, Ray{{0, 0, 0}, {0, 0, -1}}, 0, kInfinity);
}

// A scene of spheres only (one leaf) with transparent and opaque materials: closest_hit and
// transmittance through the quads against the same scene without them (the scalar loops).
TEST(SphereQuad, OneLeafSceneQueriesEqualTheSpheresOneByOne) {
  test::Random rng(5);
  for (int count = 1; count <= 9; ++count) {
    Scene scene;
    for (int i = 0; i < count; ++i) {
      Material m = material_with_color(Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
      if (i % 3 != 2) {
        m.transparency = rng.uniform(0.2, 0.9);
        m.filter = i % 2 == 0;
      }
      scene.add(Sphere(rng.point(-2, 2), rng.uniform(0.2, 1), m));
    }
    const RenderScene rs = compile(scene);
    SceneView quads = rs.view();
    ASSERT_TRUE(is_sphere_leaf(quads.accel)) << count << " spheres";
    ASSERT_NE(quads.accel.sphere_quads, nullptr);
    SceneView one_by_one = quads;
    one_by_one.accel.sphere_quads = nullptr;
    for (int r = 0; r < 400; ++r) {
      const Ray ray{rng.point(-4, 4), rng.direction()};
      const Hit a = closest_hit(quads, ray, 0, kInfinity), b = closest_hit(one_by_one, ray, 0, kInfinity);
      EXPECT_EQ(bits(a.t), bits(b.t));
      EXPECT_EQ(a.index, b.index);
      EXPECT_EQ(a.kind, b.kind);
      const Real distance = rng.uniform(0, 8);
      const Vec3 ta = transmittance(quads, ray, distance), tb = transmittance(one_by_one, ray, distance);
      EXPECT_EQ(bits(ta.x), bits(tb.x));
      EXPECT_EQ(bits(ta.y), bits(tb.y));
      EXPECT_EQ(bits(ta.z), bits(tb.z));
      EXPECT_EQ(sphere_leaf_occluded(quads.accel, ray, 0, distance), sphere_leaf_occluded(one_by_one.accel, ray, 0, distance));
    }
  }
}

}  // namespace
}  // namespace strahl::sphere_quad_test
