// Whitted recursion in rendered scenes: invisible glass, refraction paths through a slab and a
// sphere, total internal reflection, Fresnel, mirror images, and the two stopping rules
// (max_depth and min_weight), with ray counts from RenderStats / RayCounters.

#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.h"

namespace strahl::recursion_test {
namespace {

using test::deg;

// Snell's law written as a rotation in the plane of incidence (independent of strahl::refract):
// n faces the incoming side, eta = n1/n2.
Vec3 snell(const Vec3& d, const Vec3& n, Real eta) {
  const Real cos1 = -dot(d, n);
  const Vec3 tangent = normalize(d + n * cos1);
  const Real sin2 = eta * std::sqrt(1 - cos1 * cos1);
  return tangent * sin2 - n * std::sqrt(1 - sin2 * sin2);
}

// A small scene with shadows, highlights and a mirror, seen through a 32×24 camera.
Scene opaque_scene() {
  Scene s;
  s.camera.position = {0, 1, 3};
  s.camera.look_at = {0, 0.3, 0};
  s.camera.fov_degrees = 50;
  s.settings.width = 32;
  s.settings.height = 24;
  s.add(Plane({0, 1, 0}, 0, test::phong({0.5, 0.5, 0.5}, 0.1, 0.7, Vec3(0.6), 100)));
  s.add(Sphere({0.3, 0.3, -0.5}, 0.3, test::phong({0.8, 0.2, 0.2}, 0.1, 0.7, Vec3(0.6), 100)));
  s.add(Sphere({-0.4, 0.2, 0.2}, 0.2, test::phong({0.1, 0.3, 0.9}, 0.1, 0.7, Vec3(0.6), 50)));
  Material m = test::mirror(0.8, {0.05, 0.05, 0.05});
  m.ambient = 0.1;
  s.add(Sphere({-0.6, 0.35, -0.9}, 0.35, m));
  s.add(point_light({1, 2, 1.5}));
  s.add(point_light({-2, 1.5, 1}, {0.3, 0.3, 0.5}));
  return s;
}

TEST(Recursion, TransparentSphereWithIorOneIsInvisible) {
  // Transparency 1, ior 1, no ambient, diffuse, specular or reflection: it bends nothing, adds
  // nothing, and its shadow rays pass unattenuated, so the image stays as it was.
  const Image before = test::render_image(opaque_scene());
  Scene with = opaque_scene();
  with.add(Sphere({0.05, 0.5, 0.5}, 0.35, test::clear_glass(1)));  // in front of things, and in the light's path
  const Image after = test::render_image(with);
  EXPECT_LE(test::max_abs_diff(before, after), 1e-5f);

  // The sphere covers a good part of the image: glass with ior 1.5 in its place changes it a lot.
  Scene refracting = opaque_scene();
  refracting.add(Sphere({0.05, 0.5, 0.5}, 0.35, test::clear_glass(1.5)));
  const Image bent = test::render_image(refracting);
  int changed = 0;
  for (std::size_t i = 0; i < bent.pixels().size(); ++i)
    changed += std::fabs(bent.pixels()[i].r - before.pixels()[i].r) > 1e-3f;
  EXPECT_GT(changed, 20);
}

TEST(Recursion, TransparentSphereOverTheFloorCastsNoShadow) {
  // Floor point straight below the sphere, light straight above: the shadow ray crosses the
  // sphere twice with transmittance 1 each.
  Scene s;
  test::one_ray_camera(s, {0, 1, 3}, {0, 0, 0});
  s.add(Plane({0, 1, 0}, 0, test::phong({0.5, 0.6, 0.7}, 0.1, 0.7, Vec3(0), 1)));
  s.add(point_light({0, 5, 0}));
  const Vec3 lit = test::pixel(s);
  s.add(Sphere({0, 2, 0}, 0.5, test::clear_glass(1)));
  EXPECT_VEC_NEAR(test::pixel(s), lit, 1e-14);
  // Sanity: the lit value is not the ambient-only one.
  EXPECT_GT(lit.x, 0.5 * 0.1 + 0.1);
}

TEST(Recursion, RayThroughGlassSlabLeavesParallelToItsEntry) {
  // Slab between the top face y = 0 (normal up) and the bottom face y = −1 (normal down), ior 1.5.
  // The camera ray arrives at 45° at the origin, runs inside at θ2 = asin(sin 45°/1.5), leaves
  // at P2 = (tan θ2, −1, 0) in the entry direction. A small target sphere 3 units along that
  // exit ray is seen; with ior 1 (no bending) the ray passes 0.47 beside it.
  const Vec3 d = normalize(Vec3(1, -1, 0));
  const Real theta2 = std::asin(std::sin(deg(45)) / 1.5);
  const Vec3 exit_point(std::tan(theta2), -1, 0);
  const Vec3 target_color(0.2, 0.6, 0.9);
  for (Real ior : {1.5, 1.0}) {
    Scene s;
    test::one_ray_camera(s, {-2, 2, 0}, {0, 0, 0});
    s.add(Plane({0, 1, 0}, 0, test::clear_glass(ior)));
    s.add(Plane({0, -1, 0}, 1, test::clear_glass(ior)));
    s.add(Sphere(exit_point + d * 3, 0.05, test::emissive_like(target_color)));
    RayCounters counters;
    const Vec3 c = test::pixel(s, 0, 0, &counters);
    if (ior == 1.5) {
      EXPECT_VEC_NEAR(c, target_color, 1e-12);
      EXPECT_EQ(counters.camera, 1u);
      EXPECT_EQ(counters.refraction, 2u);
      EXPECT_EQ(counters.reflection, 0u);
    } else {
      EXPECT_VEC_NEAR(c, Vec3(0), 0) << "control: an unbent ray misses the target";
    }
  }
}

TEST(Recursion, RayThroughGlassSphereFollowsSnellsLaw) {
  // Camera ray x = 0.5 down −z into a unit glass sphere at (0, 0, −5); the exit ray is computed
  // by hand with Snell's law at both surfaces, and a small target sphere placed on it.
  const Vec3 c(0, 0, -5);
  const Real ior = 1.5;
  const Vec3 d0(0, 0, -1);
  const Vec3 p1(0.5, 0, -5 + std::sqrt(0.75));
  const Vec3 d1 = snell(d0, p1 - c, 1 / ior);
  const Real chord = -2 * dot(p1 - c, d1);
  const Vec3 p2 = p1 + d1 * chord;
  const Vec3 d2 = snell(d1, -(p2 - c), ior);
  ASSERT_GT(std::acos(dot(d2, d0)), deg(10)) << "the test needs a clearly bent ray";
  const Vec3 target_color(0.9, 0.5, 0.1);
  Scene s;
  test::one_ray_camera(s, {0.5, 0, 0}, {0.5, 0, -1});
  s.add(Sphere(c, 1, test::clear_glass(ior)));
  s.add(Sphere(p2 + d2 * 4, 0.05, test::emissive_like(target_color)));
  EXPECT_VEC_NEAR(test::pixel(s), target_color, 1e-12);
}

// Nearest positive root of the ray o + t·d (unit d) with a sphere, in long double.
Real sphere_root(const Vec3& o, const Vec3& d, const Vec3& c, Real r) {
  const long double b = dot(o - c, d), cc = dot(o - c, o - c) - r * r;
  const long double disc = b * b - cc;
  const long double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
  return Real(t0 > 1e-9L ? t0 : t1);
}

TEST(Recursion, NestedMediaUseTheRightPairsOfIndices) {
  // A glass ball (1.5) inside a water ball (1.333), concentric, in air (medium_ior 1.0003). The
  // off-centre camera ray crosses air→water, water→glass, glass→water, water→air.
  const Vec3 c(0, 0, -6);
  const Real air = 1.0003, water = 1.333, glass = 1.5;
  Vec3 o(0.9, 0, 0), d(0, 0, -1);
  struct Step { Real r; bool entering; Real n1, n2; };
  for (const Step& st : {Step{2, true, air, water}, Step{1, true, water, glass}, Step{1, false, glass, water},
                         Step{2, false, water, air}}) {
    const Vec3 p = o + d * sphere_root(o, d, c, st.r);
    const Vec3 outward = (p - c) / st.r;
    d = snell(d, st.entering ? outward : -outward, st.n1 / st.n2);
    o = p;
  }
  ASSERT_GT(std::acos(-d.z), deg(5)) << "the test needs a clearly bent ray";
  const Vec3 target_color(0.3, 0.9, 0.6);
  Scene s;
  s.settings.medium_ior = air;
  test::one_ray_camera(s, {0.9, 0, 0}, {0.9, 0, -1});
  s.add(Sphere(c, 2, test::clear_glass(water)));
  s.add(Sphere(c, 1, test::clear_glass(glass)));
  s.add(Sphere(o + d * 4, 0.05, test::emissive_like(target_color)));
  RayCounters counters;
  EXPECT_VEC_NEAR(test::pixel(s, 0, 0, &counters), target_color, 1e-12);
  EXPECT_EQ(counters.refraction, 4u);
}

// Camera inside glass (the half-space below y = 0, ior n) looking up at `theta` from the
// normal; above the surface a ceiling (colour B), below a floor (colour A). Refracted rays see
// B; totally reflected ones see A.
Vec3 inside_glass_pixel(Real n, Real theta, RayCounters* counters = nullptr) {
  Scene s;
  const Vec3 eye(0, -0.5, 0);
  test::one_ray_camera(s, eye, eye + Vec3(std::sin(theta), std::cos(theta), 0), {0, 0, 1});
  s.add(Plane({0, 1, 0}, 0, test::clear_glass(n)));
  s.add(Plane({0, 1, 0}, -1, test::emissive_like({1, 0, 0})));   // floor y = −1, colour A
  s.add(Plane({0, -1, 0}, -1, test::emissive_like({0, 0, 1})));  // ceiling y = 1, colour B
  return test::pixel(s, 0, 0, counters);
}

TEST(Recursion, TotalInternalReflectionStartsAtTheCriticalAngle) {
  for (Real n : {1.5, 2.419, 1.31}) {
    const Real critical = std::asin(1 / n);
    RayCounters below, above;
    EXPECT_VEC_NEAR(inside_glass_pixel(n, critical - 1e-6, &below), Vec3(0, 0, 1), 1e-12) << "ior " << n;
    EXPECT_VEC_NEAR(inside_glass_pixel(n, critical + 1e-6, &above), Vec3(1, 0, 0), 1e-12) << "ior " << n;
    EXPECT_EQ(below.refraction, 1u);
    EXPECT_EQ(below.reflection, 0u);
    EXPECT_EQ(above.refraction, 0u);
    EXPECT_EQ(above.reflection, 1u);
    EXPECT_VEC_NEAR(inside_glass_pixel(n, deg(5)), Vec3(0, 0, 1), 1e-12);
    EXPECT_VEC_NEAR(inside_glass_pixel(n, deg(80)), Vec3(1, 0, 0), 1e-12);
  }
}

// Camera above a fresnel glass surface y = 0 looking down at `theta` from the normal; the
// reflection sees a ceiling (colour A) at y = 2, the refraction a floor (colour B) at y = −1.
Vec3 fresnel_pixel(Real theta) {
  Scene s;
  const Vec3 eye(0, 1, 0);
  test::one_ray_camera(s, eye, eye + Vec3(std::sin(theta), -std::cos(theta), 0), {0, 0, 1});
  Material glass = test::clear_glass(1.5);
  glass.fresnel = true;
  s.add(Plane({0, 1, 0}, 0, glass));
  s.add(Plane({0, -1, 0}, -2, test::emissive_like({1, 0, 0})));  // ceiling y = 2
  s.add(Plane({0, 1, 0}, -1, test::emissive_like({0, 1, 0})));   // floor y = −1
  return test::pixel(s);
}

TEST(Recursion, FresnelSplitsBetweenReflectionAndRefractionBySchlick) {
  EXPECT_VEC_NEAR(fresnel_pixel(0), Vec3(0.04, 0.96, 0), 1e-14);
  const Real f60 = 0.04 + 0.96 / 32;  // (1 − cos 60°)⁵ = 1/32
  EXPECT_VEC_NEAR(fresnel_pixel(deg(60)), Vec3(f60, 1 - f60, 0), 1e-14);
}

TEST(Recursion, TransparencyDimsAmbientAndDiffuseButNotTheHighlight) {
  // Half-transparent sphere, light along N = V (N·L = N·H = 1); behind it an emissive wall.
  Material m = test::phong({0.8, 0.4, 0.2}, 0.1, 0.7, Vec3(0.3), 50);
  m.transparency = 0.5;
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.add(Sphere({0, 0, -3}, 1, m));
  s.add(Plane({0, 0, 1}, -10, test::emissive_like({0.2, 0.2, 0.2})));  // z = −10, facing the camera
  s.add(point_light({0, 0, 5}));
  // Front hit: (1 − T)·k_a·C + (1 − T)·k_d·C·1 + k_s·1 (the highlight is not dimmed).
  // The refracted ray (weight T, ior 1: straight on) meets the back surface from inside; its
  // normal facing the viewer, (0,0,1), faces the light too, so it is lit, but its shadow ray
  // crosses the front surface once: ·T. The ray leaving there (·T again) sees the wall's 0.2.
  const Vec3 C(0.8, 0.4, 0.2);
  const Vec3 front = C * (0.5 * 0.1) + C * (0.5 * 0.7) + Vec3(0.3);
  const Vec3 back = C * (0.5 * 0.1) + (C * (0.5 * 0.7) + Vec3(0.3)) * 0.5;
  const Vec3 expected = front + (back + Vec3(0.2) * 0.5) * 0.5;
  EXPECT_VEC_NEAR(test::pixel(s), expected, 1e-12);
}

TEST(Recursion, FilteringGlassTintsPerSurfaceCrossing) {
  Material glass = test::clear_glass(1);
  glass.color = {1, 0.5, 0.25};
  glass.filter = true;
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.add(Sphere({0, 0, -3}, 1, glass));
  s.add(Plane({0, 0, 1}, -10, test::emissive_like(Vec3(1))));
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(1, 0.25, 0.0625), 1e-14);
  glass.filter = false;
  Scene clear;
  test::one_ray_camera(clear, {0, 0, 0}, {0, 0, -1});
  clear.add(Sphere({0, 0, -3}, 1, glass));
  clear.add(Plane({0, 0, 1}, -10, test::emissive_like(Vec3(1))));
  EXPECT_VEC_NEAR(test::pixel(clear), Vec3(1), 1e-14);
}

TEST(Recursion, ReflectedRaysThatMissEverythingSeeTheBackground) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.add(Sphere({0, 0, -3}, 1, test::mirror(0.75, {0.1, 0.1, 0.1})));
  s.settings.background = {0.2, 0.4, 0.8};
  // Local 0.1 (ambient 1 × colour 0.1) plus 0.75 × background, reflected straight back.
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(0.1, 0.1, 0.1) + Vec3(0.2, 0.4, 0.8) * 0.75, 1e-15);
}

