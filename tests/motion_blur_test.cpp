// Motion blur: a sphere moving across the frame covers the swept region with the expected
// average coverage; moving shapes cast moving shadows; the scene keys load; images are the same
// for any thread count and tile size with every effect on.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::motion_blur_test {
namespace {

// Fraction of the shutter [0, 1] during which a sphere moving c(t) = c0 + t·Δ covers the ray
// (origin at 0, unit direction d): |perp(c0) + t·perp(Δ)|² < r² is a quadratic inequality in t.
Real covered_fraction(const Vec3& c0, const Vec3& delta, Real r, const Vec3& d) {
  const Vec3 p0 = c0 - d * dot(c0, d), pd = delta - d * dot(delta, d);
  const Real A = dot(pd, pd), B = 2 * dot(p0, pd), C = dot(p0, p0) - r * r;
  if (A == 0) return C < 0 ? 1 : 0;
  const Real disc = B * B - 4 * A * C;
  if (disc <= 0) return 0;
  const Real t0 = (-B - std::sqrt(disc)) / (2 * A), t1 = (-B + std::sqrt(disc)) / (2 * A);
  return std::fmax(Real(0), std::fmin(Real(1), t1) - std::fmax(Real(0), t0));
}

TEST(MotionBlur, MovingSphereCoversTheSweptRegionOnAverage) {
  const Vec3 c0(-0.3, 0.05, -5), velocity(0.45, 0.1, 0);
  const Real r = 0.3;
  const int nx = 64, ny = 32, ss = 8;
  Scene s;
  Sphere sphere(c0, r, test::emissive_like(Vec3(1)));
  sphere.motion = Motion::linear(velocity);
  s.add(std::move(sphere));
  test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -0.2, 0.2, -0.1, 0.1, 1, nx, ny);
  s.settings.supersample = ss;
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.moving_spheres.size(), 1u);
  ASSERT_TRUE(rs.spheres.empty());
  const Image img = render(rs, RenderOptions{});

  double measured = 0, expected = 0, variance = 0;
  int swept = 0, full = 0;
  for (int row = 0; row < ny; ++row) {
    for (int x = 0; x < nx; ++x) {
      const int y = ny - 1 - row;
      double p_sum = 0, var = 0;
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i) {
          const Ray ray = rs.camera.generate_ray(x + (i + 0.5) / ss, y + (j + 0.5) / ss);
          const double p = covered_fraction(c0, velocity, r, ray.direction);
          p_sum += p;
          var += p * (1 - p);
        }
      const double pixel_expected = p_sum / (ss * ss), v = img.at(x, row).r;
      if (pixel_expected == 0) {
        ASSERT_EQ(v, 0) << "outside the swept region " << x << "," << row;
        continue;
      }
      if (pixel_expected == 1) {
        ASSERT_NEAR(v, 1, 1e-6) << "covered all the time " << x << "," << row;
        ++full;
      }
      ++swept;
      measured += v;
      expected += pixel_expected;
      variance += var / (ss * ss * ss * ss);
    }
  }
  ASSERT_GT(swept, 200);
  ASSERT_GT(full, 0);
  // Each sample is a Bernoulli draw (covered or not at its random time): 4σ.
  EXPECT_NEAR(measured, expected, 4 * std::sqrt(variance)) << swept << " pixels in the swept region";
  EXPECT_NEAR(measured / expected, 1, 0.02);
}

TEST(MotionBlur, ShutterOfZeroLengthFreezesTheSphereAtOpen) {
  Scene s;
  Sphere sphere({0, 0, -5}, 0.5, test::emissive_like(Vec3(1)));
  sphere.motion = Motion::linear({10, 0, 0});
  s.add(std::move(sphere));
  s.camera.shutter_open = s.camera.shutter_close = 0.1;  // the sphere sits at x = 1
  test::one_ray_camera(s, {1, 0, 0}, {1, 0, -5});
  s.camera.shutter_open = s.camera.shutter_close = 0.1;
  EXPECT_NEAR(test::pixel(s).x, 1, 1e-12);
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -5});
  s.camera.shutter_open = s.camera.shutter_close = 0.1;
  EXPECT_EQ(test::pixel(s), Vec3(0));
}

