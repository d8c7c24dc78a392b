// Root finding on implicit surfaces (geometry/implicit.h) against closed forms: the unit sphere
// written as a distance and as a quadric, by every method; the max_gradient report; the
// lecture's ray marching before and after refinement; hits from inside and on the bound.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/geometry/implicit.h"
#include "strahl/geometry/sphere.h"
#include "strahl/scene/expression_compiler.h"
#include "test_random.h"

namespace strahl::implicit_test {
namespace {

using kernel::Implicit;
using kernel::ImplicitBound;
using kernel::ImplicitStats;
using kernel::RootMethod;

Implicit make(const char* f, RootMethod method, Real max_gradient = 1, Real accuracy = 1e-3, Real step = 0) {
  Implicit s;
  s.f = compile_expression(f);
  s.method = method;
  s.max_gradient = max_gradient;
  s.accuracy = accuracy;
  s.step = step;
  s.lo = Vec3(-2);
  s.hi = Vec3(2);
  s.normal_step = 1e-6;
  return s;
}

Implicit in_sphere(Implicit s, Real radius) {
  s.bound = ImplicitBound::Sphere;
  s.center = Vec3(0);
  s.radius = radius;
  return s;
}

const kernel::Sphere kUnitSphere{Vec3(0), 1, 0};

struct Method {
  const char* name;
  Implicit s;
};

// Rays from outside towards points of the ball of radius 1.3, and from inside; directions of
// length 1 and 2.5 (t is then no longer a distance: accuracy must still be one).
TEST(Implicit, UnitSphereByEveryMethodWithinAccuracy) {
  const char* distance = "sqrt(x^2 + y^2 + z^2) - 1";
  const Method methods[] = {
      {"lipschitz", make(distance, RootMethod::Lipschitz)},
      {"lipschitz, sphere bound", in_sphere(make(distance, RootMethod::Lipschitz), 1.5)},
      {"sphere tracing", make(distance, RootMethod::SphereTrace)},
      {"march", make(distance, RootMethod::March, 1, 1e-3, 0.05)},
  };
  for (const Method& m : methods) {
    test::Random rng(5);
    ImplicitStats stats;
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
      const bool from_inside = i % 4 == 0;
      const Vec3 origin = from_inside ? rng.direction() * rng.uniform(0, 0.9) : rng.direction() * 4;
      const Vec3 target = rng.direction() * rng.uniform(0, 1.3);
      const Real speed = i % 3 == 0 ? 2.5 : 1;
      const Ray ray{origin, normalize(target - origin) * speed};
      const Ray unit{origin, normalize(target - origin)};
      const Real want = kernel::intersect(kUnitSphere, unit, 0, kInfinity);
      // Skip rays grazing the sphere within the accuracy: either answer is right for them.
      const Real miss = length(unit.origin + unit.direction * -dot(unit.origin, unit.direction));
      if (std::fabs(miss - 1) < 1e-3) continue;
      const kernel::ImplicitCrossing got = kernel::intersect(m.s, ray, 0, kInfinity, stats);
      ASSERT_EQ(want < kInfinity, got.t < kInfinity) << m.name << " ray " << i;
      if (want == kInfinity) continue;
      ++hits;
      EXPECT_FALSE(got.on_bound);
      EXPECT_EQ(got.entering, !from_inside);
      EXPECT_LE(std::fabs(got.t * speed - want), m.s.accuracy) << m.name << " ray " << i;
      // The polish after the bisection: the root to ~1e-10, so secondary rays start on the right side.
      EXPECT_LE(std::fabs(got.t * speed - want), 1e-9) << m.name << " ray " << i;
      const Vec3 p = ray.at(got.t);
      EXPECT_LE(length(kernel::normal_at(m.s, p, false) - p / length(p)), 1e-6) << m.name;
      EXPECT_EQ(kernel::crossings(m.s, ray, 0, kInfinity, stats), from_inside ? 1 : 2) << m.name << " ray " << i;
    }
    EXPECT_GT(hits, 1000) << m.name;
    EXPECT_EQ(stats.exhausted, 0u) << m.name;
    if (m.s.method != RootMethod::March) {
      EXPECT_LE(stats.max_gradient, 1 + 1e-9) << m.name;  // |∇f| = 1
    }
  }
}

// Rays on a grid from the camera at z = 5 through the square [−1.3, 1.3]² of the plane z = 0.
struct GridResult {
  int hits = 0, holes = 0, false_hits = 0;
  ImplicitStats stats;
};

GridResult shoot_grid(const Implicit& s, int n) {
  GridResult r;
  const Vec3 eye(0, 0, 5);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Vec3 target(-1.3 + 2.6 * (i + 0.5) / n, -1.3 + 2.6 * (j + 0.5) / n, 0);
      const Ray ray{eye, normalize(target - eye)};
      const Real want = kernel::intersect(kUnitSphere, ray, 0, kInfinity);
      const Real miss = length(ray.origin + ray.direction * -dot(ray.origin, ray.direction));
      const kernel::ImplicitCrossing got = kernel::intersect(s, ray, 0, kInfinity, r.stats);
      if (std::fabs(miss - 1) < 1e-3) continue;
      if (want < kInfinity && got.t == kInfinity) ++r.holes;
      if (want == kInfinity && got.t < kInfinity) ++r.false_hits;
      if (want < kInfinity && got.t < kInfinity) {
        ++r.hits;
        EXPECT_LE(std::fabs(got.t - want), s.accuracy);
      }
    }
  }
  return r;
}