TEST(Recursion, FilterTintUsesTheColourNotTheCheckerColour) {
  Material glass = test::clear_glass(1);
  glass.color = {1, 0.5, 0.25};
  glass.filter = true;
  glass.checker_size = 0.01;
  glass.checker_color = {0, 1, 0};
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.add(Sphere({0, 0, -3}, 1, glass));
  s.add(Plane({0, 0, 1}, -10, test::emissive_like(Vec3(1))));
  EXPECT_VEC_NEAR(test::pixel(s), Vec3(1, 0.25, 0.0625), 1e-14);
}

// Mirror plane y = 0 under two spheres, versus no mirror and the spheres' mirror images added:
// every pixel must agree (the mirror has no colour of its own, the spheres are ambient-only).
TEST(Recursion, MirrorShowsGeometryAtTheMirroredPosition) {
  const auto camera = [](Scene& s) {
    s.camera.position = {0, 1, 1};
    s.camera.look_at = {0, 0, -3};
    s.camera.fov_degrees = 60;
    s.settings.width = 24;
    s.settings.height = 24;
  };
  const Material red = test::emissive_like({1, 0.2, 0.1}), green = test::emissive_like({0.1, 0.9, 0.3});
  Scene mirrored, direct, plain;
  for (Scene* s : {&mirrored, &direct, &plain}) {
    camera(*s);
    s->add(Sphere({0.3, 0.5, -3}, 0.4, red));
    s->add(Sphere({-0.7, 0.8, -4}, 0.3, green));
  }
  mirrored.add(Plane({0, 1, 0}, 0, test::mirror(1)));
  direct.add(Sphere({0.3, -0.5, -3}, 0.4, red));
  direct.add(Sphere({-0.7, -0.8, -4}, 0.3, green));
  RenderStats stats;
  const Image a = test::render_image(mirrored, 1, 32, &stats);
  const Image b = test::render_image(direct);
  EXPECT_LE(test::max_abs_diff(a, b), 1e-6f);
  // The reflections are really there: without the mirror the lower half is black.
  const Image c = test::render_image(plain);
  int reflected_pixels = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    reflected_pixels += !(a.pixels()[i] == c.pixels()[i]);
  EXPECT_GT(reflected_pixels, 10);
  EXPECT_GT(stats.rays.reflection, 0u);
}