TEST(MotionBlur, KeyframedMeshAndTriangleMove) {
  Scene s;
  Triangle tri({-1, -1, -5}, {1, -1, -5}, {0, 1, -5}, test::emissive_like(Vec3(1)));
  Transform from, to;
  to.translate = {3, 0, 0};
  tri.motion = Motion::keyframes(from, to);
  s.add(std::move(tri));
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.moving_triangles.size(), 1u);
  EXPECT_EQ(rs.moving_triangles[0].p1[0], Vec3(2, -1, -5));
  SceneView v = rs.view();
  Ray ray{{3, 0, 0}, {0, 0, -1}, 1.0};
  EXPECT_EQ(closest_hit(v, ray, 0, kInfinity).kind, ShapeKind::MovingTriangle);
  ray.time = 0;
  EXPECT_FALSE(closest_hit(v, ray, 0, kInfinity).found());
  ray.origin = {0, 0, 0};
  EXPECT_NEAR(closest_hit(v, ray, 0, kInfinity).t, 5, 1e-12);
  // A moving occluder shadows at the times it is in the way only.
  Ray shadow{{0, 0, 0}, {0, 0, -1}, 0.0};
  EXPECT_EQ(transmittance(v, shadow, 10), Vec3(0));
  shadow.time = 1;
  EXPECT_EQ(transmittance(v, shadow, 10), Vec3(1));
}

// Keyframes act in the mesh's own coordinates: a quarter turn about its own y axis, then its
// placement. Its points move on arcs (a vertex keeps its distance from the axis: no shrinking
// midway), and vertex normals turn with it.
TEST(MotionBlur, KeyframedMeshTurnsAboutItsOwnOrigin) {
  MeshData data;
  data.positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  data.normals = {{0, 0, 1}};
  data.faces.push_back({{0, 1, 2}, {0, 0, 0}});
  Transform place;
  place.translate = {10, 0, 0};
  Mesh mesh(data, Material{}, place);
  Transform to;
  to.rotate_degrees = {0, 90, 0};
  mesh.motion = Motion::keyframes(Transform{}, to);
  Scene s;
  s.add(std::move(mesh));
  s.camera.shutter_open = 0;
  s.camera.shutter_close = 1;
  const RenderScene rs = compile(s);
  ASSERT_TRUE(rs.moving_triangles.empty());
  ASSERT_EQ(rs.moving_instances.size(), 1u);
  const kernel::MovingMap& m = rs.moving_instances[0].map;
  for (const Real u : {0.0, 0.25, 0.5, 1.0}) {
    const Real a = u * kPi / 2;
    EXPECT_TRUE(test::vec_near(kernel::moved_point(m, {1, 0, 0}, u), Vec3(10 + std::cos(a), 0, -std::sin(a)), 1e-12)) << u;
    EXPECT_TRUE(test::vec_near(kernel::moved_point(m, {0, 0, 1}, u), Vec3(10 + std::sin(a), 0, std::cos(a)), 1e-12)) << u;
  }
  // Midway the face is turned by 45°: a ray along its normal meets it at the turned centroid,
  // with the vertex normal turned alike.
  const SceneView v = rs.view();
  const Real c = std::sqrt(0.5);
  const Vec3 centroid = Vec3(10, 0, 0) + Vec3(c * 2 / 3, 1.0 / 3, 0);
  const Vec3 n = normalize(Vec3(2 * c, 1, 0));
  const Ray ray{centroid + n * 5, -n, 0.5};
  const Hit h = closest_hit(v, ray, 0, kInfinity);
  ASSERT_TRUE(h.found());
  EXPECT_NEAR(h.t, 5, 1e-12);
  EXPECT_TRUE(test::vec_near(surface_at(v, ray, h).normal, Vec3(c, 0, c), 1e-12));
  // A velocity moves the placed mesh in world space by velocity × time.
  Mesh fast(data, Material{}, place);
  fast.motion = Motion::linear({0, 2, 0});
  Scene s2;
  s2.add(std::move(fast));
  s2.camera.shutter_open = 0.5;
  s2.camera.shutter_close = 1.5;
  const RenderScene r2 = compile(s2);
  EXPECT_VEC_NEAR(r2.moving_triangles.at(0).p0[0], Vec3(11, 1, 0), 1e-12);
  EXPECT_VEC_NEAR(r2.moving_triangles.at(0).p1[0], Vec3(11, 3, 0), 1e-12);
}