// x² + y² + z² − 1 in a sphere of radius 1.2: |∇f| = 2r reaches 2.4 on the bound.
TEST(Implicit, QuadricSphereMaxGradient) {
  const Implicit good = in_sphere(make("x^2 + y^2 + z^2 - 1", RootMethod::Lipschitz, 2.4), 1.2);
  const GridResult r = shoot_grid(good, 64);
  EXPECT_EQ(r.holes, 0);
  EXPECT_EQ(r.false_hits, 0);
  EXPECT_GT(r.hits, 1500);  // π/4 · (2/2.6)² of 4096
  EXPECT_LE(r.stats.max_gradient, 2.4 * (1 + 1e-9));  // no warning: L holds
  EXPECT_GT(r.stats.max_gradient, 1.8);               // but the samples came near it

  const Implicit low = in_sphere(make("x^2 + y^2 + z^2 - 1", RootMethod::Lipschitz, 1.1), 1.2);
  const GridResult w = shoot_grid(low, 64);
  EXPECT_GT(w.stats.max_gradient, 1.1);  // reported: L was exceeded ...
  EXPECT_LE(w.stats.max_gradient, 2.4 * (1 + 1e-9));  // ... by no more than the true maximum
  EXPECT_EQ(w.false_hits, 0);
}

// Sphere tracing with a "distance" that is twice the distance: the report names the real slope.
TEST(Implicit, SphereTracingReportsASteeperDistance) {
  const Implicit s = make("2*(sqrt(x^2 + y^2 + z^2) - 1)", RootMethod::SphereTrace, 1);
  ImplicitStats stats;
  for (int i = 0; i < 50; ++i) {
    const Ray ray{{0.02 * i - 0.5, 0, 5}, {0, 0, -1}};  // i = 25: through the centre, slope 2
    (void)kernel::intersect(s, ray, 0, kInfinity, stats);
  }
  EXPECT_GT(stats.max_gradient, 1.99);
  EXPECT_LE(stats.max_gradient, 2 * (1 + 1e-9));
}

