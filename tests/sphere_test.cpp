// Ray–sphere intersection against hand-computed roots: nearest positive t, the far root from
// inside, tangent and missing rays, the open interval (t_min, t_max), and the outward normal.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/surface_point.h"
#include "test_helpers.h"

namespace strahl::sphere_test {
namespace {

// The kernel sphere exactly as compile() produces it from the C++ API.
kernel::Sphere make_sphere(const Vec3& center, Real radius) {
  Scene s;
  s.add(Sphere(center, radius, Vec3(1)));
  return compile(s).spheres.at(0);
}

const Vec3 kDown(0, 0, -1);

TEST(Sphere, HeadOnHitIsNearRoot) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);
  const Ray ray{{0, 0, 0}, kDown};
  const Real t = kernel::intersect(s, ray, 0, kInfinity);
  EXPECT_DOUBLE_EQ(t, 4);
  EXPECT_VEC_NEAR(ray.at(t), Vec3(0, 0, -4), 1e-15);
  EXPECT_VEC_NEAR(kernel::normal_at(s, ray.at(t)), Vec3(0, 0, 1), 1e-15);
}

TEST(Sphere, OffCentreHit) {
  // x = 0.6: half chord √(1 − 0.36) = 0.8, so t = 5 − 0.8 and the normal is (0.6, 0, 0.8).
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);
  const Ray ray{{0.6, 0, 0}, kDown};
  const Real t = kernel::intersect(s, ray, 0, kInfinity);
  EXPECT_NEAR(t, 4.2, 1e-14);
  EXPECT_VEC_NEAR(ray.at(t), Vec3(0.6, 0, -4.2), 1e-14);
  EXPECT_VEC_NEAR(kernel::normal_at(s, ray.at(t)), Vec3(0.6, 0, 0.8), 1e-14);
}

TEST(Sphere, ObliqueRayAgainstQuadraticFormula) {
  // The lecture's A t² + B t + C = 0, solved here in long double for reference.
  const Vec3 c(1, -2, -7), o(0.3, 0.1, 0.2);
  const Real r = 2.5;
  const Vec3 d = normalize(Vec3(0.2, -0.3, -1));
  const kernel::Sphere s = make_sphere(c, r);
  const Ray ray{o, d};
  const long double A = dot(d, d), B = 2.0L * dot(d, o - c), C = dot(o - c, o - c) - r * r;
  const long double t_ref = (-B - std::sqrt(B * B - 4 * A * C)) / (2 * A);
  ASSERT_GT(t_ref, 0);
  const Real t = kernel::intersect(s, ray, 0, kInfinity);
  EXPECT_NEAR(t, double(t_ref), 1e-12);
  EXPECT_NEAR(length(ray.at(t) - c), r, 1e-12);
  EXPECT_NEAR(length(kernel::normal_at(s, ray.at(t))), 1, 1e-12);
}

TEST(Sphere, RayFromCentreHitsFarSideAtRadius) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1.5);
  const Ray ray{{0, 0, -5}, kDown};
  const Real t = kernel::intersect(s, ray, 0, kInfinity);
  EXPECT_DOUBLE_EQ(t, 1.5);
  // The normal stays the outward one (p − c)/R, pointing away from the ray's origin.
  EXPECT_VEC_NEAR(kernel::normal_at(s, ray.at(t)), Vec3(0, 0, -1), 1e-15);
}

TEST(Sphere, RayFromInsideOffCentreTakesTheFarRoot) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);
  // From z = −4.5 towards +z the surface is at z = −4 (0.5 ahead); the other root lies behind.
  EXPECT_NEAR(kernel::intersect(s, Ray{{0, 0, -4.5}, {0, 0, 1}}, 0, kInfinity), 0.5, 1e-15);
  // Towards −z the far side z = −6 is 1.5 ahead.
  EXPECT_NEAR(kernel::intersect(s, Ray{{0, 0, -4.5}, kDown}, 0, kInfinity), 1.5, 1e-15);
}

TEST(Sphere, SphereBehindTheRayIsMissed) {
  const kernel::Sphere s = make_sphere({0, 0, 5}, 1);
  EXPECT_EQ(kernel::intersect(s, Ray{{0, 0, 0}, kDown}, 0, kInfinity), kInfinity);
}

TEST(Sphere, MissingRaysReturnInfinity) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);
  EXPECT_EQ(kernel::intersect(s, Ray{{1.5, 0, 0}, kDown}, 0, kInfinity), kInfinity);
  EXPECT_EQ(kernel::intersect(s, Ray{{0, 0, 0}, normalize(Vec3(0, 1, -2))}, 0, kInfinity), kInfinity);
}

