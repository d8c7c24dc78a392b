// Area lights: their samples follow the stated densities (chi-square), a fully lit point gets
// the analytic irradiance of a disk, a sphere and a rectangle, a fully shadowed point gets
// nothing, a half-occluded one about half; emitters are visible to camera rays.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "chi_square.h"
#include "strahl/sampling/rng.h"
#include "strahl/shading/area_light.h"
#include "strahl/shading/glossy.h"
#include "test_helpers.h"

namespace strahl::area_light_test {
namespace {

using test::chi_square;

// Six chi-square tests in this file, at an overall significance of 1%.
const double kAlpha = test::significance(0.01, 6);

std::string describe(const test::ChiSquare& r) {
  return "chi2 = " + std::to_string(r.statistic) + ", dof = " + std::to_string(r.dof) +
         ", p = " + std::to_string(r.p_value);
}

constexpr int kSamples = 200000;

Vec2 random2(std::uint32_t i) { return {random_real(7, 0, i, 0), random_real(7, 0, i, 1)}; }

Light compiled(const Light& l) {
  Scene s;
  s.add(Sphere({0, -100, 0}, 1, Vec3(1)));
  s.add(l);
  return compile(s).lights.at(0);
}

TEST(AreaLightSampling, RectIsUniformByArea) {
  const Light l = compiled(rect_light({-0.5, 2, -0.25}, {1, 0, 0}, {0, 0, 0.5}));
  EXPECT_VEC_NEAR(l.normal, Vec3(0, -1, 0), 1e-12);
  const Vec3 p(0.3, 0, 0.1);
  const int n = 10;
  std::vector<double> obs(n * n, 0), expected(n * n, 0);
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    const AreaLightSample s = sample_area_light(l, p, random2(i));
    const Vec3 q = s.point - l.position;
    const int a = std::min(n - 1, int(dot(q, l.edge_u) / length_squared(l.edge_u) * n));
    const int b = std::min(n - 1, int(dot(q, l.edge_v) / length_squared(l.edge_v) * n));
    obs[std::size_t(b * n + a)] += 1;
    for (int k = 0; k < n * n && i == 0; ++k) expected[std::size_t(k)] = kSamples * s.pdf * (0.5 / (n * n));
    ASSERT_NEAR(s.distance, length(s.point - p), 1e-12);
    ASSERT_NEAR(std::fabs(dot(q, l.normal)), 0, 1e-12);
  }
  const auto r = chi_square(obs, expected);
  EXPECT_GT(r.p_value, kAlpha) << describe(r);
}

TEST(AreaLightSampling, DiskIsUniformByArea) {
  const Real radius = 0.7;
  const Light l = compiled(disk_light({0, 2, 0}, {0, -1, 0.2}, radius));
  const Frame f = Frame::around(l.normal);
  const int n = 10;  // bins in (r/R)² and φ: equal areas
  std::vector<double> obs(n * n, 0), expected(n * n, 0);
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    const AreaLightSample s = sample_area_light(l, {0.2, 0, 0}, random2(i));
    const Vec3 q = s.point - l.position;
    ASSERT_NEAR(dot(q, l.normal), 0, 1e-12);
    const Real r2 = length_squared(q) / (radius * radius);
    ASSERT_LE(r2, 1 + 1e-12);
    const Real phi = std::atan2(dot(q, f.v), dot(q, f.u)) + kPi;
    const int a = std::min(n - 1, int(r2 * n)), b = std::min(n - 1, int(phi / (2 * kPi) * n));
    obs[std::size_t(b * n + a)] += 1;
    if (i == 0)
      for (double& e : expected) e = kSamples * s.pdf * (kPi * radius * radius / (n * n));
  }
  const auto r = chi_square(obs, expected);
  EXPECT_GT(r.p_value, kAlpha) << describe(r);
}