// Two parallel mirrors z = −1 (facing +z) and z = 0 (facing −z) with the camera between them
// looking straight at one: every ray bounces until a stopping rule ends it.
Scene facing_mirrors(Real reflectivity, int max_depth, Real min_weight, int size) {
  Scene s;
  test::set_camera(s, {0, 0, -0.5}, {0, 0, -1}, {0, 1, 0}, -0.01, 0.01, -0.01, 0.01, 1, size, size);
  s.add(Plane({0, 0, 1}, -1, test::mirror(reflectivity, {0.1, 0.2, 0.3})));
  s.add(Plane({0, 0, -1}, 0, test::mirror(reflectivity, {0.1, 0.2, 0.3})));
  s.settings.max_depth = max_depth;
  s.settings.min_weight = min_weight;
  return s;
}

TEST(Recursion, MaxDepthBoundsTheNumberOfReflections) {
  for (int depth : {1, 2, 3, 8, 20, 64}) {
    RenderStats stats;
    test::render_image(facing_mirrors(1, depth, 0, 3), 2, 2, &stats);
    EXPECT_EQ(stats.rays.camera, 9u);
    EXPECT_EQ(stats.rays.reflection, 9u * std::uint64_t(depth - 1)) << "max_depth " << depth;
    EXPECT_EQ(stats.rays.refraction, 0u);
    EXPECT_EQ(stats.rays.shadow, 0u);
  }
}