// The lecture's ray marching: the first sample inside lies within one step ε behind the surface;
// the bisection brings it within `accuracy`. Two spheres on the ray: the first is found.
TEST(Implicit, MarchFindsTheFirstSurfaceWithinOneStep) {
  const Real eps = 0.05;
  const Implicit s = make("min(sqrt((x+1)^2 + y^2 + z^2) - 0.5, sqrt((x-1)^2 + y^2 + z^2) - 0.5)", RootMethod::March,
                          1, 1e-4, eps);
  test::Random rng(11);
  for (int i = 0; i < 200; ++i) {
    // From the left, through both spheres: offsets up to 0.3 from the axis.
    const Vec3 origin(-3, rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
    const Ray ray{origin, {1, 0, 0}};
    const kernel::Sphere first{{-1, 0, 0}, 0.5, 0};
    const Real want = kernel::intersect(first, ray, 0, kInfinity);
    ASSERT_LT(want, kInfinity);
    ImplicitStats stats;
    kernel::ImplicitQuery q{s, ray, stats};
    Real ta = 0, tb = 0;
    ASSERT_TRUE(kernel::bound_range(s, ray, ta, tb));
    kernel::Bracket br;
    ASSERT_TRUE(kernel::march_bracket(q, q.sample(ta), q.sample(tb), br));
    EXPECT_LE(br.a.t, want);  // the last sample outside ...
    EXPECT_GE(br.b.t, want);  // ... and the first inside
    EXPECT_LE(br.b.t - want, eps);
    EXPECT_NEAR(br.b.t - br.a.t, eps, 1e-12);
    kernel::bisect(q, br);
    EXPECT_LE(br.b.t - br.a.t, s.accuracy);
    EXPECT_LE(std::fabs(br.b.t - want), s.accuracy);
    EXPECT_LE(std::fabs(kernel::intersect(s, ray, 0, kInfinity, stats).t - want), s.accuracy);
  }
}

// f < 0 over the whole box: the solid is the box, and its surface the box's faces.
TEST(Implicit, BoundFacesWhereTheFunctionIsInside) {
  Implicit s = make("x^2 + y^2 + z^2 - 4", RootMethod::Lipschitz, 4);
  s.lo = Vec3(-1);
  s.hi = Vec3(1);
  ImplicitStats stats;
  const Ray through{{0.2, 0.3, 5}, {0, 0, -1}};
  kernel::ImplicitCrossing c = kernel::intersect(s, through, 0, kInfinity, stats);
  EXPECT_EQ(c.t, 4);
  EXPECT_TRUE(c.on_bound);
  EXPECT_TRUE(c.entering);
  EXPECT_EQ(kernel::normal_at(s, through.at(c.t), true), Vec3(0, 0, 1));
  EXPECT_EQ(kernel::crossings(s, through, 0, kInfinity, stats), 2);
  EXPECT_EQ(kernel::crossings(s, through, 0, 5, stats), 1);
  const Ray from_inside{{0.2, 0.3, 0}, {1, 0, 0}};
  c = kernel::intersect(s, from_inside, 0, kInfinity, stats);
  EXPECT_DOUBLE_EQ(c.t, 0.8);
  EXPECT_TRUE(c.on_bound);
  EXPECT_FALSE(c.entering);
  EXPECT_EQ(kernel::normal_at(s, from_inside.at(c.t), true), Vec3(1, 0, 0));
  EXPECT_TRUE(kernel::inside(s, {0.5, 0.5, 0.5}));
  EXPECT_FALSE(kernel::inside(s, {1.5, 0, 0}));
}

// The sphere cut by the box: entering through f = 0, leaving through the face x = 0.5.
TEST(Implicit, SurfaceAndBoundTogether) {
  Implicit s = make("sqrt(x^2 + y^2 + z^2) - 1", RootMethod::Lipschitz, 1);
  s.hi = Vec3(0.5, 2, 2);
  ImplicitStats stats;
  const Ray ray{{-3, 0, 0}, {1, 0, 0}};
  int n = 0;
  kernel::for_each_implicit_crossing(s, ray, 0, kInfinity, stats, [&](const kernel::ImplicitCrossing& c) {
    if (n == 0) {
      EXPECT_NEAR(c.t, 2, 1e-9);
      EXPECT_FALSE(c.on_bound);
      EXPECT_TRUE(c.entering);
    } else {
      EXPECT_EQ(c.t, 3.5);
      EXPECT_TRUE(c.on_bound);
      EXPECT_FALSE(c.entering);
    }
    ++n;
    return false;
  });
  EXPECT_EQ(n, 2);
}

// Shadow rays: any_crossing() stops at the first change of side it sees, unrefined; its answer
// is intersect()'s, for rays from anywhere, from the surface itself, and for t_max just before or
// just after the nearest root (where a change of side seen over an interval reaching past t_max
// must not count).
TEST(Implicit, AnyCrossingAgreesWithTheNearestHit) {
  const char* functions[] = {"sqrt(x^2 + y^2 + z^2) - 1 + 0.05*sin(20*y)",
                             "(sqrt(x^2 + z^2) - 1)^2 + y^2 - 0.09",  // a torus: up to four roots
                             "x^2 + y^2 + z^2 - 1"};
  const Real gradients[] = {2.2, 2.5, 3};
  test::Random rng(13);
  int hits = 0, misses = 0;
  for (int fi = 0; fi < 3; ++fi)
    for (RootMethod method : {RootMethod::Lipschitz, RootMethod::SphereTrace, RootMethod::March}) {
      const Implicit s = in_sphere(make(functions[fi], method, gradients[fi], 1e-4, 0.01), 1.5);
      for (int i = 0; i < 400; ++i) {
        ImplicitStats stats;
        Ray ray{rng.point(-2, 2), rng.direction()};
        if (i % 2 == 1) {  // from a surface point, off it by 1e-9, as a shadow ray leaves
          const Real t = kernel::intersect(s, ray, 0, kInfinity, stats).t;
          if (!(t < kInfinity)) continue;
          const Vec3 p = ray.at(t);
          ray = spawn_ray(p, kernel::normal_at(s, p, false), rng.direction());
        }
        const Real first = kernel::intersect(s, ray, 0, kInfinity, stats).t;
        const Real ends[] = {kInfinity, rng.uniform(0, 4), first * (1 - 1e-6), first * (1 + 1e-6)};
        for (Real t_max : ends) {
          if (!(t_max < kInfinity) && t_max != kInfinity) continue;
          const bool nearest = kernel::intersect(s, ray, 0, t_max, stats).t < kInfinity;
          EXPECT_EQ(kernel::any_crossing(s, ray, 0, t_max, stats), nearest)
              << functions[fi] << " method " << int(method) << " ray " << i << " t_max " << t_max;
          (nearest ? hits : misses)++;
        }
      }
    }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 1000);
}

