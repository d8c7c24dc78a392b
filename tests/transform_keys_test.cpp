// The transform keys of scene files (docs/scene-format.md, "Transforms"): a `transform` list is
// applied in the order written, the fixed-order keys keep their order whatever order they are
// written in, `matrix` (3×4, 4×4) and axis-and-angle `rotate` equal the same map written with the
// other keys, planes and triangles have theirs baked into their coordinates, and a general
// transform survives save and load bit for bit. Bad transforms are errors at file:line:column.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"

namespace strahl::transform_keys_test {
namespace {

Scene scene_text(const std::string& objects) {
  return parse_scene(
      "camera: {position: [0, 1, 6], look_at: [0, 0, 0], fov: 40}\nrender: {width: 32, height: 24}\n"
      "lights:\n  - {type: point, position: [2, 3, 2]}\nobjects:\n" +
          objects,
      "t.yaml", ".");
}
RenderScene scene_of(const std::string& objects) { return compile(scene_text(objects)); }

// t of the nearest hit along a ray from (10, 0.5, 0.5) towards −x.
Real t_from_plus_x(const RenderScene& rs, Real y = 0.5, Real z = 0.5) {
  return closest_hit(rs.view(), Ray{{10, y, z}, {-1, 0, 0}}, 0, kInfinity).t;
}

std::string error_of(const std::string& objects) {
  try {
    scene_of(objects);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TransformKeys, ListAppliesInTheOrderWritten) {
  // The unit box [0, 1]³: translated by 1 then scaled by 2 is [2, 4]; scaled then translated [1, 3].
  const RenderScene a = scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{translate: [1, 0, 0]}, {scale: 2}]}\n");
  const RenderScene b = scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{scale: 2}, {translate: [1, 0, 0]}]}\n");
  EXPECT_EQ(t_from_plus_x(a), 6);
  EXPECT_EQ(t_from_plus_x(b), 7);  // Linear steps that do not commute: scale x by 2 then turn 90° about z gives x ∈ [−1, 0],
  // y ∈ [0, 2]; turning first gives x ∈ [−2, 0], y ∈ [0, 1].
  const RenderScene c = scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{scale: [2, 1, 1]}, {rotate: [0, 0, 90]}]}\n");
  const RenderScene d = scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{rotate: [0, 0, 90]}, {scale: [2, 1, 1]}]}\n");
  const Ray down{{-1.5, 10, 0.5}, {0, -1, 0}};
  EXPECT_EQ(closest_hit(c.view(), down, 0, kInfinity).t, kInfinity);
  EXPECT_NEAR(closest_hit(d.view(), down, 0, kInfinity).t, 9, 1e-12);
  EXPECT_NEAR(t_from_plus_x(c, 1.5), 10, 1e-12);
  EXPECT_EQ(t_from_plus_x(d, 1.5), kInfinity);
}

TEST(TransformKeys, FixedOrderKeysIgnoreTheOrderWritten) {
  const RenderScene a = scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], translate: [1, 0, 0], scale: 2}\n");
  const RenderScene b = scene_of("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], scale: 2, translate: [1, 0, 0]}\n");
  EXPECT_EQ(t_from_plus_x(a), 7);  // scale first, always
  EXPECT_EQ(t_from_plus_x(b), 7);
}

TEST(TransformKeys, MatrixEqualsTheList) {
  // Scale 2, then translate by (1, 0, 0): [[2, 0, 0, 1], [0, 2, 0, 0], [0, 0, 2, 0]].
  for (const char* m : {"[[2, 0, 0, 1], [0, 2, 0, 0], [0, 0, 2, 0]]", "[[2, 0, 0, 1], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]"}) {
    const RenderScene a = scene_of(std::string("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], matrix: ") + m + "}\n");
    EXPECT_EQ(t_from_plus_x(a), 7) << m;
  }
  // A matrix step inside a list composes with the others in order.
  const RenderScene b = scene_of(
      "  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{matrix: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}, "
      "{translate: [1, 0, 0]}, {matrix: [[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0]]}]}\n");
  EXPECT_EQ(t_from_plus_x(b), 6);
}