TEST(Recursion, EachBounceAddsTheMirrorsAmbientTermWeightedByReflectivity) {
  // Radiance = a·C · Σ_{k=0}^{N−1} r^k for N = max_depth surface hits.
  for (int depth : {1, 4, 10}) {
    for (Real r : {1.0, 0.5}) {
      Real sum = 0;
      for (int k = 0; k < depth; ++k) sum += std::pow(r, k);
      EXPECT_VEC_NEAR(test::pixel(facing_mirrors(r, depth, 0, 1)), Vec3(0.1, 0.2, 0.3) * sum, 1e-14)
          << "depth " << depth << " reflectivity " << r;
    }
  }
}

TEST(Recursion, MinWeightStopsRaysThatContributeLittle) {
  // Reflectivity 0.5: the k-th reflection ray has weight 0.5^k. With min_weight 0.1 the rays of
  // weight 0.5, 0.25, 0.125 are traced, 0.0625 is not; with 0.01 six are traced (0.5⁶ = 0.0156).
  struct Case { Real min_weight; std::uint64_t rays; };
  for (const Case& c : {Case{0.1, 3}, Case{0.01, 6}, Case{0.6, 0}, Case{0.3, 1}}) {
    RenderStats stats;
    const Image img = test::render_image(facing_mirrors(0.5, 64, c.min_weight, 2), 1, 32, &stats);
    EXPECT_EQ(stats.rays.reflection, 4 * c.rays) << "min_weight " << c.min_weight;
    Real sum = 0;
    for (std::uint64_t k = 0; k <= c.rays; ++k) sum += std::pow(0.5, Real(k));
    EXPECT_VEC_NEAR(test::to_vec(img.at(1, 1)), Vec3(0.1, 0.2, 0.3) * sum, 1e-6);
  }
}

