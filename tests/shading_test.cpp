// Local illumination of one pixel against the lecture's formulas:
//   ambient  k_a·C·ambient_light
//   Lambert  k_d·C·max(0, N·L)·I
//   Blinn-Phong  k_s·max(0, N·H)^n·I,  H = (L + V)/|L + V|
// per unshadowed light, all additive. The camera's single ray runs from the origin down −z onto
// a sphere at (0, 0, −3) of radius 1: hit point P = (0, 0, −2), normal N = V = (0, 0, 1).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "test_helpers.h"
#include "test_random.h"

namespace strahl::shading_test {
namespace {

const Vec3 kP(0, 0, -2);
const Vec3 kN(0, 0, 1);
const Vec3 kColor(0.8, 0.4, 0.2);

Scene base_scene(const Material& m) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.add(Sphere({0, 0, -3}, 1, m));
  return s;
}

TEST(Shading, AmbientOnlyWithoutLights) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0.6), 100));
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1, 1e-15);
  s.settings.ambient_light = {0.5, 1, 2};
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(0.8 * 0.1 * 0.5, 0.4 * 0.1 * 1, 0.2 * 0.1 * 2), 1e-15);
}

TEST(Shading, BackgroundWhereNothingIsHit) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0.6), 100));
  s.camera.look_at = {0, 0, 1};  // looking away from the sphere
  s.settings.background = {0.1, 0.2, 0.3};
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(0.1, 0.2, 0.3), 0);
}

TEST(Shading, LambertPixel) {
  // Light at (3, 0, 1): L = (3, 0, 3)/√18 = (1, 0, 1)/√2, N·L = 1/√2.
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 100));
  s.add(point_light({3, 0, 1}, {1, 0.5, 0.25}, 2));
  const Vec3 I(2, 1, 0.5);
  const Vec3 expected = kColor * 0.1 + kColor * I * (0.7 / std::sqrt(2.0));
  EXPECT_VEC_NEAR(test::pixel(s), expected, 1e-14);
}

TEST(Shading, LambertFollowsCosineOverManyAngles) {
  for (int deg = 0; deg < 90; deg += 10) {
    const Real a = test::deg(deg);
    const Vec3 L(std::sin(a), 0, std::cos(a));
    Scene s = base_scene(test::phong(kColor, 0, 1, Vec3(0), 1));
    s.add(point_light(kP + L * 5));
    EXPECT_VEC_NEAR(test::pixel(s), kColor * std::cos(a), 1e-14) << deg << "°";
  }
}

TEST(Shading, LightBehindTheSurfaceGivesAmbientOnly) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0.6), 10));
  s.add(directional_light({0, 0, 1}));  // travelling +z: it lights the far side only
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1, 1e-15);
}

TEST(Shading, BlinnPhongHighlight) {
  // L = (1,0,1)/√2, V = (0,0,1): H = (sin 22.5°, 0, cos 22.5°), N·H = cos 22.5° = cos(π/8).
  for (Real n : {1.0, 20.0, 100.0, 120.0, 12.5, 0.5, 0.0}) {
    Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0.5, 0.6, 0.7), n));
    s.add(point_light({3, 0, 1}));
    const Real nh = std::cos(kPi / 8);
    const Vec3 expected = kColor * 0.1 + kColor * (0.7 / std::sqrt(2.0)) + Vec3(0.5, 0.6, 0.7) * std::pow(nh, n);
    EXPECT_VEC_NEAR(test::pixel(s), expected, 1e-14) << "shininess " << n;
  }
}

TEST(Shading, MirrorConfigurationGivesFullHighlight) {
  // Light straight above the hit point along N = V: N·H = 1, so the highlight is k_s exactly.
  Scene s = base_scene(test::phong(kColor, 0, 0, Vec3(0.3, 0.2, 0.1), 1000));
  s.add(point_light({0, 0, 5}));
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(0.3, 0.2, 0.1), 1e-15);
}

TEST(Shading, HighlightOfAnObliqueViewer) {
  // Camera at (0, 2, 0) looking at P (its ray meets the sphere first there): V = (0, 1, 1)/√2;
  // the light straight above P along N, so L = N and H = (N + V)/|N + V|.
  Scene s;
  test::one_ray_camera(s, {0, 2, 0}, kP);
  s.add(Sphere({0, 0, -3}, 1, test::phong(kColor, 0, 0, Vec3(1), 7)));
  s.add(point_light(kP + Vec3(0, 0, 4)));
  const Vec3 V = normalize(Vec3(0, 2, 2));
  const Vec3 H = normalize(kN + V);
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(std::pow(dot(kN, H), 7)), 1e-12);
}