TEST(TransformKeys, AxisAngleEqualsTheEulerRotation) {
  // 90° about z: the box [0, 1]³ goes to x ∈ [−1, 0], y ∈ [0, 1]; about (1, 1, 1) by 120° the
  // axes are permuted x → y → z → x.
  for (const char* rot : {"rotate: {axis: [0, 0, 1], angle: 90}", "rotate: {axis: [0, 0, 7], angle: 90}",
                          "rotate: [0, 0, 90]", "transform: [{rotate: {axis: [0, 0, 1], angle: 90}}]"}) {
    const RenderScene rs = scene_of(std::string("  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], ") + rot + "}\n");
    EXPECT_NEAR(t_from_plus_x(rs), 10, 1e-12) << rot;
  }
  const Mat3 r = Mat3::rotation(Vec3(1, 1, 1), 120);
  const Vec3 x = r * Vec3(1, 0, 0), y = r * Vec3(0, 1, 0);
  EXPECT_NEAR(x.x, 0, 1e-15);
  EXPECT_NEAR(x.y, 1, 1e-15);
  EXPECT_NEAR(x.z, 0, 1e-15);
  EXPECT_NEAR(y.z, 1, 1e-15);
  // Scale, then the axis rotation, then translate, as with [x, y, z] degrees.
  const RenderScene s = scene_of(
      "  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], translate: [5, 0, 0], rotate: {axis: [0, 1, 0], angle: 180}, scale: 2}\n");
  EXPECT_NEAR(t_from_plus_x(s, 0.5, -0.5), 5, 1e-12);  // x ∈ [3, 5]
}

TEST(TransformKeys, EvenlyTransformedSphereStaysASphere) {
  const RenderScene rs = scene_of(
      "  - {type: sphere, center: [1, 0, 0], radius: 1, transform: [{rotate: {axis: [0, 0, 1], angle: 90}}, {scale: 2}]}\n");
  ASSERT_EQ(rs.spheres.size(), 1u);  // not an ellipsoid solid
  EXPECT_NEAR(rs.spheres[0].center.x, 0, 1e-15);
  EXPECT_NEAR(rs.spheres[0].center.y, 2, 1e-15);
  EXPECT_EQ(rs.spheres[0].radius, 2);
  const RenderScene e = scene_of("  - {type: sphere, center: [0, 0, 0], radius: 1, matrix: [[2, 0, 0], [0, 1, 0], [0, 0, 1]]}\n");
  EXPECT_TRUE(e.spheres.empty());  // an ellipsoid
  EXPECT_EQ(closest_hit(e.view(), Ray{{10, 0, 0}, {-1, 0, 0}}, 0, kInfinity).t, 8);
}

TEST(TransformKeys, PlaneIsBaked) {
  const RenderScene a = scene_of("  - {type: plane, normal: [0, 2, 0], distance: 1, translate: [5, 2, 7]}\n");
  ASSERT_EQ(a.planes.size(), 1u);
  EXPECT_EQ(a.planes[0].normal, Vec3(0, 1, 0));
  EXPECT_EQ(a.planes[0].distance, 2.5);
  // Scaled by 2 along its normal: y = 0.5 goes to y = 1; mirrored, the front side stays in front.
  const RenderScene b = scene_of("  - {type: plane, normal: [0, 1, 0], distance: 0.5, scale: [3, -2, 3]}\n");
  EXPECT_EQ(b.planes[0].normal, Vec3(0, -1, 0));
  EXPECT_EQ(b.planes[0].distance, 1);
  // Rotated 90° about z: y = 1 becomes x = −1, the normal −x.
  const RenderScene c = scene_of("  - {type: plane, normal: [0, 1, 0], distance: 1, rotate: {axis: [0, 0, 1], angle: 90}}\n");
  EXPECT_NEAR(c.planes[0].normal.x, -1, 1e-15);
  EXPECT_NEAR(c.planes[0].normal.y, 0, 1e-15);
  EXPECT_NEAR(c.planes[0].distance, 1, 1e-15);
  EXPECT_NEAR(closest_hit(c.view(), Ray{{3, 0, 0}, {-1, 0, 0}}, 0, kInfinity).t, 4, 1e-14);
}