// Sphere lights: directions uniform in the cone the sphere subtends, with pdf 1/solid angle;
// bins reach past the cone's edge, where nothing may land.
TEST(AreaLightSampling, SphereFollowsTheConeDensity) {
  const Vec3 center(0.3, 3, -0.2), p(0, 0, 0);
  const Real radius = 1.2;
  const Light l = compiled(sphere_light(center, radius));
  const Vec3 axis = normalize(center - p);
  const Frame f = Frame::around(axis);
  const Real cos_max = std::sqrt(1 - radius * radius / length_squared(center - p));
  const int nc = 12, np = 8;
  const Real lo = cos_max - 2 * (1 - cos_max) / 10;  // two bins outside the cone
  std::vector<double> obs(nc * np, 0), expected(nc * np, 0);
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    const AreaLightSample s = sample_area_light(l, p, random2(i));
    ASSERT_NEAR(length(s.point - center), radius, 1e-9);
    ASSERT_NEAR(length(s.to_light), 1, 1e-12);
    const Real c = dot(s.to_light, axis);
    const Real phi = std::atan2(dot(s.to_light, f.v), dot(s.to_light, f.u)) + kPi;
    const int a = std::clamp(int((c - lo) / (1 - lo) * nc), 0, nc - 1), b = std::min(np - 1, int(phi / (2 * kPi) * np));
    obs[std::size_t(b * nc + a)] += 1;
  }
  // Expected: pdf × solid angle of the part of each bin inside the cone.
  const Real pdf = 1 / (2 * kPi * (1 - cos_max));
  for (int a = 0; a < nc; ++a) {
    const Real c0 = std::max(cos_max, lo + (1 - lo) * a / nc), c1 = lo + (1 - lo) * (a + 1) / nc;
    const Real omega = c1 > c0 ? (c1 - c0) * 2 * kPi / np : 0;
    for (int b = 0; b < np; ++b) expected[std::size_t(b * nc + a)] = kSamples * pdf * omega;
  }
  // Nothing outside the cone (pooling below would hide it).
  for (std::size_t i = 0; i < obs.size(); ++i) {
    if (expected[i] == 0) {
      EXPECT_EQ(obs[i], 0) << "bin " << i;
    }
  }
  const auto r = chi_square(obs, expected);
  EXPECT_GT(r.p_value, kAlpha) << describe(r);
}