TEST(Shading, ShadowedPixelIsAmbientOnly) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0.6), 20));
  s.add(point_light({3, 0, 1}));
  // A blocker on the segment from P to the light (not seen by the camera ray).
  s.add(Sphere({1.5, 0, -0.5}, 0.2, test::phong(Vec3(1), 0.1, 0.7, Vec3(0), 1)));
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1, 1e-15);
}

TEST(Shading, BlockerBeyondThePointLightCastsNoShadow) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 20));
  s.add(point_light({3, 0, 1}));
  s.add(Sphere({6, 0, 4}, 0.5, Vec3(1)));  // on the same line, but behind the light
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1 + kColor * (0.7 / std::sqrt(2.0)), 1e-14);
}

TEST(Shading, PlaneBlockerCastsShadow) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 20));
  s.add(point_light({3, 0, 1}));
  s.add(Plane({1, 0, 0}, 1, Vec3(1)));  // x = 1 lies between P and the light
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1, 1e-15);
}

TEST(Shading, TriangleBlockerCastsShadow) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 20));
  s.add(point_light({3, 0, 1}));
  s.add(Triangle({1.5, -1, -1.5}, {1.5, 1, -1.5}, {1.5, 0, 1}, Vec3(1)));  // crosses the segment at (1.5, 0, −0.5)
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1, 1e-15);
}

TEST(Shading, TwoLightsAreAdditive) {
  const Material m = test::phong(kColor, 0.1, 0.7, Vec3(0.4), 30);
  const Light a = point_light({3, 0, 1}, {1, 0.9, 0.8});
  const Light b = point_light({-1, 2, 2}, {0.2, 0.5, 1}, 1.5);
  Scene none = base_scene(m), only_a = base_scene(m), only_b = base_scene(m), both = base_scene(m);
  only_a.add(a);
  only_b.add(b);
  both.add(a);
  both.add(b);
  const Vec3 amb = test::pixel(none);
  const Vec3 pa = test::pixel(only_a), pb = test::pixel(only_b), pab = test::pixel(both);
  EXPECT_VEC_NEAR(pab - amb, (pa - amb) + (pb - amb), 1e-14);
  // And each light by hand.
  const auto term = [&](const Light& l) {
    const Vec3 L = normalize(l.position - kP), H = normalize(L + kN);
    return (kColor * (0.7 * dot(kN, L)) + Vec3(0.4) * std::pow(dot(kN, H), 30)) * l.radiance;
  };
  EXPECT_VEC_NEAR(pab, kColor * 0.1 + term(a) + term(b), 1e-14);
}

TEST(Shading, ShadowOfOneLightLeavesTheOther) {
  const Material m = test::phong(kColor, 0.1, 0.7, Vec3(0), 1);
  Scene s = base_scene(m);
  s.add(point_light({3, 0, 1}));
  s.add(point_light({-3, 0, 1}));
  s.add(Sphere({1.5, 0, -0.5}, 0.2, Vec3(1)));  // blocks only the first
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1 + kColor * (0.7 / std::sqrt(2.0)), 1e-14);
}

TEST(Shading, DirectionalLightIsLikeAPointLightAtInfinity) {
  // Travelling along (−2, 0, −2): towards the light is (1, 0, 1)/√2 as for the point light at (3, 0, 1).
  const Material m = test::phong(kColor, 0.1, 0.7, Vec3(0.5), 20);
  Scene dir = base_scene(m), point = base_scene(m);
  dir.add(directional_light({-2, 0, -2}, {1, 1, 0.5}, 2));
  point.add(point_light({3, 0, 1}, {1, 1, 0.5}, 2));
  EXPECT_VEC_NEAR(test::pixel(dir), test::pixel(point), 1e-14);
  const Real nh = std::cos(kPi / 8);
  const Vec3 expected = kColor * 0.1 + (kColor * (0.7 / std::sqrt(2.0)) + Vec3(0.5) * std::pow(nh, 20)) * Vec3(2, 2, 1);
  EXPECT_VEC_NEAR(test::pixel(dir), expected, 1e-14);
}

TEST(Shading, DirectionalLightIsShadowedByAFarAwayBlocker) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 1));
  s.add(directional_light({-1, 0, -1}));
  s.add(Sphere(kP + normalize(Vec3(1, 0, 1)) * 1000, 1, Vec3(1)));
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1, 1e-15);
}