TEST(Sphere, GrazingRays) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);
  // Just outside the silhouette: no hit. Just inside: a hit at the touching point, t ≈ 5.
  EXPECT_EQ(kernel::intersect(s, Ray{{1 + 1e-9, 0, 0}, kDown}, 0, kInfinity), kInfinity);
  const Real t = kernel::intersect(s, Ray{{1 - 1e-9, 0, 0}, kDown}, 0, kInfinity);
  EXPECT_NEAR(t, 5, 1e-3);
  // The ray along y = 1 touches the sphere only at (0, 1, −5): if reported, it is there.
  const Real tangent = kernel::intersect(s, Ray{{0, 1, 0}, kDown}, 0, kInfinity);
  if (tangent != kInfinity) {
    EXPECT_NEAR(tangent, 5, 1e-6);
  }
}

TEST(Sphere, IntervalIsOpenAndRespected) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);  // roots at 4 and 6
  const Ray ray{{0, 0, 0}, kDown};
  EXPECT_DOUBLE_EQ(kernel::intersect(s, ray, 0, 100), 4);
  EXPECT_DOUBLE_EQ(kernel::intersect(s, ray, 4.5, 100), 6);  // near root excluded: far root
  EXPECT_DOUBLE_EQ(kernel::intersect(s, ray, 4, 100), 6);    // t_min itself is excluded
  EXPECT_EQ(kernel::intersect(s, ray, 0, 3.9), kInfinity);   // both roots beyond t_max
  EXPECT_EQ(kernel::intersect(s, ray, 0, 4), kInfinity);     // t_max itself is excluded
  EXPECT_DOUBLE_EQ(kernel::intersect(s, ray, 0, 5), 4);
  EXPECT_EQ(kernel::intersect(s, ray, 6.1, 100), kInfinity);
  EXPECT_EQ(kernel::intersect(s, ray, 4.2, 5.9), kInfinity);  // between the roots
}

TEST(Sphere, SmallSphereFarAwayIsHitAccurately) {
  // B² − 4AC cancels catastrophically here; the result must still be accurate.
  const kernel::Sphere s = make_sphere({0, 0, -1e4}, 1e-3);
  const Real t = kernel::intersect(s, Ray{{0, 0, 0}, kDown}, 0, kInfinity);
  EXPECT_NEAR(t, 1e4 - 1e-3, 1e-9);
  const Real t_off = kernel::intersect(s, Ray{{0.6e-3, 0, 0}, kDown}, 0, kInfinity);
  EXPECT_NEAR(t_off, 1e4 - 0.8e-3, 1e-9);
}

TEST(Sphere, ShadowCrossingsCountSurfacesInSegment) {
  const kernel::Sphere s = make_sphere({0, 0, -5}, 1);
  const Ray ray{{0, 0, 0}, kDown};
  EXPECT_EQ(kernel::crossings(s, ray, 0, 10), 2);
  EXPECT_EQ(kernel::crossings(s, ray, 0, 5), 1);
  EXPECT_EQ(kernel::crossings(s, ray, 0, 3), 0);
  EXPECT_EQ(kernel::crossings(s, Ray{{0, 0, -5}, kDown}, 0, 10), 1);  // from inside
  EXPECT_EQ(kernel::crossings(s, Ray{{2, 0, 0}, kDown}, 0, 10), 0);
}

TEST(Sphere, ScenePicksTheNearestOfSeveralSpheresAndItsNormal) {
  Scene scene;
  scene.add(Sphere({0, 0, -10}, 1, Vec3(1)));
  scene.add(Sphere({0, 0, -5}, 1, Vec3(1)));
  scene.add(Sphere({0, 0, -20}, 3, Vec3(1)));
  const RenderScene rs = compile(scene);
  const SceneView view = rs.view();
  const Ray ray{{0, 0, 0}, kDown};
  const Hit hit = closest_hit(view, ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_EQ(hit.kind, ShapeKind::Sphere);
  EXPECT_EQ(hit.index, 1u);
  EXPECT_DOUBLE_EQ(hit.t, 4);
  const SurfacePoint sp = surface_at(view, ray, hit);
  EXPECT_VEC_NEAR(sp.p, Vec3(0, 0, -4), 1e-15);
  EXPECT_VEC_NEAR(sp.normal, Vec3(0, 0, 1), 1e-15);
  EXPECT_VEC_NEAR(sp.geometric_normal, Vec3(0, 0, 1), 1e-15);
  // Restricting t_max to before every sphere: nothing.
  EXPECT_FALSE(closest_hit(view, ray, 0, 3.5).found());
  // Starting past the first sphere: the second one's near root at t = 9.
  const Hit later = closest_hit(view, ray, 6.5, kInfinity);
  ASSERT_TRUE(later.found());
  EXPECT_EQ(later.index, 0u);
  EXPECT_DOUBLE_EQ(later.t, 9);
}

TEST(Sphere, InvalidRadiusIsRejectedByCompile) {
  for (Real r : {0.0, -1.0, std::nan("")}) {
    Scene s;
    s.add(Sphere({0, 0, 0}, r, Vec3(1)));
    EXPECT_THROW(compile(s), Error) << "radius " << r;
  }
}

}  // namespace
}  // namespace strahl::sphere_test