// The ray budget (render.ray_budget): a chain of B + 1 mirror bounces with budget B traces B
// reflections, cuts one, and gives exactly the image of max_depth B + 1 (a cut ray is as if
// the recursion had stopped there); a budget the chain fits in cuts nothing.
TEST(Recursion, RayBudgetCutsTheRaysBeyondItAndCountsThem) {
  for (const int budget : {0, 1, 5, 18}) {
    Scene cut = facing_mirrors(1, 64, 0, 2);
    cut.settings.ray_budget = budget;
    RenderStats stats;
    const Image a = test::render_image(cut, 1, 32, &stats);
    EXPECT_EQ(stats.rays.reflection, 4u * std::uint64_t(budget)) << "budget " << budget;
    EXPECT_EQ(stats.rays.cut, 4u) << "one cut per camera sample, where its chain of mirror rays ends";
    const Image b = test::render_image(facing_mirrors(1, budget + 1, 0, 2));
    EXPECT_EQ(test::max_abs_diff(a, b), 0.0f) << "budget " << budget;
  }
  Scene fits = facing_mirrors(1, 20, 0, 2);
  fits.settings.ray_budget = 19;  // max_depth 20: 19 reflections per camera ray
  RenderStats stats;
  test::render_image(fits, 1, 32, &stats);
  EXPECT_EQ(stats.rays.reflection, 4u * 19u);
  EXPECT_EQ(stats.rays.cut, 0u);
}

