// Ray–triangle intersection (barycentric), and triangle meshes from OBJ files with vertex
// normals interpolated across the face and transformed by the inverse transpose.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/obj_loader.h"
#include "test_helpers.h"

namespace strahl::triangle_test {
namespace {

kernel::Triangle make_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Scene s;
  s.add(Triangle(a, b, c, Vec3(1)));
  return compile(s).triangles.at(0);
}

const Vec3 kDown(0, 0, -1);

// The unit right triangle in the plane z = −2, facing +z.
kernel::Triangle unit_triangle() { return make_triangle({0, 0, -2}, {1, 0, -2}, {0, 1, -2}); }

TEST(Triangle, HitInsideGivesTBarycentricsAndNormal) {
  const kernel::Triangle tri = unit_triangle();
  const kernel::TriangleHit h = kernel::intersect(tri, Ray{{0.25, 0.5, 0}, kDown}, 0, kInfinity);
  EXPECT_DOUBLE_EQ(h.t, 2);
  EXPECT_DOUBLE_EQ(h.b1, 0.25);
  EXPECT_DOUBLE_EQ(h.b2, 0.5);
  EXPECT_VEC_NEAR(kernel::geometric_normal(tri), Vec3(0, 0, 1), 1e-15);
}

TEST(Triangle, ObliqueTriangleAgainstHandComputedValues) {
  // Vertices (1,0,0), (0,2,0), (0,0,3): the plane x + y/2 + z/3 = 1. Along the diagonal from the
  // origin the hit is (6/11)(1,1,1) with b1 = 3/11, b2 = 2/11; the normal is (6,3,2)/7.
  const kernel::Triangle tri = make_triangle({1, 0, 0}, {0, 2, 0}, {0, 0, 3});
  const Ray ray{{0, 0, 0}, normalize(Vec3(1, 1, 1))};
  const kernel::TriangleHit h = kernel::intersect(tri, ray, 0, kInfinity);
  EXPECT_NEAR(h.t, 6.0 / 11.0 * std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(h.b1, 3.0 / 11.0, 1e-15);
  EXPECT_NEAR(h.b2, 2.0 / 11.0, 1e-15);
  EXPECT_VEC_NEAR(ray.at(h.t), Vec3(6.0 / 11, 6.0 / 11, 6.0 / 11), 1e-15);
  EXPECT_VEC_NEAR(kernel::geometric_normal(tri), Vec3(6.0 / 7, 3.0 / 7, 2.0 / 7), 1e-15);
}

TEST(Triangle, WindingDecidesTheGeometricNormal) {
  EXPECT_VEC_NEAR(kernel::geometric_normal(make_triangle({0, 0, -2}, {0, 1, -2}, {1, 0, -2})), Vec3(0, 0, -1), 1e-15);
}

TEST(Triangle, PointsOutsideMiss) {
  const kernel::Triangle tri = unit_triangle();
  for (const Vec3& o : {Vec3(0.6, 0.6, 0), Vec3(-0.01, 0.5, 0), Vec3(0.5, -0.01, 0), Vec3(1.01, 0, 0),
                        Vec3(0, 1.01, 0), Vec3(-0.1, -0.1, 0), Vec3(2, 2, 0)})
    EXPECT_EQ(kernel::intersect(tri, Ray{o, kDown}, 0, kInfinity).t, kInfinity) << o.x << "," << o.y;
}

TEST(Triangle, EdgesJustInsideHitJustOutsideMiss) {
  const kernel::Triangle tri = unit_triangle();
  const Real e = 1e-9;
  // Edge v0–v1 (y = 0), edge v0–v2 (x = 0), hypotenuse x + y = 1.
  EXPECT_NEAR(kernel::intersect(tri, Ray{{0.5, e, 0}, kDown}, 0, kInfinity).t, 2, 1e-12);
  EXPECT_EQ(kernel::intersect(tri, Ray{{0.5, -e, 0}, kDown}, 0, kInfinity).t, kInfinity);
  EXPECT_NEAR(kernel::intersect(tri, Ray{{e, 0.5, 0}, kDown}, 0, kInfinity).t, 2, 1e-12);
  EXPECT_EQ(kernel::intersect(tri, Ray{{-e, 0.5, 0}, kDown}, 0, kInfinity).t, kInfinity);
  EXPECT_NEAR(kernel::intersect(tri, Ray{{0.5 - e, 0.5 - e, 0}, kDown}, 0, kInfinity).t, 2, 1e-12);
  EXPECT_EQ(kernel::intersect(tri, Ray{{0.5 + e, 0.5 + e, 0}, kDown}, 0, kInfinity).t, kInfinity);
}

TEST(Triangle, PointsExactlyOnEdgesAndVerticesHit) {
  const kernel::Triangle tri = unit_triangle();
  for (const Vec3& o : {Vec3(0.5, 0, 0), Vec3(0, 0.5, 0), Vec3(0.5, 0.5, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)})
    EXPECT_DOUBLE_EQ(kernel::intersect(tri, Ray{o, kDown}, 0, kInfinity).t, 2) << o.x << "," << o.y;
}

TEST(Triangle, SharedEdgeOfAQuadHasNoCrack) {
  // Two triangles sharing the diagonal (0,0)–(1,1) of the unit square at z = −1: rays along
  // the diagonal must hit at least one of them.
  Scene s;
  s.add(Triangle({0, 0, -1}, {1, 0, -1}, {1, 1, -1}, Vec3(1)));
  s.add(Triangle({0, 0, -1}, {1, 1, -1}, {0, 1, -1}, Vec3(1)));
  const RenderScene rs = compile(s);
  for (int i = 1; i < 100; ++i) {
    const Real a = i / 100.0 + 0.001 * std::sin(i);  // not only exactly representable points
    const Hit hit = closest_hit(rs.view(), Ray{{a, a, 0}, kDown}, 0, kInfinity);
    EXPECT_TRUE(hit.found()) << "ray at (" << a << ", " << a << ")";
  }
}

TEST(Triangle, ParallelRaysMiss) {
  const kernel::Triangle tri = unit_triangle();
  EXPECT_EQ(kernel::intersect(tri, Ray{{-1, 0.25, -2}, {1, 0, 0}}, 0, kInfinity).t, kInfinity);  // in its plane
  EXPECT_EQ(kernel::intersect(tri, Ray{{-1, 0.25, 0}, {1, 0, 0}}, 0, kInfinity).t, kInfinity);
}

TEST(Triangle, BackFaceIsHitToo) {
  const kernel::Triangle tri = unit_triangle();
  EXPECT_DOUBLE_EQ(kernel::intersect(tri, Ray{{0.25, 0.25, -4}, {0, 0, 1}}, 0, kInfinity).t, 2);
}

TEST(Triangle, TriangleBehindTheRayIsMissed) {
  const kernel::Triangle tri = unit_triangle();
  EXPECT_EQ(kernel::intersect(tri, Ray{{0.25, 0.25, 0}, {0, 0, 1}}, 0, kInfinity).t, kInfinity);
}

TEST(Triangle, IntervalIsOpenAndRespected) {
  const kernel::Triangle tri = unit_triangle();
  const Ray ray{{0.25, 0.25, 0}, kDown};
  EXPECT_DOUBLE_EQ(kernel::intersect(tri, ray, 1.5, 2.5).t, 2);
  EXPECT_EQ(kernel::intersect(tri, ray, 0, 2).t, kInfinity);
  EXPECT_EQ(kernel::intersect(tri, ray, 2, 10).t, kInfinity);
  EXPECT_EQ(kernel::intersect(tri, ray, 0, 1.9).t, kInfinity);
  EXPECT_EQ(kernel::intersect(tri, ray, 2.1, 10).t, kInfinity);
}

TEST(Triangle, DegenerateTriangleIsRejected) {
  Scene s;
  s.add(Triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, Vec3(1)));
  EXPECT_THROW(compile(s), Error);
}

TEST(Triangle, SceneTriangleIsFoundAndShadedWithItsNormal) {
  Scene s;
  s.add(Triangle({0, 0, -2}, {1, 0, -2}, {0, 1, -2}, Vec3(1)));
  const RenderScene rs = compile(s);
  const Ray ray{{0.25, 0.25, 0}, kDown};
  const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_EQ(hit.kind, ShapeKind::Triangle);
  EXPECT_DOUBLE_EQ(hit.t, 2);
  const SurfacePoint sp = surface_at(rs.view(), ray, hit);
  EXPECT_VEC_NEAR(sp.p, Vec3(0.25, 0.25, -2), 1e-15);
  EXPECT_VEC_NEAR(sp.normal, Vec3(0, 0, 1), 1e-15);
  EXPECT_FALSE(closest_hit(rs.view(), Ray{{0.75, 0.75, 0}, kDown}, 0, kInfinity).found());
}

// ---- meshes from OBJ files ----

class MeshTest : public ::testing::Test {
 protected:
  fs::path write_obj(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    test::write_text(p, text);
    return p;
  }
  test::TempDir dir_;
};

const char* kNormalTriangleObj =
    "# one triangle with a different normal at each vertex\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    "vn 0 0 1\nvn 1 0 0\nvn 0 1 0\n"
    "f 1//1 2//2 3//3\n";

TEST_F(MeshTest, ObjLoaderReadsPositionsNormalsAndFaces) {
  const MeshData data = load_obj(write_obj("tri.obj", kNormalTriangleObj));
  ASSERT_EQ(data.positions.size(), 3u);
  ASSERT_EQ(data.normals.size(), 3u);
  ASSERT_EQ(data.faces.size(), 1u);
  EXPECT_EQ(data.positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(data.normals[2], Vec3(0, 1, 0));
  EXPECT_EQ(data.faces[0].v[0], 0u);
  EXPECT_EQ(data.faces[0].v[2], 2u);
  EXPECT_EQ(data.faces[0].n[1], 1);
}

TEST_F(MeshTest, QuadFacesAreTriangulated) {
  const MeshData data = load_obj(write_obj("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  EXPECT_EQ(data.faces.size(), 2u);
  Scene s;
  s.add(Mesh(data, Material{}));
  const RenderScene rs = compile(s);
  EXPECT_EQ(rs.triangles.size(), 2u);
  // Both halves of the square are there.
  EXPECT_TRUE(closest_hit(rs.view(), Ray{{0.8, 0.2, 1}, kDown}, 0, kInfinity).found());
  EXPECT_TRUE(closest_hit(rs.view(), Ray{{0.2, 0.8, 1}, kDown}, 0, kInfinity).found());
  EXPECT_FALSE(closest_hit(rs.view(), Ray{{1.2, 0.8, 1}, kDown}, 0, kInfinity).found());
}

TEST_F(MeshTest, VertexNormalsAreInterpolatedBarycentrically) {
  Scene s;
  s.add(Mesh(load_obj(write_obj("tri.obj", kNormalTriangleObj)), Material{}));
  const RenderScene rs = compile(s);
  struct Case { Real x, y; Vec3 normal; };
  // n = (1 − b1 − b2)·(0,0,1) + b1·(1,0,0) + b2·(0,1,0), normalised; here b1 = x, b2 = y.
  const Case cases[] = {
      {0.25, 0.25, normalize(Vec3(0.25, 0.25, 0.5))},
      {0.5, 0.25, normalize(Vec3(0.5, 0.25, 0.25))},
      {0.1, 0.7, normalize(Vec3(0.1, 0.7, 0.2))},
  };
  for (const Case& c : cases) {
    const Ray ray{{c.x, c.y, 1}, kDown};
    const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
    ASSERT_TRUE(hit.found());
    EXPECT_DOUBLE_EQ(hit.t, 1);
    const SurfacePoint sp = surface_at(rs.view(), ray, hit);
    EXPECT_VEC_NEAR(sp.normal, c.normal, 1e-14) << "at " << c.x << "," << c.y;
    EXPECT_VEC_NEAR(sp.geometric_normal, Vec3(0, 0, 1), 1e-15);
  }
}

TEST_F(MeshTest, TransformMovesVerticesAndNormalsUseInverseTranspose) {
  // Vertex 2's normal (1,0,1) under scale (2,1,1) becomes M^−T·n = (0.5,0,1) ∝ (1,0,2), not M·n ∝ (2,0,1).
  const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 1 0 1\nvn 0 1 0\nf 1//1 2//2 3//3\n";
  Transform t;
  t.scale = {2, 1, 1};
  t.translate = {0, 0, -3};
  Scene s;
  s.add(Mesh(load_obj(write_obj("tri.obj", obj)), Material{}, t));
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.triangles.size(), 1u);
  EXPECT_VEC_NEAR(rs.triangles[0].v0, Vec3(0, 0, -3), 1e-15);
  EXPECT_VEC_NEAR(rs.triangles[0].v1, Vec3(2, 0, -3), 1e-15);
  EXPECT_VEC_NEAR(rs.triangles[0].v2, Vec3(0, 1, -3), 1e-15);
  // At (1, 0.25): b1 = 0.5, b2 = 0.25.
  const Ray ray{{1, 0.25, 0}, kDown};
  const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_DOUBLE_EQ(hit.t, 3);
  const Vec3 n1 = normalize(Vec3(1, 0, 2));
  const Vec3 expected = normalize(Vec3(0, 0, 1) * 0.25 + n1 * 0.5 + Vec3(0, 1, 0) * 0.25);
  EXPECT_VEC_NEAR(surface_at(rs.view(), ray, hit).normal, expected, 1e-14);
}

TEST_F(MeshTest, RotationIsRightHandedAboutTheAxis) {
  // 90° about z takes (1,0,0) to (0,1,0).
  Transform t;
  t.rotate_degrees = {0, 0, 90};
  Scene s;
  s.add(Mesh(load_obj(write_obj("tri.obj", kNormalTriangleObj)), Material{}, t));
  const RenderScene rs = compile(s);
  EXPECT_VEC_NEAR(rs.triangles.at(0).v1, Vec3(0, 1, 0), 1e-15);
  EXPECT_VEC_NEAR(rs.triangles.at(0).v2, Vec3(-1, 0, 0), 1e-15);
}

TEST_F(MeshTest, MirroringTransformKeepsFrontFacesFacingTheSameWay) {
  // The triangle faces +z; mirrored in x (scale −1, 1, 1) it must still face +z, as a closed
  // mesh's outside must stay outside. Its vertex normals follow M^−T: (1,0,0) → (−1,0,0).
  Transform t;
  t.scale = {-1, 1, 1};
  Scene s;
  s.add(Mesh(load_obj(write_obj("tri.obj", kNormalTriangleObj)), Material{}, t));
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.triangles.size(), 1u);
  EXPECT_VEC_NEAR(kernel::geometric_normal(rs.triangles[0]), Vec3(0, 0, 1), 1e-15);
  // At (−0.5, 0.25): weights 0.25 for (0,0,1), 0.5 for (−1,0,0), 0.25 for (0,1,0).
  const Ray ray{{-0.5, 0.25, 1}, kDown};
  const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_VEC_NEAR(surface_at(rs.view(), ray, hit).normal, normalize(Vec3(-0.5, 0.25, 0.25)), 1e-14);
}

TEST_F(MeshTest, TransformOrderIsScaleThenRotateXYZThenTranslate) {
  // p' = R_z·R_y·R_x·S·p + t. rotate [90, 0, 0] turns +y into +z.
  const fs::path obj = write_obj("tri.obj", kNormalTriangleObj);  // (0,0,0), (1,0,0), (0,1,0)
  const auto placed = [&](const Transform& t) {
    Scene s;
    s.add(Mesh(load_obj(obj), Material{}, t));
    const RenderScene rs = compile(s);
    const kernel::Triangle& tri = rs.triangles.at(0);
    return std::pair{tri.v1, tri.v2};
  };
  Transform rx;
  rx.rotate_degrees = {90, 0, 0};
  EXPECT_VEC_NEAR(placed(rx).second, Vec3(0, 0, 1), 1e-15);
  // Scale (2,1,1), then 90° about z: (1,0,0) → (2,0,0) → (0,2,0); then translate.
  Transform sz;
  sz.scale = {2, 1, 1};
  sz.rotate_degrees = {0, 0, 90};
  sz.translate = {1, 1, 1};
  EXPECT_VEC_NEAR(placed(sz).first, Vec3(1, 3, 1), 1e-15);
  EXPECT_VEC_NEAR(placed(sz).second, Vec3(0, 1, 1), 1e-15);
  // 90° about x, then 90° about z: (1,0,0) → (1,0,0) → (0,1,0); (0,1,0) → (0,0,1) → (0,0,1).
  Transform xz;
  xz.rotate_degrees = {90, 0, 90};
  EXPECT_VEC_NEAR(placed(xz).first, Vec3(0, 1, 0), 1e-15);
  EXPECT_VEC_NEAR(placed(xz).second, Vec3(0, 0, 1), 1e-15);
  // 90° about y takes +z to +x: (0,0,1)… use (1,0,0) → (0,0,−1).
  Transform ry;
  ry.rotate_degrees = {0, 90, 0};
  EXPECT_VEC_NEAR(placed(ry).first, Vec3(0, 0, -1), 1e-15);
}

TEST_F(MeshTest, ZeroAreaFacesAreDropped) {
  Scene s;
  s.add(Mesh(load_obj(write_obj("deg.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n")), Material{}));
  EXPECT_EQ(compile(s).triangles.size(), 1u);
}

TEST_F(MeshTest, FacesWithoutNormalsAreFlatShaded) {
  Scene s;
  s.add(Mesh(load_obj(write_obj("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")), Material{}));
  const RenderScene rs = compile(s);
  const Ray ray{{0.3, 0.3, 1}, kDown};
  const Hit hit = closest_hit(rs.view(), ray, 0, kInfinity);
  ASSERT_TRUE(hit.found());
  EXPECT_VEC_NEAR(surface_at(rs.view(), ray, hit).normal, Vec3(0, 0, 1), 1e-15);
}

TEST_F(MeshTest, InterpolatedNormalDrivesLambertShading) {
  // Directional light straight down the −z axis (towards the triangle's front): the flat normal
  // would give N·L = 1; the interpolated normal (1,1,2)/√6 at b1 = b2 = 0.25 gives 2/√6.
  Scene s;
  s.add(Mesh(load_obj(write_obj("tri.obj", kNormalTriangleObj)), test::phong(Vec3(0.5, 1, 0.25), 0, 1, Vec3(0), 1)));
  s.add(directional_light({0, 0, -1}));
  test::one_ray_camera(s, {0.25, 0.25, 1}, {0.25, 0.25, 0});
  const Vec3 c = test::pixel(s);
  EXPECT_VEC_NEAR(c, Vec3(0.5, 1, 0.25) * (2 / std::sqrt(6.0)), 1e-12);
}

TEST_F(MeshTest, MissingOrBrokenObjFileIsAnError) {
  EXPECT_THROW(load_obj(dir_ / "missing.obj"), Error);
  EXPECT_THROW(load_obj(write_obj("empty.obj", "v 0 0 0\n")), Error);  // no faces
  EXPECT_THROW(load_obj(write_obj("bad-index.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n")), Error);
}

}  // namespace
}  // namespace strahl::triangle_test