TEST(Shading, PointLightHasNoDistanceFalloff) {
  Scene near = base_scene(test::phong(kColor, 0, 1, Vec3(0), 1));
  Scene far = base_scene(test::phong(kColor, 0, 1, Vec3(0), 1));
  near.add(point_light(kP + Vec3(1, 0, 1)));
  far.add(point_light(kP + Vec3(100, 0, 100)));
  EXPECT_VEC_NEAR(test::pixel(near), test::pixel(far), 1e-14);
}

TEST(Shading, HalfTransparentOccluderAttenuatesPerSurfaceCrossing) {
  // A shadow ray through a sphere of transparency T crosses two surfaces: factor T² (T·C per
  // crossing when filtering). The occluder is not seen by the camera ray.
  Material occ = test::phong(Vec3(1, 0.5, 0.25), 0.1, 0.7, Vec3(0), 1);
  occ.transparency = 0.5;
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 1));
  s.add(point_light({3, 0, 1}));
  s.add(Sphere({1.5, 0, -0.5}, 0.2, occ));
  const Vec3 lambert = kColor * (0.7 / std::sqrt(2.0));
  EXPECT_VEC_NEAR(test::pixel(s), kColor * 0.1 + lambert * 0.25, 1e-14);

  occ.filter = true;
  Scene f = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 1));
  f.add(point_light({3, 0, 1}));
  f.add(Sphere({1.5, 0, -0.5}, 0.2, occ));
  const Vec3 per_crossing = Vec3(1, 0.5, 0.25) * 0.5;
  EXPECT_VEC_NEAR(test::pixel(f), kColor * 0.1 + lambert * per_crossing * per_crossing, 1e-14);
}

TEST(Shading, CheckerboardPlaneAlternatesBetweenItsTwoColours) {
  // Looking straight down at y = 0 from y = 10 with a 4×4 image whose pixel centres land on the
  // centres of the unit squares x, z ∈ {−1.5, −0.5, 0.5, 1.5}.
  Material m = test::emissive_like({0.9, 0.8, 0.7});
  m.checker_size = 1;
  m.checker_color = {0.1, 0.2, 0.3};
  Scene s;
  test::set_camera(s, {0, 10, 0}, {0, 0, 0}, {0, 0, -1}, -2, 2, -2, 2, 10, 4, 4);
  s.add(Plane({0, 1, 0}, 0, m));
  const Image img = test::render_image(s);
  const Vec3 first = test::to_vec(img.at(0, 0));
  const bool first_is_color = first == Vec3(Real(0.9f), Real(0.8f), Real(0.7f));
  EXPECT_TRUE(first_is_color || first == Vec3(Real(0.1f), Real(0.2f), Real(0.3f)));
  for (int row = 0; row < 4; ++row)
    for (int x = 0; x < 4; ++x) {
      const bool same_as_first = (x + row) % 2 == 0;
      const Vec3 expected = same_as_first == first_is_color ? Vec3(0.9, 0.8, 0.7) : Vec3(0.1, 0.2, 0.3);
      EXPECT_VEC_NEAR(test::to_vec(img.at(x, row)), expected, 1e-6) << "x=" << x << " row=" << row;
    }
}

TEST(Shading, CheckerSizeScalesTheSquares) {
  // Squares of size 2: pixel centres at ±0.5 and ±1.5 pair up, so columns 0,1 share a colour.
  Material m = test::emissive_like({1, 1, 1});
  m.checker_size = 2;
  m.checker_color = {0, 0, 0};
  Scene s;
  test::set_camera(s, {0, 10, 0}, {0, 0, 0}, {0, 0, -1}, -2, 2, -2, 2, 10, 4, 4);
  s.add(Plane({0, 1, 0}, 0, m));
  const Image img = test::render_image(s);
  for (int row = 0; row < 4; ++row)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(img.at(x, row), img.at(x ^ 1, row ^ 1)) << x << "," << row;  // same 2×2 block
      EXPECT_NE(img.at(x, row), img.at((x + 2) % 4, row)) << x << "," << row;  // neighbouring block
    }
}