TEST(TransformKeys, TriangleIsBaked) {
  const RenderScene a =
      scene_of("  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], transform: [{scale: 2}, {translate: [1, 1, 1]}]}\n");
  ASSERT_EQ(a.triangles.size(), 1u);
  EXPECT_EQ(a.triangles[0].v0, Vec3(1, 1, 1));
  EXPECT_EQ(a.triangles[0].v1, Vec3(3, 1, 1));
  EXPECT_EQ(a.triangles[0].v2, Vec3(1, 3, 1));
  // Mirrored in x: two vertices swap, so the winding's normal is still the mirrored +z.
  const RenderScene b = scene_of("  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], scale: [-1, 1, 1]}\n");
  const kernel::Triangle& t = b.triangles[0];
  EXPECT_GT(cross(t.v1 - t.v0, t.v2 - t.v0).z, 0);
  EXPECT_EQ(t.v0, Vec3(0, 0, 0));
}

// The C++ API's placement of a plane or a triangle is what a scene file's keys do (both are taken
// into the coordinates), survives a save and a load, and a singular one is an error.
TEST(TransformKeys, ApiPlacementOfPlanesAndTrianglesIsTheFilesKeys) {
  const RenderScene file = scene_of(
      "  - {type: plane, normal: [0, 1, 0], distance: 0.5, scale: [3, -2, 3]}\n"
      "  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], transform: [{scale: [-1, 2, 1]}, "
      "{rotate: {axis: [1, 1, 0], angle: 30}}, {translate: [1, 2, 3]}]}\n");
  // The same map as the file's list: its matrix and translation.
  const Scene listed = scene_text(
      "  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{scale: [-1, 2, 1]}, "
      "{rotate: {axis: [1, 1, 0], angle: 30}}, {translate: [1, 2, 3]}]}\n");
  Scene api = scene_text("  - {type: sphere, center: [0, -50, 0], radius: 1}\n");
  Plane& plane = api.add(Plane(Vec3(0, 1, 0), 0.5, Vec3(1)));
  plane.placement.scale = Vec3(3, -2, 3);
  Triangle& triangle = api.add(Triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1)));
  triangle.placement = listed.objects()[0]->placement;
  const RenderScene placed = compile(api);
  ASSERT_EQ(placed.planes.size(), 1u);
  EXPECT_EQ(placed.planes[0].normal, file.planes[0].normal);
  EXPECT_EQ(placed.planes[0].distance, file.planes[0].distance);
  ASSERT_EQ(placed.triangles.size(), 1u);
  EXPECT_EQ(placed.triangles[0].v0, file.triangles[0].v0);
  EXPECT_EQ(placed.triangles[0].v1, file.triangles[0].v1);
  EXPECT_EQ(placed.triangles[0].v2, file.triangles[0].v2);
  EXPECT_EQ(file.planes[0].normal, Vec3(0, -1, 0));  // (the file's plane: mirrored, scaled by 2)
  // Saved and loaded back: the loader takes the written keys into the coordinates.
  const RenderScene back = compile(parse_scene(scene_to_yaml(api), "back.yaml", "."));
  EXPECT_EQ(back.planes[0].normal, file.planes[0].normal);
  EXPECT_EQ(back.planes[0].distance, file.planes[0].distance);
  EXPECT_EQ(back.triangles[0].v0, file.triangles[0].v0);
  EXPECT_EQ(back.triangles[0].v2, file.triangles[0].v2);
  plane.placement.scale = Vec3(1, 0, 1);
  try {
    compile(api);
    ADD_FAILURE() << "a singular plane placement compiled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the transform is singular"), std::string::npos) << e.what();
  }
}