// The Illinois polish at a root its first secant step all but hits (f linear): the next sample
// goes half the tolerance in from that end and closes the bracket, instead of the bisection
// from the other end that regula falsi falls back to there (32 samples).
TEST(Implicit, PolishClosesOnARootItHasAlmostHit) {
  const Implicit s = make("x - 0.3", RootMethod::Lipschitz, 1, 1e-4);
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  ImplicitStats stats;
  kernel::ImplicitQuery q{s, ray, stats};
  kernel::Bracket br{q.sample(0.25), q.sample(0.35)};
  const Real t = kernel::refine(q, br);
  EXPECT_NEAR(t, 0.3, 1e-12);
  EXPECT_LE(q.evaluations, 2 + 3);
}

// A ray leaving a surface (f(a) = 1e-9, rising at slope 1 against L = 2): the Lipschitz
// search steps away from it, 2·accuracy first and then geometrically, instead of halving the
// whole range down to `accuracy` and coming back up (15 samples).
TEST(Implicit, LipschitzSearchStepsAwayFromASurface) {
  const Implicit s = make("sqrt(x^2 + y^2 + z^2) - 1", RootMethod::Lipschitz, 2, 1e-4);
  const Ray ray{{1 + 1e-9, 0, 0}, {1, 0, 0}};
  ImplicitStats stats;
  kernel::ImplicitQuery q{s, ray, stats};
  kernel::Bracket br;
  EXPECT_FALSE(kernel::lipschitz_bracket(q, q.sample(0), q.sample(0.999), br));
  EXPECT_LE(q.evaluations, 2 + 9);
  ImplicitStats any_stats;
  EXPECT_FALSE(kernel::any_crossing(s, ray, 0, kInfinity, any_stats));
}

// f = 0 everywhere: no interval can be ruled out; the query stops at its budget, counted once.
TEST(Implicit, EvaluationBudget) {
  const Implicit s = make("0*x", RootMethod::Lipschitz, 1, 1e-6);
  ImplicitStats stats;
  EXPECT_EQ(kernel::intersect(s, {{0, 0, 5}, {0, 0, -1}}, 0, kInfinity, stats).t, kInfinity);
  EXPECT_EQ(stats.exhausted, 1u);
}

}  // namespace
}  // namespace strahl::implicit_test