TEST(Shading, SolidCheckerOnSphereUsesThePointsCoordinates) {
  // P = (0, 0, −2): with size 0.75, floor(0) + floor(0) + floor(−2.67) = −3 is odd → checker colour;
  // with size 0.6, floor(−3.33) = −4 is even → the base colour.
  for (const auto& [size, expected] : {std::pair{0.75, Vec3(0.1, 0.2, 0.3)}, std::pair{0.6, Vec3(0.9, 0.8, 0.7)}}) {
    Material m = test::emissive_like({0.9, 0.8, 0.7});
    m.checker_size = size;
    m.checker_color = {0.1, 0.2, 0.3};
    EXPECT_VEC_NEAR(test::pixel(base_scene(m)), expected, 1e-15) << "size " << size;
  }
}

// The checker's cell parity against whole-number arithmetic where that is exact, and defined
// (no conversion of an out-of-range cell index, which UBSan reports) for any size and point:
// issue 12's `checker: {size: 1e-300}`. Cells of magnitude 2^53 or more are even.
TEST(Shading, CheckerParityIsExactAndDefinedForAnySize) {
  Material m;
  m.color = {1, 1, 1};
  m.checker_color = {0, 0, 0};
  m.checker_size = 0.25;
  for (int i = -40; i <= 40; ++i)
    for (int j = -3; j <= 3; ++j) {
      const Vec3 p(i * 0.1 + 0.01, j * 0.3 + 0.01, -0.6);
      const long sum = long(std::floor(p.x / 0.25)) + long(std::floor(p.y / 0.25)) + long(std::floor(p.z / 0.25));
      EXPECT_EQ(surface_color(m, p, {}).x, (sum % 2 != 0) ? 0.0 : 1.0) << p.x << ", " << p.y;
    }
  for (const double size : {1e-300, 4.9e-324, 1e-30, 1e300}) {
    m.checker_size = size;
    for (const Vec3& p : {Vec3(0.3, 0.7, -0.1), Vec3(-1e200, 3e250, 0), Vec3(1e-300, -1e-300, 0)}) {
      const Vec3 c = surface_color(m, p, {});
      EXPECT_TRUE(c.x == 0 || c.x == 1) << "size " << size << " at " << p.x << ", " << p.y;
    }
  }
  m.checker_size = 1e-300;  // every cell index is a huge even number: the base colour
  EXPECT_EQ(surface_color(m, Vec3(0.3, 0.7, -0.1), {}).x, 1.0);
  m.checker_size = 1;  // −1 + 0 + 0: odd
  EXPECT_EQ(surface_color(m, Vec3(-0.5, 0.5, 0.5), {}).x, 0.0);
  // odd_cell against its definition, |fmod(floor(a), 2)| = 1, over every magnitude and sign, the
  // neighbours of 2^53 and the values that are no number.
  const auto odd_by_fmod = [](double a) { return std::fabs(std::fmod(std::floor(a), 2.0)) == 1.0; };
  std::vector<double> values = {0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.5, -2.5, 0x1p53, -0x1p53, 0x1p53 - 1, 1 - 0x1p53,
                                0x1p52 + 1.5, -0x1p52 - 1.5, 1e300, -1e300, 4.9e-324, -4.9e-324,
                                std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN()};
  test::Random random(12);
  for (int i = 0; i < 100000; ++i) values.push_back(random.uniform(-1, 1) * std::pow(2.0, random.uniform(-30, 60)));
  for (const double a : values) EXPECT_EQ(odd_cell(a), odd_by_fmod(a)) << a;
}

TEST(Shading, CheckerColourIsShadedLikeTheBaseColour) {
  // Lambert uses the checker colour at the point too.
  Material m = test::phong({0.9, 0.8, 0.7}, 0.1, 0.7, Vec3(0), 1);
  m.checker_size = 0.75;  // odd square at P, see above
  m.checker_color = {0.1, 0.2, 0.3};
  Scene s = base_scene(m);
  s.add(point_light({3, 0, 1}));
  const Vec3 c(0.1, 0.2, 0.3);
  EXPECT_VEC_NEAR(test::pixel(s), c * 0.1 + c * (0.7 / std::sqrt(2.0)), 1e-14);
}

TEST(Shading, OneShadowRayPerLightFacingThePoint) {
  Scene s = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 1));
  s.add(point_light({3, 0, 1}));            // faces P
  s.add(point_light({-1, 2, 2}));           // faces P
  s.add(directional_light({0, 0, 1}));      // behind P: no shadow ray
  RayCounters counters;
  test::pixel(s, 0, 0, &counters);
  EXPECT_EQ(counters.camera, 1u);
  EXPECT_EQ(counters.shadow, 2u);
  EXPECT_EQ(counters.reflection + counters.refraction, 0u);
}