TEST(TransformKeys, MeshTakesTheSameForms) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "strahl_transform_keys_mesh";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const auto mesh = [&](const std::string& keys) {
    return compile(parse_scene(
        "camera: {position: [0, 1, 6], look_at: [0, 0, 0], fov: 40}\nobjects:\n  - {type: mesh, file: tri.obj, " + keys + "}\n",
        "m.yaml", dir));
  };
  const RenderScene a = mesh("transform: [{translate: [1, 1, 1]}, {scale: 2}]");
  ASSERT_EQ(a.triangles.size(), 1u);
  EXPECT_EQ(a.triangles[0].v0, Vec3(2, 2, 2));
  EXPECT_EQ(a.triangles[0].v1, Vec3(4, 2, 2));
  EXPECT_EQ(a.triangles[0].v2, Vec3(2, 4, 2));
  const RenderScene b = mesh("matrix: [[0, -1, 0, 5], [1, 0, 0, 0], [0, 0, 1, 0]]");
  EXPECT_EQ(b.triangles[0].v1, Vec3(5, 1, 0));
  EXPECT_EQ(b.triangles[0].v2, Vec3(4, 0, 0));
  std::filesystem::remove_all(dir);
}

TEST(TransformKeys, GeneralTransformRoundTrips) {
  const Scene s = scene_text(
      "  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], transform: [{rotate: {axis: [1, 2, 3], angle: 33}}, {scale: [1, 2, 3]}, "
      "{translate: [0.1, 0.2, 0.3]}]}\n");
  const std::string yaml = scene_to_yaml(s);
  EXPECT_NE(yaml.find("matrix: [["), std::string::npos);
  const Scene back = parse_scene(yaml, "back.yaml", ".");
  ASSERT_EQ(back.objects().size(), 1u);
  const Transform& x = s.objects()[0]->placement;
  const Transform& y = back.objects()[0]->placement;
  ASSERT_TRUE(y.general());
  for (int r = 0; r < 3; ++r) EXPECT_EQ(x.matrix().row[r], y.matrix().row[r]);
  EXPECT_EQ(x.translate, y.translate);
}

TEST(TransformKeys, BadTransformsNameTheirPlace) {
  const std::string box = "  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], ";
  EXPECT_EQ(error_of(box + "matrix: [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0]]}\n"),
            "t.yaml:6:58: matrix is singular (its determinant is 0): it flattens the object");
  EXPECT_EQ(error_of(box + "matrix: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}\n"),
            "t.yaml:6:101: a 4x4 matrix's last row must be [0, 0, 0, 1] (an affine map; projective ones are not supported)");
  EXPECT_EQ(error_of(box + "rotate: {axis: [0, 0, 0], angle: 3}}\n"), "t.yaml:6:65: rotate axis must not be the zero vector");
  EXPECT_EQ(error_of(box + "transform: [{scale: 2}], scale: 3}\n"),
            "t.yaml:6:82: give either a transform list or 'scale', not both (put it in the list)");
  EXPECT_EQ(error_of(box + "transform: [{shear: 2}]}\n"), "t.yaml:6:63: unknown transform step 'shear' (scale, rotate, translate or matrix)");
  EXPECT_EQ(error_of(box + "transform: [{scale: 1e-200}, {scale: 1e-200}]}\n"), "t.yaml:6:61: the transform is singular (its determinant is 0): it flattens the object");
  EXPECT_EQ(error_of(box + "matrix: [[1, 0, 0], [0, 1, 0]]}\n"),
            "t.yaml:6:58: matrix must be a list of 3 or 4 rows of 4 numbers (3 rows of 3: no translation)");
  EXPECT_EQ(error_of("  - {type: plane, normal: [0, 1, 0], scale: [1, 0, 1]}\n"), "t.yaml:6:45: scale must not be zero");
}

}  // namespace
}  // namespace strahl::transform_keys_test
