// Path tracing (render/path_tracer.h) against what can be computed: a convex diffuse sphere under
// a uniform sky (every bounce escapes: k_d·C times the sky, exactly), the inside of a closed
// diffuse sphere lit by a point light at its centre (the geometric series of interreflections,
// exactly up to the third hit, in the mean beyond it where Russian roulette decides), the ways
// on taken in proportion to their weights, area lights counted once, and — where every way on is
// a perfect mirror and nothing is ambient — Whitted's image.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "test_helpers.h"
#include "test_random.h"

namespace strahl::path_tracer_test {
namespace {

using test::vec_near;

Material matte(const Vec3& color, Real kd) {
  Material m;
  m.color = color;
  m.diffuse = kd;
  m.specular = Vec3(0);
  m.ambient = 0.5;  // Whitted's stand-in for the light a path tracer computes: not used by it
  return m;
}

// The mean radiance of pixel (x, row) as the renderer samples it.
Vec3 pixel_mean(const RenderScene& rs, int x, int row) {
  RayCounters counters;
  return render_pixel(rs.view(), x, row, rs.sampling, counters);
}

// A camera at `eye` looking at `target` with a narrow field of view, w×h pixels.
void look(Scene& s, const Vec3& eye, const Vec3& target, Real fov, int w, int h) {
  s.camera.position = eye;
  s.camera.look_at = target;
  s.camera.fov_degrees = fov;
  s.settings.width = w;
  s.settings.height = h;
}

TEST(PathTracer, ConvexSphereUnderAUniformSkyReflectsKdCTimesTheSkyExactly) {
  const Vec3 c{0.9, 0.5, 0.3}, sky{0.8, 1.0, 1.2};
  const Real kd = 0.7;
  Scene s;
  s.add(Sphere({0, 0, 0}, 1, matte(c, kd)));
  look(s, {0, 0, 4}, {0, 0, 0}, 10, 6, 6);  // every pixel on the sphere
  s.settings.background = sky;
  s.settings.integrator = IntegratorKind::Path;
  s.settings.sampling.sampler = SamplerKind::Random;
  s.settings.sampling.spp = 8;
  const RenderScene rs = compile(s);
  // The first way on is always taken: β = w_d·(Σa/a_d) = k_d·C (Σa = a_d); the bounce leaves the
  // convex sphere and meets the sky, whatever direction was drawn.
  const Vec3 expected = c * kd * sky;
  for (int row = 0; row < 6; ++row)
    for (int x = 0; x < 6; ++x) EXPECT_TRUE(vec_near(pixel_mean(rs, x, row), expected, 1e-14)) << x << ", " << row;
  // Whitted's image of it: the ambient term only (no lights), k_a·C·ambient_light.
  s.settings.integrator = IntegratorKind::Whitted;
  EXPECT_TRUE(vec_near(pixel_mean(compile(s), 2, 3), c * 0.5, 1e-14));
}

// The inside of a diffuse sphere (albedo ρ, radius 2) with a point light of intensity 1 at its
// centre: every hit gets direct light ρ·(N·L) = ρ, and every bounce meets the sphere again, so a
// path of D hits brings ρ·(1 + ρ + … + ρ^(D−1)).
// (`glow`: the sphere's emission, without the light.)
Scene lit_cavity(Real rho, int max_depth, const Vec3& glow = Vec3(0)) {
  Scene s;
  Material m = matte(Vec3(1), rho);
  m.emission = glow;
  s.add(Sphere({0, 0, 0}, 2, m));
  if (is_black(glow)) s.add(point_light({0, 0, 0}));
  look(s, {0.3, -0.2, 0.5}, {0.5, 0.1, -1}, 50, 16, 16);
  s.settings.integrator = IntegratorKind::Path;
  s.settings.max_depth = max_depth;
  s.settings.sampling.sampler = SamplerKind::Random;
  return s;
}

TEST(PathTracer, LitCavityUpToThreeHitsIsTheGeometricSeriesExactly) {
  const Real rho = 0.6;
  for (int depth = 1; depth <= 3; ++depth) {
    Scene s = lit_cavity(rho, depth);
    s.settings.sampling.spp = 4;
    const RenderScene rs = compile(s);
    Real expected = 0, term = rho;
    for (int k = 0; k < depth; ++k, term *= rho) expected += term;
    for (const auto& [x, row] : {std::pair{0, 0}, std::pair{7, 9}, std::pair{15, 15}})
      EXPECT_TRUE(vec_near(pixel_mean(rs, x, row), Vec3(expected), 1e-12)) << "max_depth " << depth;
  }
}

TEST(PathTracer, AGlowingCavityIsTheGeometricSeriesOfItsEmission) {
  // No lights: the inside of a sphere of albedo ρ emitting E. Every hit adds E, and every bounce
  // meets the sphere again: D hits bring E·(1 + ρ + … + ρ^(D−1)). Whitted's integrator shows E
  // and the ambient term only.
  const Real rho = 0.7;
  const Vec3 e{0.5, 1, 2};
  for (int depth = 1; depth <= 3; ++depth) {
    Scene s = lit_cavity(rho, depth, e);
    s.settings.sampling.spp = 4;
    const RenderScene rs = compile(s);
    Real series = 0, term = 1;
    for (int k = 0; k < depth; ++k, term *= rho) series += term;
    EXPECT_TRUE(vec_near(pixel_mean(rs, 3, 5), e * series, 1e-12)) << "max_depth " << depth;
    s.settings.integrator = IntegratorKind::Whitted;
    EXPECT_TRUE(vec_near(pixel_mean(compile(s), 3, 5), e + Vec3(0.5), 1e-14)) << "max_depth " << depth;
  }
}

TEST(PathTracer, LitCavityWithRussianRouletteHasTheGeometricSeriesAsItsMean) {
  // ρ = 1/2, max_depth 64: hits 1–3 give ρ(1 + ρ + ρ²) = 0.875 in every sample; the fourth hit is
  // reached with probability q = β = ρ³ (then β = 1) and each later one with probability ρ, each
  // adding ρ. So a sample is 0.875 + ρ·N, N = 0 with probability 1 − ρ³, else geometric (≥ 1,
  // going on with probability ρ): E[N] = ρ³/(1 − ρ), E[N²] = ρ³(1 + ρ)/(1 − ρ)², and the mean is
  // ρ/(1 − ρ) = 1 (less ρ^64).
  const Real rho = 0.5;
  Scene s = lit_cavity(rho, 64);
  s.settings.sampling.spp = 64;
  const RenderScene rs = compile(s);
  Vec3 sum{0};
  for (int row = 0; row < 16; ++row)
    for (int x = 0; x < 16; ++x) sum += pixel_mean(rs, x, row);
  const Real mean = sum.x / 256, n = 256.0 * 64;
  const Real en = rho * rho * rho / (1 - rho), en2 = rho * rho * rho * (1 + rho) / ((1 - rho) * (1 - rho));
  const Real sigma = rho * std::sqrt(en2 - en * en) / std::sqrt(n);
  EXPECT_NEAR(mean, rho * (1 - std::pow(rho, 64)) / (1 - rho), 5 * sigma);
  EXPECT_EQ(sum.x, sum.y);  // grey: the channels go together
  EXPECT_EQ(sum.x, sum.z);
}

TEST(PathTracer, TakesTheDiffuseAndTheMirrorWayInProportionToTheirWeights) {
  // A convex sphere, w_d = k_d·C = (0.48, 0.24, 0.12) (a_d = 0.48) and k_r = 0.32, under a sky of
  // 1: the diffuse way (probability 0.6) gives w_d·Σa/a_d = (0.8, 0.4, 0.2), the mirror way
  // (0.4) gives Σa = 0.8; the mean is w_d + k_r. In blue the two differ by 0.6: σ = 0.6·√(0.24).
  Scene s;
  Material m = matte({0.8, 0.4, 0.2}, 0.6);
  m.reflectivity = 0.32;
  s.add(Sphere({0, 0, 0}, 1, m));
  look(s, {0, 0, 4}, {0, 0, 0}, 10, 16, 16);
  s.settings.background = Vec3(1);
  s.settings.integrator = IntegratorKind::Path;
  s.settings.sampling.sampler = SamplerKind::Random;
  s.settings.sampling.spp = 64;
  const RenderScene rs = compile(s);
  Vec3 sum{0};
  for (int row = 0; row < 16; ++row)
    for (int x = 0; x < 16; ++x) sum += pixel_mean(rs, x, row);
  const Vec3 mean = sum / 256;
  const Real sigma = 0.6 * std::sqrt(0.24) / std::sqrt(256.0 * 64);
  EXPECT_NEAR(mean.z, 0.12 + 0.32, 5 * sigma);
  EXPECT_NEAR(mean.y, 0.24 + 0.32, 5 * sigma * (0.4 / 0.6));
  EXPECT_NEAR(mean.x, 0.48 + 0.32, 1e-12);  // both ways give 0.8 in red
}

TEST(PathTracer, AreaLightsAreCountedOnceAsDirectLightNotAgainWhenABounceMeetsThem) {
  // A diffuse floor under a rect light and nothing else: a bounce off the floor meets the light or
  // the black sky, neither of which may add to the floor, so the path tracer's floor is Whitted's
  // without the ambient term, bit for bit (the same area light samples, drawn first).
  Scene s;
  s.add(Plane({0, 1, 0}, 0, matte({0.7, 0.6, 0.5}, 0.9)));
  s.add(rect_light({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, Vec3(3), 3));  // emits downwards (edge_u × edge_v)
  look(s, {0, 1.5, 5}, {0, 0.5, 0}, 45, 12, 10);
  s.settings.max_depth = 8;
  s.settings.ambient_light = Vec3(0);
  const Image whitted = test::render_image(s);
  s.settings.integrator = IntegratorKind::Path;
  const Image path = test::render_image(s);
  EXPECT_EQ(test::max_abs_diff(whitted, path), 0.0f);
  // The light is in view (its radiance 3) and the floor is lit.
  float brightest = 0;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 12; ++x) brightest = std::max(brightest, path.at(x, y).r);
  EXPECT_EQ(brightest, 3.0f);
}

TEST(PathTracer, PerfectMirrorsAndHighlightsWithoutAmbientLightGiveWhittedsImage) {
  // Where every way on is a perfect mirror (k_r = 1, k_d = 0) the path is Whitted's ray tree (one
  // branch, weight 1, no roulette: β stays 1), so the images agree up to the order of the sums.
  test::Random r(20261207);
  for (int trial = 0; trial < 6; ++trial) {
    Scene s;
    look(s, {0, 0.5, 4}, {r.uniform(-0.3, 0.3), 0, -1}, 60, 24, 18);
    s.settings.background = {r.uniform(), r.uniform(), r.uniform()};
    s.settings.ambient_light = Vec3(0);
    s.settings.max_depth = std::array{1, 2, 5, 12}[r.below(4)];
    auto material = [&] {
      Material m;
      m.color = {r.uniform(), r.uniform(), r.uniform()};
      m.diffuse = 0;
      m.specular = Vec3(r.uniform(0, 0.8));
      m.shininess = r.uniform(5, 200);
      m.reflectivity = r.coin() ? 1 : 0;
      return m;
    };
    s.add(Plane({0, 1, 0}, -1, material()));
    for (int i = 0; i < 5; ++i) s.add(Sphere(r.point(-1.5, 1.5) - Vec3(0, 0, 1.5), r.uniform(0.2, 0.7), material()));
    s.add(point_light({2, 3, 2}, Vec3(r.uniform(0.5, 1))));
    s.add(point_light({-3, 2, 1}, Vec3(r.uniform(0.5, 1))));
    const Image whitted = test::render_image(s);
    s.settings.integrator = IntegratorKind::Path;
    const Image path = test::render_image(s);
    EXPECT_LE(test::max_abs_diff(whitted, path), 1e-6f) << "trial " << trial;
  }
}

}  // namespace
}  // namespace strahl::path_tracer_test
