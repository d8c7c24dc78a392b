// The lecture's camera: basis {u, v, w}, image plane l, r, b, t at distance d, and the ray
//   s_u = l + (r − l)(x + 0.5)/n_x,  s_v = b + (t − b)(y + 0.5)/n_y,  dir = s_u·u + s_v·v − d·w.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/scene/scene.h"
#include "test_helpers.h"

namespace strahl::camera_test {
namespace {

using test::deg;

Camera compiled_camera(const Scene& s) { return compile(s).camera; }

// The lecture's pixel formula, written out independently of the camera code.
Vec3 lecture_direction(const Camera& c, const Vec3& u, const Vec3& v, const Vec3& w, int x, int y) {
  const Real su = c.l + (c.r - c.l) * (x + 0.5) / c.nx;
  const Real sv = c.b + (c.t - c.b) * (y + 0.5) / c.ny;
  return normalize(u * su + v * sv - w * c.d);
}

void expect_orthonormal_right_handed(const Frame& f) {
  EXPECT_NEAR(length(f.u), 1, 1e-14);
  EXPECT_NEAR(length(f.v), 1, 1e-14);
  EXPECT_NEAR(length(f.w), 1, 1e-14);
  EXPECT_NEAR(dot(f.u, f.v), 0, 1e-14);
  EXPECT_NEAR(dot(f.u, f.w), 0, 1e-14);
  EXPECT_NEAR(dot(f.v, f.w), 0, 1e-14);
  EXPECT_VEC_NEAR(cross(f.u, f.v), f.w, 1e-14);  // right-handed
}

TEST(Camera, BasisLookingDownNegativeZIsTheWorldAxes) {
  Scene s;
  test::set_camera(s, {1, 2, 3}, {1, 2, -7}, {0, 1, 0}, -1, 1, -1, 1, 1, 4, 4);
  const Camera c = compiled_camera(s);
  EXPECT_VEC_NEAR(c.basis.u, Vec3(1, 0, 0), 1e-15);
  EXPECT_VEC_NEAR(c.basis.v, Vec3(0, 1, 0), 1e-15);
  EXPECT_VEC_NEAR(c.basis.w, Vec3(0, 0, 1), 1e-15);  // w points back from the look-at point to the eye
  EXPECT_EQ(c.eye, Vec3(1, 2, 3));
}

TEST(Camera, BasisLookingAlongPositiveXHasRightAlongPositiveZ) {
  Scene s;
  test::set_camera(s, {0, 0, 0}, {5, 0, 0}, {0, 1, 0}, -1, 1, -1, 1, 1, 4, 4);
  const Camera c = compiled_camera(s);
  EXPECT_VEC_NEAR(c.basis.u, Vec3(0, 0, 1), 1e-15);
  EXPECT_VEC_NEAR(c.basis.v, Vec3(0, 1, 0), 1e-15);
  EXPECT_VEC_NEAR(c.basis.w, Vec3(-1, 0, 0), 1e-15);
}

TEST(Camera, BasisIsOrthonormalRightHandedForAnObliqueUpVector) {
  Scene s;
  const Vec3 eye(1, -2, 0.5), target(-3, 4, 2), up(0.3, 1, -0.2);
  test::set_camera(s, eye, target, up, -1, 1, -1, 1, 1, 4, 4);
  const Camera c = compiled_camera(s);
  expect_orthonormal_right_handed(c.basis);
  EXPECT_VEC_NEAR(c.basis.w, normalize(eye - target), 1e-15);
  EXPECT_NEAR(dot(c.basis.u, up), 0, 1e-14);          // u is horizontal with respect to up
  EXPECT_GT(dot(c.basis.v, up), 0);                     // v points up, not down
  EXPECT_NEAR(dot(cross(up, c.basis.w), c.basis.v), 0, 1e-14);  // v lies in the plane of up and w
}

TEST(Camera, ExplicitImagePlaneRaysMatchLectureFormulaAtCornersAndCentre) {
  Scene s;
  const Vec3 eye(1, 2, 3);
  // Looking down −z: u = x, v = y, w = z, so the directions are (s_u, s_v, −d) by hand.
  test::set_camera(s, eye, {1, 2, -7}, {0, 1, 0}, -0.8, 0.4, -0.3, 0.6, 1.5, 6, 4);
  const Camera c = compiled_camera(s);
  EXPECT_EQ(c.l, -0.8);
  EXPECT_EQ(c.r, 0.4);
  EXPECT_EQ(c.b, -0.3);
  EXPECT_EQ(c.t, 0.6);
  EXPECT_EQ(c.d, 1.5);
  EXPECT_EQ(c.nx, 6);
  EXPECT_EQ(c.ny, 4);
  // s_u at x = 0: −0.8 + 1.2·0.5/6 = −0.7; at x = 5: −0.8 + 1.2·5.5/6 = 0.3.
  // s_v at y = 0: −0.3 + 0.9·0.5/4 = −0.1875; at y = 3: −0.3 + 0.9·3.5/4 = 0.4875.
  struct Case { int x, y; Vec3 dir; };
  const Case cases[] = {
      {0, 0, {-0.7, -0.1875, -1.5}},
      {5, 0, {0.3, -0.1875, -1.5}},
      {0, 3, {-0.7, 0.4875, -1.5}},
      {5, 3, {0.3, 0.4875, -1.5}},
  };
  for (const Case& k : cases) {
    const Ray ray = c.generate_ray(k.x + 0.5, k.y + 0.5);
    EXPECT_EQ(ray.origin, eye);
    EXPECT_VEC_NEAR(ray.direction, normalize(k.dir), 1e-15) << "pixel " << k.x << "," << k.y;
  }
  // The image centre (between the middle pixels): s_u = (l + r)/2 = −0.2, s_v = (b + t)/2 = 0.15.
  EXPECT_VEC_NEAR(c.generate_ray(3, 2).direction, normalize(Vec3(-0.2, 0.15, -1.5)), 1e-15);
}

TEST(Camera, CentrePixelOfOddGridLooksAtTheLookAtPointForSymmetricPlane) {
  Scene s;
  const Vec3 eye(0.5, 1, 2), target(-1, 0.2, -3);
  test::set_camera(s, eye, target, {0, 1, 0}, -2, 2, -1, 1, 0.7, 5, 3);
  const Camera c = compiled_camera(s);
  EXPECT_VEC_NEAR(c.generate_ray(2 + 0.5, 1 + 0.5).direction, normalize(target - eye), 1e-15);
}

TEST(Camera, RotatedCameraRaysMatchLectureFormula) {
  Scene s;
  // Looking along +x: u = +z, v = +y, w = −x, so dir = (d, s_v, s_u).
  test::set_camera(s, {0, 0, 0}, {5, 0, 0}, {0, 1, 0}, -1, 3, -2, 1, 2, 4, 3);
  const Camera c = compiled_camera(s);
  // x = 3: s_u = −1 + 4·3.5/4 = 2.5; y = 0: s_v = −2 + 3·0.5/3 = −1.5.
  EXPECT_VEC_NEAR(c.generate_ray(3.5, 0.5).direction, normalize(Vec3(2, -1.5, 2.5)), 1e-15);
}

TEST(Camera, ObliqueCameraRaysMatchLectureFormulaEverywhere) {
  Scene s;
  test::set_camera(s, {1, -2, 0.5}, {-3, 4, 2}, {0.3, 1, -0.2}, -0.5, 0.9, -0.4, 0.2, 0.8, 7, 5);
  const Camera c = compiled_camera(s);
  for (int y = 0; y < c.ny; ++y)
    for (int x = 0; x < c.nx; ++x)
      EXPECT_VEC_NEAR(c.generate_ray(x + 0.5, y + 0.5).direction,
                      lecture_direction(c, c.basis.u, c.basis.v, c.basis.w, x, y), 1e-14);
}

TEST(Camera, HorizontalFovSpansTheImageWidth) {
  Scene s;
  s.camera.position = {0, 0, 0};
  s.camera.look_at = {0, 0, -1};
  s.camera.fov_degrees = 90;
  s.camera.fov_axis = CameraDescription::FovAxis::Horizontal;
  s.settings.width = 8;
  s.settings.height = 4;
  const Camera c = compiled_camera(s);
  // tan(45°) = 1 across, 1/aspect = 0.5 up, at d = 1.
  EXPECT_NEAR(c.r, 1, 1e-15);
  EXPECT_NEAR(c.l, -1, 1e-15);
  EXPECT_NEAR(c.t, 0.5, 1e-15);
  EXPECT_NEAR(c.b, -0.5, 1e-15);
  EXPECT_NEAR(c.d, 1, 1e-15);
  // Bottom-left pixel: s_u = −1 + 2·0.5/8 = −0.875, s_v = −0.5 + 0.5/4 = −0.375.
  EXPECT_VEC_NEAR(c.generate_ray(0.5, 0.5).direction, normalize(Vec3(-0.875, -0.375, -1)), 1e-15);
  // The left and right image edges are 90° apart; top and bottom 2·atan(0.5).
  const Real horizontal = std::acos(dot(c.generate_ray(0, 2).direction, c.generate_ray(8, 2).direction));
  const Real vertical = std::acos(dot(c.generate_ray(4, 0).direction, c.generate_ray(4, 4).direction));
  EXPECT_NEAR(horizontal, deg(90), 1e-12);
  EXPECT_NEAR(vertical, 2 * std::atan(0.5), 1e-12);
}

TEST(Camera, VerticalFovSpansTheImageHeight) {
  Scene s;
  s.camera.position = {0, 0, 0};
  s.camera.look_at = {0, 0, -1};
  s.camera.fov_degrees = 60;
  s.camera.fov_axis = CameraDescription::FovAxis::Vertical;
  s.settings.width = 3;
  s.settings.height = 2;
  const Camera c = compiled_camera(s);
  const Real t = std::tan(deg(30));
  EXPECT_NEAR(c.t, t, 1e-15);
  EXPECT_NEAR(c.b, -t, 1e-15);
  EXPECT_NEAR(c.r, 1.5 * t, 1e-15);
  EXPECT_NEAR(c.l, -1.5 * t, 1e-15);
  const Real vertical = std::acos(dot(c.generate_ray(1.5, 0).direction, c.generate_ray(1.5, 2).direction));
  EXPECT_NEAR(vertical, deg(60), 1e-12);
  // Top-right pixel (x = 2, y = 1).
  const Real su = -1.5 * t + 3 * t * 2.5 / 3, sv = -t + 2 * t * 1.5 / 2;
  EXPECT_VEC_NEAR(c.generate_ray(2.5, 1.5).direction, normalize(Vec3(su, sv, -1)), 1e-15);
}

// Image rows count from the top, x from the left: a tiny sphere placed on each corner ray
// shows up in exactly that corner pixel of the rendered image.
TEST(Camera, RenderedCornersLandInTheRightPixels) {
  Scene s;
  const Vec3 eye(1, 2, 3);
  test::set_camera(s, eye, {1, 2, -7}, {0, 1, 0}, -0.8, 0.4, -0.3, 0.6, 1.5, 6, 4);
  const Vec3 top_left = normalize(Vec3(-0.7, 0.4875, -1.5)), top_right = normalize(Vec3(0.3, 0.4875, -1.5));
  const Vec3 bottom_left = normalize(Vec3(-0.7, -0.1875, -1.5)), bottom_right = normalize(Vec3(0.3, -0.1875, -1.5));
  const Vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
  s.add(Sphere(eye + top_left * 10, 0.1, test::emissive_like(red)));
  s.add(Sphere(eye + top_right * 10, 0.1, test::emissive_like(green)));
  s.add(Sphere(eye + bottom_left * 10, 0.1, test::emissive_like(blue)));
  s.add(Sphere(eye + bottom_right * 10, 0.1, test::emissive_like(white)));
  const Image img = test::render_image(s);
  ASSERT_EQ(img.width(), 6);
  ASSERT_EQ(img.height(), 4);
  for (int row = 0; row < 4; ++row) {
    for (int x = 0; x < 6; ++x) {
      Vec3 expected(0);
      if (x == 0 && row == 0) expected = red;
      if (x == 5 && row == 0) expected = green;
      if (x == 0 && row == 3) expected = blue;
      if (x == 5 && row == 3) expected = white;
      EXPECT_VEC_NEAR(test::to_vec(img.at(x, row)), expected, 1e-6) << "pixel x=" << x << " row=" << row;
    }
  }
}

TEST(Camera, InvalidDescriptionsAreRejected) {
  const auto fails = [](auto&& edit) {
    Scene s;
    test::set_camera(s, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, -1, 1, -1, 1, 1, 4, 4);
    edit(s.camera);
    EXPECT_THROW(compile(s), Error);
  };
  fails([](CameraDescription& c) { c.up = {0, 0, 1}; });          // parallel to the view
  fails([](CameraDescription& c) { c.up = {0, 0, 0}; });          // zero
  fails([](CameraDescription& c) { c.look_at = c.position; });    // no view direction
  fails([](CameraDescription& c) { c.l = 1; });                   // l >= r
  fails([](CameraDescription& c) { c.b = 2; });                   // b >= t
  fails([](CameraDescription& c) { c.d = 0; });                   // d <= 0
  fails([](CameraDescription& c) { c.explicit_image_plane = false; c.fov_degrees = 0; });
  fails([](CameraDescription& c) { c.explicit_image_plane = false; c.fov_degrees = 180; });
  fails([](CameraDescription& c) { c.position = {std::nan(""), 0, 5}; });
}

}  // namespace
}  // namespace strahl::camera_test
