// Transforms on solids (scale, rotate, translate; geometry/placement.h): an unevenly scaled,
// rotated and moved sphere is the ellipsoid of the closed form (hit t and normal); a uniformly
// scaled one stays an analytic sphere; a CSG node's transform equals the same transform on each
// operand; a rotated box agrees with the ray rotated the other way; every accelerator agrees.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "strahl/geometry/solid.h"
#include "strahl/math/transform.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/scene_file.h"
#include "test_random.h"

namespace strahl::placement_test {
namespace {

RenderScene scene_of(const std::string& objects, AccelKind accel = AccelKind::Bvh) {
  Scene s = parse_scene(
      "camera: {position: [0, 1, 6], look_at: [0, 0, 0], fov: 40}\nrender: {width: 32, height: 24}\n"
      "lights:\n  - {type: point, position: [2, 3, 2]}\nobjects:\n" +
          objects,
      "placed.yaml", ".");
  s.settings.accel = accel;
  return compile(s);
}

std::vector<Ray> rays_towards_middle(std::uint64_t seed, int n, const Vec3& middle, Real spread) {
  test::Random rng(seed);
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    const Vec3 o = middle + rng.direction() * 6;
    rays.push_back(Ray{o, normalize(middle + rng.point(-spread, spread) - o)});
  }
  return rays;
}

TEST(Placement, EllipsoidMatchesTheClosedForm) {
  // Unit sphere at c = (0.3, 0, 0) scaled by (2, 1, 0.5), rotated 30° about z, moved by (1, 2, 3):
  // world p lies on it where |S⁻¹·R⁻¹·(p − T) − c| = 1, a quadratic in t along the ray.
  const RenderScene rs = scene_of(
      "  - {type: sphere, center: [0.3, 0, 0], radius: 1, scale: [2, 1, 0.5], rotate: [0, 0, 30], translate: [1, 2, "
      "3]}\n");
  ASSERT_TRUE(rs.spheres.empty());
  ASSERT_EQ(rs.solids.size(), 1u);
  ASSERT_EQ(rs.solids[0].kind, kernel::SolidKind::Placed);
  const Mat3 r_inv = Mat3::rotation(2, -30);
  const Vec3 s_inv(0.5, 1, 2), T(1, 2, 3), c(0.3, 0, 0);
  const SceneView v = rs.view();
  int hits = 0;
  for (const Ray& ray : rays_towards_middle(1, 5000, T, 2.5)) {
    const Vec3 o = r_inv * (ray.origin - T) * s_inv - c, d = r_inv * ray.direction * s_inv;
    const Real a = dot(d, d), b = 2 * dot(o, d), k = dot(o, o) - 1;
    const Real disc = b * b - 4 * a * k;
    const Hit hit = closest_hit(v, ray, 0, kInfinity);
    if (disc < 1e-9) {  // misses (or grazes: left out)
      if (disc < -1e-9) {
        ASSERT_FALSE(hit.found());
      }
      continue;
    }
    const Real t = (-b - std::sqrt(disc)) / (2 * a);
    ASSERT_TRUE(hit.found());
    ASSERT_NEAR(hit.t, t, 1e-12 * (1 + t));
    // Normal: the gradient of |S⁻¹R⁻¹(p − T) − c|², (S⁻¹R⁻¹)ᵀ·(q − c) with q the object point.
    const Vec3 q = r_inv * (ray.at(hit.t) - T) * s_inv - c;
    const Vec3 n = normalize(r_inv.transposed() * (q * s_inv));
    const SurfacePoint sp = surface_at(v, ray, hit);
    ASSERT_NEAR(length(sp.normal - n), 0, 1e-9);
    ++hits;
  }
  EXPECT_GT(hits, 800);
}

TEST(Placement, UniformScaleKeepsASphere) {
  const RenderScene rs =
      scene_of("  - {type: sphere, center: [1, 0, 0], radius: 0.5, scale: -2, rotate: [0, 90, 0], translate: [0, 1, 0]}\n");
  ASSERT_EQ(rs.spheres.size(), 1u);
  EXPECT_TRUE(rs.solids.empty());
  EXPECT_DOUBLE_EQ(rs.spheres[0].radius, 1);
  // (1, 0, 0) scaled by −2 → (−2, 0, 0), turned 90° about y → (0, 0, 2), moved → (0, 1, 2).
  EXPECT_NEAR(rs.spheres[0].center.x, 0, 1e-15);
  EXPECT_NEAR(rs.spheres[0].center.y, 1, 1e-15);
  EXPECT_NEAR(rs.spheres[0].center.z, 2, 1e-15);
}

TEST(Placement, RotatedBoxIsTheRayTurnedBack) {
  const RenderScene rs = scene_of("  - {type: box, corners: [[-1, -0.5, -0.25], [1, 0.5, 0.25]], rotate: [20, 35, -50]}\n"
                                  "  - {type: box, corners: [[-1, -0.5, -0.25], [1, 0.5, 0.25]]}\n");
  const Mat3 back = (Mat3::rotation(2, -50) * Mat3::rotation(1, 35) * Mat3::rotation(0, 20)).inverse();
  const kernel::SolidArrays a = rs.shapes();
  int hits = 0;
  for (const Ray& ray : rays_towards_middle(2, 5000, Vec3(0), 1)) {
    const Ray turned{back * ray.origin, back * ray.direction};
    const kernel::SolidCrossing p = kernel::intersect(a, rs.solids[0], ray, 0, kInfinity);
    const kernel::SolidCrossing q = kernel::intersect(a, rs.solids[1], turned, 0, kInfinity);
    ASSERT_EQ(p.t == kInfinity, q.t == kInfinity);
    if (p.t == kInfinity) continue;
    ASSERT_NEAR(p.t, q.t, 1e-12);
    ++hits;
    ASSERT_EQ(p.part, q.part);
    const Vec3 n = kernel::normal_at(a, rs.solids[0], int(p.part), ray.at(p.t));
    const Vec3 m = kernel::normal_at(a, rs.solids[1], int(q.part), turned.at(q.t));
    ASSERT_NEAR(length(back * n - m), 0, 1e-12);
  }
  EXPECT_GT(hits, 1000);
}

TEST(Placement, CsgNodeTransformIsEachOperandsTransform) {
  const RenderScene rs = scene_of(
      "  - type: difference\n    rotate: [0, 30, 0]\n    translate: [1, 0.5, 0]\n    objects:\n"
      "      - {type: box, corners: [[-1, -1, -1], [1, 1, 1]], scale: [1, 2, 1]}\n"
      "      - {type: sphere, center: [0, 0, 0], radius: 1.2, scale: [1.5, 1, 1]}\n"
      "  - type: difference\n    objects:\n"
      "      - {type: box, corners: [[-1, -1, -1], [1, 1, 1]], scale: [1, 2, 1], rotate: [0, 30, 0], translate: [1, "
      "0.5, 0]}\n"
      "      - {type: sphere, center: [0, 0, 0], radius: 1.2, scale: [1.5, 1, 1], rotate: [0, 30, 0], translate: [1, "
      "0.5, 0]}\n");
  const kernel::SolidArrays a = rs.shapes();
  int crossings = 0;
  for (const Ray& ray : rays_towards_middle(3, 3000, Vec3(1, 0.5, 0), 1.5)) {
    std::vector<kernel::SolidCrossing> x, y;
    kernel::for_each_solid_crossing(a, rs.solids[0], ray, 0, kInfinity, [&](const kernel::SolidCrossing& c) {
      x.push_back(c);
      return false;
    });
    kernel::for_each_solid_crossing(a, rs.solids[1], ray, 0, kInfinity, [&](const kernel::SolidCrossing& c) {
      y.push_back(c);
      return false;
    });
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
      ASSERT_NEAR(x[k].t, y[k].t, 1e-12);
      ASSERT_EQ(x[k].part, y[k].part);
    }
    crossings += int(x.size());
  }
  EXPECT_GT(crossings, 1000);
}