TEST(MotionBlur, SceneKeysLoadAndAreChecked) {
  const std::string ok = R"(
camera: {position: [0, 0, 5], look_at: [0, 0, 0], shutter: [0, 0.5], aperture: 0.1, focus_point: [0, 0, 1]}
lights:
  - {type: rect, corner: [-1, 3, -1], edge_u: [0, 0, 2], edge_v: [2, 0, 0], power: 40, samples: 3}
  - {type: disk, center: [0, 3, 0], normal: [0, -1, 0], radius: 0.5, intensity: 2}
  - {type: sphere, center: [2, 3, 0], radius: 0.25, color: [1, 0.5, 0.5]}
materials:
  brushed: {reflectivity: 0.8, roughness: 0.2}
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: brushed, motion: {velocity: [1, 0, 0]}}
  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], motion: {from: {translate: [0, 0, 0]}, to: {rotate: [0, 0, 90]}}}
)";
  const Scene scene = parse_scene(ok, "ok.yaml", ".");
  EXPECT_EQ(scene.lights().size(), 3u);
  EXPECT_EQ(scene.lights()[0].samples, 3);
  EXPECT_NEAR(scene.lights()[0].radiance.x, 40 / (kPi * 4), 1e-12);
  const RenderScene rs = compile(scene);
  EXPECT_NEAR(rs.camera.focus_distance, 4, 1e-12);
  EXPECT_EQ(rs.camera.shutter_close, 0.5);
  EXPECT_EQ(rs.materials[0].roughness, 0.2);
  EXPECT_EQ(rs.moving_spheres.at(0).center1, Vec3(0.5, 0, 0));
  EXPECT_EQ(rs.moving_instances.size(), 1u);  // (the triangle turns: an instance, moving on arcs)

  const auto error_of = [](const std::string& text) {
    try {
      compile(parse_scene(text, "bad.yaml", "."));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string obj = "objects: [{type: sphere, center: [0, 0, 0], radius: 1}]\n";
  EXPECT_NE(error_of("lights: [{type: rect, corner: [0, 1, 0], edge_u: [1, 0, 0], edge_v: [1, 0, 1]}]\n" + obj)
                .find("bad.yaml:1:"),
            std::string::npos);
  EXPECT_NE(error_of("lights: [{type: disk, center: [0, 1, 0], normal: [0, 0, 0], radius: 1}]\n" + obj).find("zero"),
            std::string::npos);
  EXPECT_NE(error_of("lights: [{type: sphere, center: [0, 1, 0], radius: -1}]\n" + obj).find("positive"),
            std::string::npos);
  EXPECT_NE(error_of("lights: [{type: sphere, center: [0, 1, 0], radius: 1, samples: 0}]\n" + obj).find("samples"),
            std::string::npos);
  EXPECT_NE(error_of("lights: [{type: sphere, center: [0, 1, 0], radius: 1, power: 1, intensity: 1}]\n" + obj)
                .find("not both"),
            std::string::npos);
  EXPECT_NE(error_of("camera: {aperture: -1}\n" + obj).find("bad.yaml:1:"), std::string::npos);
  EXPECT_NE(error_of("camera: {shutter: [1, 0]}\n" + obj).find("shutter"), std::string::npos);
  EXPECT_NE(error_of("camera: {focus_point: [0, 0, 10]}\n" + obj).find("in front"), std::string::npos);
  EXPECT_NE(error_of("materials: {m: {roughness: 2}}\n" + obj).find("roughness"), std::string::npos);
  EXPECT_NE(error_of("objects: [{type: plane, normal: [0, 1, 0], motion: {velocity: [1, 0, 0]}}]\n").find("motion"),
            std::string::npos);
  EXPECT_NE(error_of("objects: [{type: sphere, center: [0, 0, 0], radius: 1, motion: {speed: 1}}]\n").find("unknown key"),
            std::string::npos);
}

// Issue 12: a sphere's keyframes transform it as a whole, in world space, as docs/scene-format.md
// says: the centre by the transform, the radius by the scale's magnitude. A non-uniform scale is
// refused at the scale's own line and column; a static sphere has no transform keys at all.
TEST(MotionBlur, SphereKeyframesScaleTheRadiusWithTheCentre) {
  const Scene scene = parse_scene(
      "objects:\n"
      "  - {type: sphere, center: [1, 0, -4], radius: 0.5, motion: {from: {scale: 2}, to: {scale: -3, translate: [0, 1, 0]}}}\n",
      "ok.yaml", ".");
  const RenderScene rs = compile(scene);
  ASSERT_EQ(rs.moving_spheres.size(), 1u);
  const kernel::MovingSphere& m = rs.moving_spheres[0];
  EXPECT_EQ(m.center0, Vec3(2, 0, -8));
  EXPECT_EQ(m.radius0, 1.0);
  EXPECT_EQ(m.center1, Vec3(-3, 1, 12));
  EXPECT_EQ(m.radius1, 1.5);
  EXPECT_EQ(kernel::at_time(m, 0.5).radius, 1.25);
  EXPECT_EQ(kernel::at_time(m, 0.5).center, Vec3(-0.5, 0.5, 2));

  // The same scale at both keys: the image of the static sphere scaled by hand.
  const auto picture = [](Sphere sphere) {
    Scene s;
    test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -1, 1, -1, 1, 1, 24, 24);
    s.add(std::move(sphere));
    s.add(point_light({2, 2, 0}));
    return test::render_image(s);
  };
  Sphere moving({0.25, 0.1, -1.5}, 0.3, test::phong({0.8, 0.3, 0.2}, 0.1, 0.7, Vec3(0.5), 20));
  Transform two;
  two.scale = Vec3(2);
  moving.motion = Motion::keyframes(two, two);
  const Image a = picture(moving);
  const Image b = picture(Sphere({0.5, 0.2, -3}, 0.6, test::phong({0.8, 0.3, 0.2}, 0.1, 0.7, Vec3(0.5), 20)));
  EXPECT_LE(test::max_abs_diff(a, b), 1e-6f);
  long lit = 0;
  for (const Rgb& p : b.pixels()) lit += p.r > 0;
  EXPECT_GT(lit, 12);  // the sphere covers about 18 of the 576 pixels

  const auto error_of = [](const std::string& text) {
    try {
      compile(parse_scene(text, "bad.yaml", "."));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // Keys that scale it unevenly make it a moving ellipsoid (tests/moving_solid_test.cpp).
  EXPECT_EQ(error_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, motion: {to: {scale: [1, 2, 1]}}}\n"),
            "no error");
  EXPECT_EQ(error_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, motion: {from: {scale: [2, -2, 2]}}}\n"),
            "no error");
  // A static scale places the sphere (docs/scene-format.md, "Transforms"); an uneven one makes an
  // ellipsoid, which moves as solids do (tests/moving_solid_test.cpp).
  EXPECT_EQ(error_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, scale: 2}\n"), "no error");
  EXPECT_EQ(error_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, scale: [1, 2, 1], motion: {velocity: "
                     "[1, 0, 0]}}\n"),
            "no error");
  // Through the C++ API, where there is no line to name, the sphere's own location.
  Scene api;
  Sphere squashed({0, 0, -3}, 1, Material{});
  Transform flat;
  flat.scale = Vec3(1, 0.5, 1);
  squashed.motion = Motion::keyframes(Transform{}, flat);
  api.add(std::move(squashed));
  const RenderScene squashed_scene = compile(api);
  EXPECT_EQ(squashed_scene.moving_solids.size(), 1u);
  EXPECT_TRUE(squashed_scene.moving_spheres.empty());
}