// Bit for bit, as the render's image depends on it: -0 and 0 differ here (EXPECT_EQ on doubles
// would let them pass), so the bits are compared.
bool same_bits(Real a, Real b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

// AreaLightLanes (the shading loops': an area light's samples side by side, from one point or
// from a point per lane) gives each lane exactly what its point's AreaLightSampler::sample()
// gives it, for every kind of light, from points near and far, for the cone's rim (u.x → 1:
// grazing directions, where the tangent distance stands in), at the disk's centre, from behind
// the flat lights, at distance 0, and for a point inside a sphere light (no light).
TEST(AreaLightSampling, SamplesSideBySideEqualOneByOne) {
  const Light lights[] = {
      compiled(sphere_light({0.3, 3, -0.2}, 1.2)), compiled(sphere_light({-2, 0.5, 7}, 0.01)),
      compiled(sphere_light({1e3, -2e3, 5e2}, 40)),
      compiled(disk_light({0, 2, 0}, {0.2, -1, 0.1}, 0.5)),
      compiled(rect_light({-0.5, 2, -0.25}, {1, 0, 0}, {0, 0, 0.5}))};
  // Near and far, behind the disk and the rectangle, inside the first sphere, a corner of the
  // rectangle (distance 0 for u = (0, 0)).
  const Vec3 points[] = {{0, 0, 0},       {0.3, 1.8001, -0.2}, {5, -3, 2}, {-2.005, 0.5, 7},
                         {0.3, 3.5, -0.2}, {-0.5, 2, -0.25}};
  constexpr int kPoints = 6, kLanes = 4;
  int compared = 0, grazing = 0;
  for (const Light& l : lights) {
    // Each point in every lane (one point's strata), then the points spread over the lanes.
    for (int layout = 0; layout <= kPoints; ++layout) {
      Vec3 p[kLanes];
      Real px[kLanes], py[kLanes], pz[kLanes];
      for (int j = 0; j < kLanes; ++j) {
        p[j] = points[layout < kPoints ? layout : (j + 3 * j * j) % kPoints];
        px[j] = p[j].x, py[j] = p[j].y, pz[j] = p[j].z;
      }
      const AreaLightLanes<kLanes> lanes = layout < kPoints ? AreaLightLanes<kLanes>(l, p[0])
                                                           : AreaLightLanes<kLanes>(l, px, py, pz);
      for (std::uint32_t i = 0; i < 2000; ++i) {
        Vec2 u[kLanes];
        for (int j = 0; j < kLanes; ++j) u[j] = random2(kLanes * i + std::uint32_t(j));
        if (i % 3 == 0) u[i % 4].x = 1 - std::ldexp(Real(1), -int(i % 50));  // towards the rim
        if (i % 7 == 0) u[(i + 1) % 4] = {0.5, 0.5};                             // the disk's centre
        if (i % 5 == 0) u[(i + 2) % 4] = {0, 0};                                 // the corner
        Real ux[kLanes], uy[kLanes], tx[kLanes], ty[kLanes], tz[kLanes], distance[kLanes], ir[kLanes], ig[kLanes],
            ib[kLanes];
        for (int j = 0; j < kLanes; ++j) ux[j] = u[j].x, uy[j] = u[j].y;
        lanes.sample(ux, uy, tx, ty, tz, distance, ir, ig, ib);
        for (int j = 0; j < kLanes; ++j) {
          const AreaLightSampler sampler(l, p[j]);
          const AreaLightSample one = sampler.sample(u[j]);
          ASSERT_TRUE(same_bits(Vec3(tx[j], ty[j], tz[j]), one.to_light) && same_bits(distance[j], one.distance) &&
                      same_bits(Vec3(ir[j], ig[j], ib[j]), one.intensity))
              << "light " << &l - lights << " layout " << layout << " sample " << i << " lane " << j;
          const AreaLightSample old = sample_area_light(l, p[j], u[j]);
          ASSERT_TRUE(same_bits(old.point, one.point) && same_bits(old.distance, one.distance));
          if (l.kind == LightKind::Sphere && sampler.lit()) {
            const kernel::Sphere sphere{l.position, l.radius, 0};
            grazing += int(kernel::intersect(sphere, Ray{p[j], one.to_light}, 0, kInfinity) == kInfinity);
          }
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 5 * (kPoints + 1) * 2000 * kLanes);
  EXPECT_GT(grazing, 0);  // the tangent fallback was compared too
  // Inside a sphere light: not lit, every sample dark.
  const AreaLightSampler inside(lights[0], {0.3, 3.5, -0.2});
  EXPECT_FALSE(inside.lit());
  EXPECT_TRUE(is_black(inside.sample({0.5, 0.5}).intensity));
}

TEST(GlossySampling, PhongLobeFollowsItsDensity) {
  for (const Real roughness : {0.2, 0.6, 1.0}) {
    const Real e = glossy_exponent(roughness);
    const Vec3 axis = normalize(Vec3(0.3, 1, -0.4));
    const Frame f = Frame::around(axis);
    const int nc = 10, np = 6;
    std::vector<double> obs(nc * np, 0), expected(nc * np, 0);
    for (std::uint32_t i = 0; i < kSamples; ++i) {
      const Vec3 d = sample_phong_lobe(axis, e, random2(i));
      const Real c = dot(d, axis);
      const Real phi = std::atan2(dot(d, f.v), dot(d, f.u)) + kPi;
      const int a = std::clamp(int(c * nc), 0, nc - 1), b = std::min(np - 1, int(phi / (2 * kPi) * np));
      obs[std::size_t(b * nc + a)] += 1;
    }
    // ∫ (e + 1)/(2π) c^e dc dφ over a bin = (c1^(e+1) − c0^(e+1)) Δφ/(2π)
    for (int a = 0; a < nc; ++a)
      for (int b = 0; b < np; ++b)
        expected[std::size_t(b * nc + a)] =
            kSamples * (std::pow(Real(a + 1) / nc, e + 1) - std::pow(Real(a) / nc, e + 1)) / np;
    const auto r = chi_square(obs, expected);
    EXPECT_GT(r.p_value, kAlpha) << "roughness " << roughness << ": " << describe(r);
  }
}

// ---- irradiance at a point on the floor y = 0, seen by one camera ray from the side ----

// One pixel so narrow that all its samples see the origin.
void narrow_camera(Scene& s, const Vec3& eye) {
  test::set_camera(s, eye, {0, 0, 0}, {0, 1, 0}, -1e-7, 1e-7, -1e-7, 1e-7, 1, 1, 1);
}

// Floor with k_d = 1, colour 1 and nothing else: its radiance is E/π (shading/area_light.h).
Scene floor_scene(const Light& light) {
  Scene s;
  s.add(Plane({0, 1, 0}, 0, test::phong(Vec3(1), 0, 1, Vec3(0), 1)));
  s.add(light);
  narrow_camera(s, {2, 0.3, 0.05});
  s.settings.supersample = 4;  // 16 camera samples, each with its own light samples
  return s;
}

TEST(AreaLightShading, DiskOnAxisGivesTheAnalyticIrradiance) {
  const Real h = 1, r = 0.5, L = 3;
  const Vec3 c = test::pixel(floor_scene(disk_light({0, h, 0}, {0, -1, 0}, r, Vec3(L), 32)));
  // E = π L r²/(r² + h²)
  EXPECT_NEAR(c.x, L * r * r / (r * r + h * h), 0.005 * L * r * r / (r * r + h * h));
}

TEST(AreaLightShading, SphereGivesTheAnalyticIrradiance) {
  const Real d = 2, r = 0.6, L = 2;
  const Vec3 c = test::pixel(floor_scene(sphere_light({0, d, 0}, r, Vec3(L), 32)));
  // A sphere wholly above the horizon: E = π L (r/d)²
  EXPECT_NEAR(c.x, L * r * r / (d * d), 0.005 * L * r * r / (d * d));
}

// Form factor from a point to a parallel rectangle a × b at height h with a corner above it.
Real corner_form_factor(Real a, Real b, Real h) {
  const Real x = a / h, y = b / h;
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
         (2 * kPi);
}

TEST(AreaLightShading, RectangleGivesTheAnalyticIrradiance) {
  const Real a = 1.2, b = 0.8, h = 1.5, L = 4;
  // Centred above the point: four corner rectangles. Edges chosen so that u × v points down.
  const Vec3 c = test::pixel(floor_scene(rect_light({-a / 2, h, -b / 2}, {a, 0, 0}, {0, 0, b}, Vec3(L), 32)));
  const Real expected = L * 4 * corner_form_factor(a / 2, b / 2, h);
  EXPECT_NEAR(c.x, expected, 0.005 * expected);
}

TEST(AreaLightShading, PowerSetsTheRadiance) {
  Light l = disk_light({0, 1, 0}, {0, -1, 0}, 0.5);
  const Real power = 10;
  EXPECT_NEAR(radiance_from_power(l, power), power / (kPi * kPi * 0.25), 1e-12);
  l = sphere_light({0, 1, 0}, 0.5);
  EXPECT_NEAR(radiance_from_power(l, power), power / (kPi * 4 * kPi * 0.25), 1e-12);
}

TEST(AreaLightShading, FullyShadowedPointGetsNothing) {
  Scene s = floor_scene(disk_light({0, 1, 0}, {0, -1, 0}, 0.5, Vec3(3), 8));
  s.add(Triangle({-5, 0.5, -5}, {5, 0.5, -5}, {0, 0.5, 5}, Vec3(1)));  // covers the light
  narrow_camera(s, {0.3, 0.2, 0});
  EXPECT_EQ(test::pixel(s), Vec3(0));
}

// A blocker covering the half-space x < 0 halfway up hides half of the (symmetric) disk.
TEST(AreaLightShading, HalfOccludedPointGetsHalf) {
  const Light light = disk_light({0, 1, 0}, {0, -1, 0}, 0.5, Vec3(3), 16);
  const Vec3 full = test::pixel(floor_scene(light));
  Scene s = floor_scene(light);
  s.add(Triangle({0, 0.5, -50}, {0, 0.5, 50}, {-50, 0.5, 0}, Vec3(1)));
  const Vec3 half = test::pixel(s);
  // 16 camera samples × 256 light samples: a fraction's standard deviation is at most
  // 0.5/√4096 ≈ 0.008 (stratification only lowers it); 4σ.
  EXPECT_NEAR(half.x / full.x, 0.5, 0.032);
  EXPECT_GT(full.x, 0);
}

TEST(AreaLightShading, EmittersAreVisibleFromTheirFrontOnly) {
  Scene s;
  s.add(Sphere({0, -100, 0}, 1, Vec3(1)));
  s.add(disk_light({0, 0, 0}, {0, 0, 1}, 0.5, Vec3(2, 3, 4)));
  s.settings.background = Vec3(0.25);
  test::one_ray_camera(s, {0.1, 0.1, 3}, {0.1, 0.1, 0});
  EXPECT_EQ(test::pixel(s), Vec3(2, 3, 4));
  test::one_ray_camera(s, {0.1, 0.1, -3}, {0.1, 0.1, 0});
  EXPECT_EQ(test::pixel(s), Vec3(0.25));  // its back
  s.add(sphere_light({0, 0, -5}, 1, Vec3(5)));
  test::one_ray_camera(s, {0, 0, -10}, {0, 0, 0});
  EXPECT_EQ(test::pixel(s), Vec3(5));
}

// A mirror shows the light: the mirror ray meeting the emitter returns L, weighted by k_r.
TEST(AreaLightShading, EmittersAreVisibleInMirrors) {
  Scene s;
  s.add(Plane({0, 1, 0}, 0, test::mirror(0.5)));
  s.add(rect_light({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, Vec3(4, 2, 1)));  // faces down
  test::one_ray_camera(s, {-0.25, 1, 0}, {0, 0, 0});  // reflected towards (0.5, 2, 0)
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(2, 1, 0.5), 1e-12);
  test::one_ray_camera(s, {-1, 1, 0}, {0, 0, 0});  // reflected past the light's edge
  EXPECT_EQ(test::pixel(s), Vec3(0));
}

// Light shapes cast no shadow: a sphere light between a point light and the floor blocks nothing.
TEST(AreaLightShading, LightShapesCastNoShadows) {
  Scene s;
  s.add(Plane({0, 1, 0}, 0, test::phong(Vec3(1), 0, 1, Vec3(0), 1)));
  s.add(point_light({0, 4, 0}));
  s.add(sphere_light({0, 2, 0}, 0.5, Vec3(0)));
  test::one_ray_camera(s, {2, 0.3, 0.05}, {0, 0, 0});
  EXPECT_NEAR(test::pixel(s).x, 1, 1e-12);
}

TEST(AreaLightShading, StratifiedSamplesAreDeterministic) {
  const Scene s = floor_scene(rect_light({-0.5, 1, -0.5}, {0, 0, 1}, {1, 0, 0}, Vec3(2), 3));
  EXPECT_EQ(test::pixel(s), test::pixel(s));
}

}  // namespace
}  // namespace strahl::area_light_test