TEST(Placement, AcceleratorsAgree) {
  const std::string objects =
      "  - {type: sphere, center: [0, 0, 0], radius: 1, scale: [2, 0.5, 1], rotate: [10, 20, 30]}\n"
      "  - {type: torus, major_radius: 0.6, minor_radius: 0.2, rotate: [90, 0, 0], translate: [1, 1, 0], scale: [1, 1.5, 1]}\n"
      "  - {type: cylinder, base: [0, 0, 0], cap: [0, 1, 0], radius: 0.3, scale: [1, 1, 3], translate: [-1, 0, 1]}\n"
      "  - {type: quadric, coefficients: [1, 0, 1, 0, 0, 0, 0, 0, 0, -0.04], rotate: [0, 0, 45]}\n"
      "  - {type: intersection, rotate: [0, 45, 0], objects: [{type: box, corners: [[-1, -1, -1], [1, 1, 1]]}, "
      "{type: sphere, center: [0, 0, 0], radius: 1.3}]}\n"
      "  - {type: sphere, center: [0, 2, 0], radius: 0.5}\n";
  std::vector<Hit> want;
  const std::vector<Ray> rays = rays_towards_middle(4, 4000, Vec3(0), 2);
  for (AccelKind k : {AccelKind::Naive, AccelKind::Bvh, AccelKind::KdTree, AccelKind::Octree}) {
    const RenderScene rs = scene_of(objects, k);
    const SceneView v = rs.view();
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Hit h = closest_hit(v, rays[i], 0, kInfinity);
      if (want.size() < rays.size()) {
        want.push_back(h);
        continue;
      }
      ASSERT_EQ(h.t, want[i].t) << accel_name(k) << " ray " << i;
      ASSERT_EQ(h.index, want[i].index) << accel_name(k) << " ray " << i;
    }
  }
}

TEST(Placement, SingularScaleIsRefused) {
  try {
    scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], scale: [1, 0, 1]}\n");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "placed.yaml:6:57: scale must not be zero");
  }
}

}  // namespace
}  // namespace strahl::placement_test