// Every distributed effect at once: the image does not depend on thread count or tile size.
TEST(DistributedEffects, DeterministicAcrossThreadsAndTiles) {
  Scene s;
  s.add(Plane({0, 1, 0}, 0, test::phong(Vec3(0.8), 0.1, 0.7, Vec3(0.3), 20)));
  Material glossy = test::mirror(0.7, Vec3(0.1));
  glossy.roughness = 0.3;
  Sphere moving({0, 0.5, 0}, 0.5, glossy);
  moving.motion = Motion::linear({0.4, 0, 0});
  s.add(std::move(moving));
  Material frosted = test::clear_glass(1.5);
  frosted.roughness = 0.2;
  s.add(Sphere({-1, 0.4, 0.5}, 0.4, frosted));
  s.add(rect_light({-1, 3, -1}, {0, 0, 2}, {2, 0, 0}, Vec3(4), 2));
  s.add(sphere_light({2, 2, 1}, 0.3, Vec3(8), 2));
  s.camera.position = {0, 1.5, 4};
  s.camera.look_at = {0, 0.4, 0};
  s.camera.aperture = 0.05;
  s.settings.width = 48;
  s.settings.height = 32;
  s.settings.supersample = 2;
  const Image one = test::render_image(s, 1, 32);
  const Image many = test::render_image(s, 4, 7);
  EXPECT_EQ(test::max_abs_diff(one, many), 0);
}

}  // namespace
}  // namespace strahl::motion_blur_test