TEST(Shading, HalfTransparentPlaneOrTriangleAttenuatesOnce) {
  Material half = test::phong(Vec3(1), 0.1, 0.7, Vec3(0), 1);
  half.transparency = 0.5;
  const Vec3 expected = kColor * 0.1 + kColor * (0.7 / std::sqrt(2.0)) * 0.5;
  Scene plane = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 1));
  plane.add(point_light({3, 0, 1}));
  plane.add(Plane({1, 0, 0}, 1, half));  // x = 1, between P and the light
  EXPECT_VEC_NEAR(test::pixel(plane), expected, 1e-14);
  Scene tri = base_scene(test::phong(kColor, 0.1, 0.7, Vec3(0), 1));
  tri.add(point_light({3, 0, 1}));
  tri.add(Triangle({1.5, -1, -1.5}, {1.5, 1, -1.5}, {1.5, 0, 1}, half));
  EXPECT_VEC_NEAR(test::pixel(tri), expected, 1e-14);
}

// Colour of the floor y = 0 straight below (x, z), seen by a one-ray camera from above.
Vec3 floor_color(const Material& m, Real x, Real z) {
  Scene s;
  test::one_ray_camera(s, {x, 1, z}, {x, 0, z}, {0, 0, -1});
  s.add(Plane({0, 1, 0}, 0, m));
  return test::pixel(s);
}

TEST(Shading, PlaneCheckerEdgesLieAtWholeMultiplesOfTheSize) {
  // On a floor the squares follow x and z, with edges at multiples of `size` (here 0.5).
  Material m = test::emissive_like({0.9, 0.8, 0.7});
  m.checker_size = 0.5;
  m.checker_color = {0.1, 0.2, 0.3};
  const Vec3 a = floor_color(m, 0.26, 0.25);
  EXPECT_TRUE(floor_color(m, 0.49, 0.25) == a);
  EXPECT_TRUE(floor_color(m, 0.26, 0.01) == a);
  EXPECT_TRUE(floor_color(m, 0.26, 0.49) == a);
  EXPECT_FALSE(floor_color(m, 0.51, 0.25) == a);   // across x = 0.5
  EXPECT_FALSE(floor_color(m, 0.26, 0.51) == a);   // across z = 0.5
  EXPECT_FALSE(floor_color(m, -0.01, 0.25) == a);  // across x = 0
  EXPECT_FALSE(floor_color(m, 0.26, -0.01) == a);  // across z = 0
  EXPECT_TRUE(floor_color(m, 0.51, 0.51) == a);   // diagonal neighbour
  EXPECT_TRUE(floor_color(m, 1.26, -0.74) == a);  // two squares along x, two along z
  EXPECT_TRUE(a == Vec3(0.9, 0.8, 0.7) || a == Vec3(0.1, 0.2, 0.3));
}

TEST(Shading, WallCheckerFollowsXAndY) {
  // A wall z = −3 facing +z: squares in x and y, edges at multiples of 1.
  Material m = test::emissive_like(Vec3(1));
  m.checker_size = 1;
  m.checker_color = Vec3(0);
  const auto wall = [&](Real x, Real y) {
    Scene s;
    test::one_ray_camera(s, {x, y, 0}, {x, y, -1});
    s.add(Plane({0, 0, 1}, -3, m));
    return test::pixel(s);
  };
  const Vec3 a = wall(0.5, 0.5);
  EXPECT_TRUE(wall(0.98, 0.02) == a);
  EXPECT_FALSE(wall(1.02, 0.5) == a);
  EXPECT_FALSE(wall(0.5, 1.02) == a);
  EXPECT_FALSE(wall(0.5, -0.02) == a);
  EXPECT_TRUE(wall(1.5, 1.5) == a);
}

TEST(Shading, SupersamplingAveragesSubpixelRays) {
  // 2×2 samples of one pixel at s_u, s_v = ±0.5; a large white triangle covers x < 0 only, so
  // two samples see white and two the black background.
  Scene s;
  test::set_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, -1, 1, -1, 1, 1, 1, 1);
  s.settings.supersample = 2;
  s.add(Triangle({0, -10, -5}, {0, 10, -5}, {-10, 0, -5}, test::emissive_like(Vec3(1))));
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(0.5), 1e-15);
  RayCounters counters;
  test::pixel(s, 0, 0, &counters);
  EXPECT_EQ(counters.camera, 4u);
}

}  // namespace
}  // namespace strahl::shading_test