// Issue 12's exponential ray tree: glass that both reflects and refracts everywhere, a camera
// inside a glass shell looking at a glass ball, max_depth 64, min_weight 0. Without the budget
// one camera ray would spawn some 2^60 rays; with it, exactly the default budget is traced.
TEST(Recursion, RayBudgetBoundsAnExponentialRayTree) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  Material glass = test::clear_glass(1.5);
  glass.transparency = 0.5;
  glass.reflectivity = 0.5;
  s.add(Sphere({0, 0, -3}, 1, glass));
  s.add(Sphere({0, 0, 0}, 10, glass));
  s.settings.max_depth = 64;
  s.settings.min_weight = 0;
  RayCounters counters;
  test::pixel(s, 0, 0, &counters);
  EXPECT_EQ(counters.reflection + counters.refraction, std::uint64_t(kDefaultRayBudget));
  EXPECT_GT(counters.cut, 0u);
  // A larger budget is spent too: the tree is far bigger than any allowed budget.
  s.settings.ray_budget = int(kMaxRayBudget);
  counters = {};
  test::pixel(s, 0, 0, &counters);
  EXPECT_EQ(counters.reflection + counters.refraction, std::uint64_t(kMaxRayBudget));
  EXPECT_GT(counters.cut, 0u);
}

TEST(Recursion, MaxDepthOneShowsOnlyLocalColour) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  Material glass = test::clear_glass(1.5);
  glass.ambient = 1;
  glass.color = {0.3, 0.3, 0.3};
  glass.transparency = 0.5;
  glass.reflectivity = 0.5;
  s.add(Sphere({0, 0, -3}, 1, glass));
  s.add(Plane({0, 0, 1}, -10, test::emissive_like(Vec3(1))));
  s.settings.max_depth = 1;
  RayCounters counters;
  EXPECT_VEC_NEAR(test::pixel(s, 0, 0, &counters), Vec3(0.3 * 0.5), 1e-15);  // (1 − T)·k_a·C
  EXPECT_EQ(counters.reflection + counters.refraction, 0u);
}

}  // namespace
}  // namespace strahl::recursion_test
