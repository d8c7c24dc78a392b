// Ray–plane intersection (the plane N·p = d of the lecture's Plane(normal, d, colour)).

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/surface_point.h"
#include "test_helpers.h"

namespace strahl::plane_test {
namespace {

kernel::Plane make_plane(const Vec3& normal, Real d) {
  Scene s;
  s.add(Plane(normal, d, Vec3(1)));
  return compile(s).planes.at(0);
}

TEST(Plane, FortyFiveDegreeHit) {
  const kernel::Plane p = make_plane({0, 1, 0}, 0);
  const Ray ray{{0, 1, 0}, normalize(Vec3(1, -1, 0))};
  const Real t = kernel::intersect(p, ray, 0, kInfinity);
  EXPECT_NEAR(t, std::sqrt(2.0), 1e-15);
  EXPECT_VEC_NEAR(ray.at(t), Vec3(1, 0, 0), 1e-15);
}

TEST(Plane, OffsetPlaneSatisfiesNDotPEqualsD) {
  // N = (0, 0, 1), d = −3: the plane z = −3.
  const kernel::Plane p = make_plane({0, 0, 1}, -3);
  const Ray ray{{0.5, -0.25, 1}, normalize(Vec3(0.1, 0.2, -1))};
  const Real t = kernel::intersect(p, ray, 0, kInfinity);
  const Real expected = 4 / std::fabs(ray.direction.z);
  EXPECT_NEAR(t, expected, 1e-14);
  EXPECT_NEAR(ray.at(t).z, -3, 1e-14);
}

TEST(Plane, ObliquePlaneAndNormal) {
  // Unnormalised N = (1, 1, 1), d = 3: the plane x + y + z = 3, stored as N/√3 and d/√3 = √3;
  // hit from the origin along the diagonal at t = √3.
  Scene s;
  s.add(Plane(Vec3(1, 1, 1), 3, Vec3(1)));
  const RenderScene rs = compile(s);
  const kernel::Plane& p = rs.planes.at(0);
  EXPECT_VEC_NEAR(p.normal, normalize(Vec3(1, 1, 1)), 1e-15);
  EXPECT_NEAR(p.distance, std::sqrt(3.0), 1e-15);
  const Ray ray{{0, 0, 0}, normalize(Vec3(1, 1, 1))};
  const Real t = kernel::intersect(p, ray, 0, kInfinity);
  EXPECT_NEAR(t, std::sqrt(3.0), 1e-14);
  EXPECT_VEC_NEAR(ray.at(t), Vec3(1, 1, 1), 1e-14);
  const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_EQ(hit.kind, ShapeKind::Plane);
  const SurfacePoint sp = surface_at(rs.view(), ray, hit);
  EXPECT_VEC_NEAR(sp.normal, normalize(Vec3(1, 1, 1)), 1e-15);
}

TEST(Plane, LectureFloorNormalisesNormalAndDistance) {
  const kernel::Plane p = make_plane({0, 2, 0}, 4);  // 2y = 4: y = 2
  EXPECT_VEC_NEAR(p.normal, Vec3(0, 1, 0), 1e-15);
  EXPECT_DOUBLE_EQ(p.distance, 2);
  EXPECT_NEAR(kernel::intersect(p, Ray{{3, 5, -1}, {0, -1, 0}}, 0, kInfinity), 3, 1e-15);
}

TEST(Plane, HitFromBehindTheNormal) {
  const kernel::Plane p = make_plane({0, 1, 0}, 0);
  EXPECT_NEAR(kernel::intersect(p, Ray{{0, -2, 0}, {0, 1, 0}}, 0, kInfinity), 2, 1e-15);
}

TEST(Plane, ParallelRaysMiss) {
  const kernel::Plane p = make_plane({0, 1, 0}, 0);
  EXPECT_EQ(kernel::intersect(p, Ray{{0, 1, 0}, {1, 0, 0}}, 0, kInfinity), kInfinity);
  EXPECT_EQ(kernel::intersect(p, Ray{{0, -1, 0}, normalize(Vec3(1, 0, 1))}, 0, kInfinity), kInfinity);
  EXPECT_EQ(kernel::intersect(p, Ray{{0, 0, 0}, {0, 0, -1}}, 0, kInfinity), kInfinity);  // lying in the plane
}

TEST(Plane, PlaneBehindTheRayIsMissed) {
  const kernel::Plane p = make_plane({0, 1, 0}, 0);
  EXPECT_EQ(kernel::intersect(p, Ray{{0, 1, 0}, normalize(Vec3(1, 1, 0))}, 0, kInfinity), kInfinity);
}

TEST(Plane, IntervalIsOpenAndRespected) {
  const kernel::Plane p = make_plane({0, 1, 0}, 0);
  const Ray ray{{0, 2, 0}, {0, -1, 0}};  // hits at t = 2
  EXPECT_DOUBLE_EQ(kernel::intersect(p, ray, 0, kInfinity), 2);
  EXPECT_DOUBLE_EQ(kernel::intersect(p, ray, 1.999, 2.001), 2);
  EXPECT_EQ(kernel::intersect(p, ray, 0, 2), kInfinity);
  EXPECT_EQ(kernel::intersect(p, ray, 2, 10), kInfinity);
  EXPECT_EQ(kernel::intersect(p, ray, 2.5, 10), kInfinity);
  EXPECT_EQ(kernel::intersect(p, ray, 0, 1.5), kInfinity);
}

TEST(Plane, TextureFrameIsOrthonormalAndInThePlane) {
  for (const Vec3& n : {Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(1, 2, -3), Vec3(-0.95, 0.1, 0.2)}) {
    const kernel::Plane p = make_plane(n, 1);
    EXPECT_NEAR(length(p.tangent), 1, 1e-14);
    EXPECT_NEAR(length(p.bitangent), 1, 1e-14);
    EXPECT_NEAR(dot(p.tangent, p.bitangent), 0, 1e-14);
    EXPECT_NEAR(dot(p.tangent, p.normal), 0, 1e-14);
    EXPECT_NEAR(dot(p.bitangent, p.normal), 0, 1e-14);
  }
}

TEST(Plane, ZeroOrNonFiniteNormalIsRejected) {
  for (const Vec3& n : {Vec3(0, 0, 0), Vec3(std::nan(""), 1, 0)}) {
    Scene s;
    s.add(Plane(n, 0, Vec3(1)));
    EXPECT_THROW(compile(s), Error);
  }
}

TEST(Plane, NearerSphereOccludesPlane) {
  Scene s;
  s.add(Plane({0, 1, 0}, 0, Vec3(1)));
  s.add(Sphere({0, 1, 0}, 0.5, Vec3(1)));
  const RenderScene rs = compile(s);
  const Ray ray{{0, 3, 0}, {0, -1, 0}};
  const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_EQ(hit.kind, ShapeKind::Sphere);
  EXPECT_DOUBLE_EQ(hit.t, 1.5);
  const Hit past = closest_hit(rs.view(), ray, 2.6, kInfinity);  // beyond the sphere
  ASSERT_TRUE(past.found());
  EXPECT_EQ(past.kind, ShapeKind::Plane);
  EXPECT_DOUBLE_EQ(past.t, 3);
}

}  // namespace
}  // namespace strahl::plane_test
