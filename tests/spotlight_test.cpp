// Spotlights (POV-Ray's `spotlight`, shading/light.h spot_factor): the share of the light that
// leaves towards a point at angle θ from the axis is cos^tightness θ, times a cubic step in cos θ
// between the falloff and the full-light angle, 0 beyond the falloff and behind the light. Checked
// against values worked out by hand, through a rendered pixel (Lambert + Blinn-Phong times the
// share, as the lecture's formulas with I scaled), and through the shadow rays it saves.

#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.h"

namespace strahl::spotlight_test {
namespace {

// The compiled light (compile() takes the cosines of the angles and normalises the axis).
Light compiled(const Light& l) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.add(Sphere({0, 0, -3}, 1, Vec3(0.5)));
  s.add(l);
  return compile(s).lights.at(0);
}

// The share towards a point θ degrees off the axis of a spot at the origin aimed down −z.
Real share_at(const Light& spot, Real theta_degrees) {
  const Real a = test::deg(theta_degrees);
  const Vec3 from_light(std::sin(a), 0, -std::cos(a));  // the way from the light to the point
  return spot_factor(spot, -from_light);
}

TEST(Spotlight, ShareIsPovRaysAttenuation) {
  const Light spot = compiled(spot_light(Vec3(0), Vec3(0, 0, -2)));  // angle 30, falloff 45, tightness 0
  EXPECT_DOUBLE_EQ(spot.cos_angle, std::cos(kPi / 6));
  EXPECT_DOUBLE_EQ(spot.cos_falloff, std::sqrt(0.5));
  EXPECT_EQ(spot.direction, Vec3(0, 0, -1));
  EXPECT_EQ(share_at(spot, 0), 1);
  EXPECT_EQ(share_at(spot, 29.9), 1);  // full light within the angle
  EXPECT_EQ(share_at(spot, 45.1), 0);  // none beyond the falloff
  EXPECT_EQ(share_at(spot, 120), 0);   // nor behind the light
  // Halfway between the two cosines the cubic step (3 − 2x)·x² is 1/2; a quarter of the way
  // from the falloff, 5/32.
  const Real c30 = std::cos(kPi / 6), c45 = std::sqrt(0.5);
  for (const auto& [x, step] : {std::pair{0.5, 0.5}, std::pair{0.25, 5.0 / 32}, std::pair{0.75, 27.0 / 32}}) {
    const Real c = c45 + x * (c30 - c45);
    const Vec3 from_light(std::sqrt(1 - c * c), 0, -c);
    EXPECT_NEAR(spot_factor(spot, -from_light), step, 1e-12) << "x = " << x;
  }
  // The share falls steadily from 1 to 0 across the edge, without a jump: 0.01° apart, shares
  // differ by at most the step's steepest slope, 3/2 per unit of x, times the change of x,
  // sin θ·Δθ/(cos 30° − cos 45°) ≈ 0.0011 here.
  Real last = 1;
  for (Real theta = 25; theta <= 50; theta += 0.01) {
    const Real s = share_at(spot, theta);
    EXPECT_LE(s, last) << theta;
    EXPECT_LT(last - s, 1.2e-3) << theta;
    last = s;
  }
  EXPECT_EQ(last, 0);

  // tightness: cos^tightness θ, inside the angle too.
  const Light tight = compiled(spot_light(Vec3(0), Vec3(0, 0, -1), 30, 45, 7));
  EXPECT_NEAR(share_at(tight, 0), 1, 1e-15);
  EXPECT_NEAR(share_at(tight, 20), std::pow(std::cos(test::deg(20)), 7), 1e-15);
  // A falloff inside the angle: a hard edge at the angle.
  const Light hard = compiled(spot_light(Vec3(0), Vec3(0, 0, -1), 30, 20));
  EXPECT_EQ(share_at(hard, 29.9), 1);
  EXPECT_EQ(share_at(hard, 30.1), 0);
  // Angle and falloff 90: the whole half space ahead, cos^tightness θ (no step), nothing behind.
  const Light wide = compiled(spot_light(Vec3(0), Vec3(0, 0, -1), 90, 90, 2));
  EXPECT_NEAR(share_at(wide, 80), std::pow(std::cos(test::deg(80)), 2), 1e-15);
  EXPECT_EQ(share_at(wide, 91), 0);
  // Other lights are not spots: their share is 1 whatever the direction.
  EXPECT_EQ(spot_factor(compiled(point_light(Vec3(0, 5, 0))), Vec3(0, -1, 0)), 1);
}

// The camera's one ray meets a sphere at P = (0, 0, −2), N = V = (0, 0, 1); the spot sits on a
// ray from P at 30° to N and is turned θ off P: the pixel is the lecture's terms with I × share.
TEST(Spotlight, PixelIsLambertAndBlinnPhongTimesTheShare) {
  const Vec3 color(0.8, 0.4, 0.2), ks(0.5, 0.6, 0.7);
  const Real a = test::deg(30);
  const Vec3 p(0, 0, -2), to_light(std::sin(a), 0, std::cos(a)), light = p + to_light * 5;
  const Light reference = compiled(spot_light(Vec3(0), Vec3(0, 0, -1), 20, 40, 3));
  int lit = 0, dark = 0, edge = 0;
  for (Real theta = 1.25; theta < 52; theta += 2.5) {  // never on an edge
    const Real t = test::deg(theta);
    const Vec3 d = -to_light;  // aimed at P, then turned θ about y
    const Vec3 axis(d.x * std::cos(t) + d.z * std::sin(t), 0, -d.x * std::sin(t) + d.z * std::cos(t));
    Scene s;
    test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
    s.add(Sphere({0, 0, -3}, 1, test::phong(color, 0.1, 0.7, ks, 20)));
    s.add(spot_light(light, axis, 20, 40, 3, Vec3(1, 0.5, 0.25), 2));
    const Real share = share_at(reference, theta);
    const Vec3 expected = color * 0.1 + (color * (0.7 * std::cos(a)) + ks * std::pow(std::cos(a / 2), 20)) *
                                            Vec3(2, 1, 0.5) * share;
    RayCounters counters;
    EXPECT_VEC_NEAR(test::pixel(s, 0, 0, &counters), expected, 1e-12) << theta << "°";
    // No shadow ray where the spot sends no light.
    EXPECT_EQ(counters.shadow, share > 0 ? 1u : 0u) << theta << "°";
    if (theta < 20) {
      EXPECT_NEAR(share, std::pow(std::cos(t), 3), 1e-15) << theta << "°";
    }
    (share == 0 ? dark : theta < 20 ? lit : edge) += 1;
  }
  EXPECT_EQ(lit, 8);   // θ = 1.25 … 18.75
  EXPECT_EQ(edge, 8);  // 21.25 … 38.75
  EXPECT_EQ(dark, 5);  // 41.25 … 51.25
}

// POV-Ray's fade, of point and spot lights: 2/(1 + (d/fade_distance)^fade_power), times the
// spot's share. The light sits 5 from P, as above.
TEST(Spotlight, FadeWithDistanceIsPovRays) {
  const Vec3 color(0.8, 0.4, 0.2);
  const Real a = test::deg(30);
  const Vec3 p(0, 0, -2), to_light(std::sin(a), 0, std::cos(a)), at = p + to_light * 5;
  const Vec3 lambert = color * (0.7 * std::cos(a));
  const auto pixel = [&](const Light& l) {
    Scene s;
    test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
    s.add(Sphere({0, 0, -3}, 1, test::phong(color, 0.1, 0.7, Vec3(0), 20)));
    s.add(l);
    return test::pixel(s);
  };
  const auto faded = [](Light l, Real distance, Real power) {
    l.fade_distance = distance;
    l.fade_power = power;
    return l;
  };
  const Light point = point_light(at);
  EXPECT_VEC_NEAR(pixel(point), color * 0.1 + lambert, 1e-14);
  EXPECT_VEC_NEAR(pixel(faded(point, 2.5, 2)), color * 0.1 + lambert * 0.4, 1e-14);       // 2/(1 + 2²)
  EXPECT_VEC_NEAR(pixel(faded(point, 5, 1.5)), color * 0.1 + lambert, 1e-14);             // at fade_distance: 1
  EXPECT_VEC_NEAR(pixel(faded(point, 10, 1)), color * 0.1 + lambert * (4.0 / 3), 1e-14);  // 2/(1 + 1/2)
  EXPECT_VEC_NEAR(pixel(faded(point, 2.5, 0)), color * 0.1 + lambert, 1e-14);             // power 0: no fade
  // A spot's share times the fade: aimed at P (share cos² 0 = 1), then turned 30° (on its step).
  EXPECT_VEC_NEAR(pixel(faded(spot_light(at, -to_light, 20, 40, 2), 2.5, 2)), color * 0.1 + lambert * 0.4, 1e-14);
  const Real t = test::deg(30);
  const Vec3 d = -to_light, turned(d.x * std::cos(t) + d.z * std::sin(t), 0, -d.x * std::sin(t) + d.z * std::cos(t));
  const Real share = share_at(compiled(spot_light(Vec3(0), Vec3(0, 0, -1), 20, 40, 2)), 30);
  EXPECT_GT(share, 0.1);
  EXPECT_LT(share, 0.9);
  EXPECT_VEC_NEAR(pixel(faded(spot_light(at, turned, 20, 40, 2), 2.5, 2)), color * 0.1 + lambert * (share * 0.4), 1e-12);
  // Only point and spot lights fade, and only with a fade_distance.
  for (const Light& l : {faded(directional_light(Vec3(0, -1, 0)), 1, 2), faded(point, 0, 2)}) {
    Scene s;
    s.add(l);
    EXPECT_THROW(compile(s), Error);
  }
}

}  // namespace
}  // namespace strahl::spotlight_test
