// Depth of field: aperture 0 is exactly the pinhole camera; a surface on the focus plane renders
// as with the pinhole; a point off it blurs into the circle of confusion of the thin-lens formula.

#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.h"

namespace strahl::dof_test {
namespace {

TEST(ThinLens, ApertureZeroIsThePinholeRay) {
  Scene s;
  s.add(Sphere({0, 0, 0}, 1, Vec3(1)));
  s.camera.position = {1, 2, 5};
  s.camera.look_at = {0, 0.3, 0};
  const Camera cam = compile(s).camera;
  for (const Real lx : {0.0, 0.3, 0.999}) {
    CameraSample cs;
    cs.film_x = 100.25;
    cs.film_y = 33.5;
    cs.lens = {lx, 1 - lx};
    const Ray a = cam.generate_ray(cs), b = cam.generate_ray(cs.film_x, cs.film_y);
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.direction, b.direction);
  }
}

TEST(ThinLens, RaysOfOneFilmPointMeetOnTheFocusPlane) {
  Scene s;
  s.add(Sphere({0, 0, 0}, 1, Vec3(1)));
  s.camera.position = {1, 2, 5};
  s.camera.look_at = {0, 0.3, 0};
  s.camera.aperture = 0.2;
  s.camera.focus_point = {0.5, -0.2, 0.4};
  s.camera.has_focus_point = true;
  const Camera cam = compile(s).camera;
  const Real f = dot(s.camera.focus_point - s.camera.position, -cam.basis.w);
  EXPECT_NEAR(cam.focus_distance, f, 1e-12);
  CameraSample cs;
  cs.film_x = 400;
  cs.film_y = 200;
  const Ray pin = cam.generate_ray(cs.film_x, cs.film_y);
  const Vec3 target = pin.at(f / -dot(pin.direction, cam.basis.w));
  for (const Vec2 lens : {Vec2{0.1, 0.9}, Vec2{0.7, 0.2}, Vec2{0.99, 0.5}}) {
    cs.lens = lens;
    const Ray r = cam.generate_ray(cs);
    EXPECT_LE(length(r.origin - cam.eye), 0.2 + 1e-12);
    EXPECT_NEAR(dot(r.origin - cam.eye, cam.basis.w), 0, 1e-12);  // on the lens plane
    const Vec3 on_plane = r.at(f / -dot(r.direction, cam.basis.w) + dot(r.origin - cam.eye, cam.basis.w));
    EXPECT_VEC_NEAR(on_plane, target, 1e-9);
  }
}

// A checkerboard wall facing the camera (view-independent shading) exactly on the focus plane.
Scene wall(Real aperture, Real focus_distance) {
  Scene s;
  Material m = test::emissive_like(Vec3(0.9, 0.5, 0.1));
  m.checker_size = 0.37;
  m.checker_color = Vec3(0.1, 0.2, 0.8);
  s.add(Plane({0, 0, 1}, 0, m));
  test::set_camera(s, {0.05, 0.02, 5}, {0.05, 0.02, 0}, {0, 1, 0}, -0.5, 0.5, -0.375, 0.375, 1, 64, 48);
  s.camera.aperture = aperture;
  s.camera.focus_distance = focus_distance;
  s.settings.supersample = 2;
  return s;
}

TEST(ThinLens, TheFocusPlaneIsSharp) {
  const Image pinhole = test::render_image(wall(0, 0));
  EXPECT_LT(test::max_abs_diff(test::render_image(wall(0.3, 5)), pinhole), 1e-6);
  // The control: focused elsewhere the same wall blurs.
  EXPECT_GT(test::max_abs_diff(test::render_image(wall(0.3, 3)), pinhole), 0.1);
}

// A disk emitter of radius ρ facing the camera at depth z, camera focused at f with lens
// radius a. In image-plane units (distance d) the picture is the disk's image (radius ρ·d/z)
// blurred by the circle of confusion, radius R = a·d·|1/f − 1/z|: the sum of two independent
// uniform disks, whose mean squared distance from the centre is (ρ·d/z)²/2 + R²/2.
TEST(ThinLens, OutOfFocusPointBlursByTheCircleOfConfusion) {
  const Real a = 0.4, f = 1, z = 4, rho = 0.4, d = 1;
  const int n = 96;
  const Real px_per_unit = n / 2.0;
  Scene s;
  s.add(Sphere({0, 0, 100}, 1, Vec3(0)));  // behind the camera: only the light shows
  s.add(disk_light({0, 0, -z}, {0, 0, 1}, rho, Vec3(1), 1));
  test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -1, 1, -1, 1, d, n, n);
  s.camera.aperture = a;
  s.camera.focus_distance = f;
  s.settings.supersample = 8;
  const Image img = test::render_image(s, 0);
  double sum = 0, moment = 0;
  for (int row = 0; row < n; ++row) {
    for (int x = 0; x < n; ++x) {
      const double v = img.at(x, row).r;
      const double dx = x + 0.5 - n / 2.0, dy = row + 0.5 - n / 2.0;
      sum += v;
      moment += v * (dx * dx + dy * dy);
    }
  }
  ASSERT_GT(sum, 0);
  // Pixel values are averages over the pixel: add its own spread, 2 × 1/12 px².
  const double mean_r2 = moment / sum + 1.0 / 6;
  const double image_radius = rho * d / z * px_per_unit;
  const double measured = std::sqrt(2 * mean_r2 - image_radius * image_radius);
  const double predicted = a * d * std::fabs(1 / f - 1 / z) * px_per_unit;
  EXPECT_NEAR(measured, predicted, 0.01 * predicted) << "circle of confusion in pixels";
  // Nothing outside the blurred disk.
  const double reach = predicted + image_radius + 1.5;
  for (int row = 0; row < n; ++row) {
    for (int x = 0; x < n; ++x) {
      if (std::hypot(x + 0.5 - n / 2.0, row + 0.5 - n / 2.0) > reach) {
        ASSERT_EQ(img.at(x, row).r, 0) << x << "," << row;
      }
    }
  }
}

}  // namespace
}  // namespace strahl::dof_test
