// The solids of geometry/solid.h against closed forms: a quadric with a sphere's coefficients is
// the analytic sphere; axis-aligned rays into cylinder, cone and hyperboloid quadrics and into the
// cylinder, cone and box solids; a tangent ray; the torus's exact hits at ±(R ± r) and ±r, at
// 1e-3 and 1e4 scale and 1e5 from the origin, and its normal formula; an implicit sphere through
// the solid interface by every method. Then invariants: inside() against analytic membership at
// random points, and the parity of a ray's crossings from a point against inside() there.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "strahl/geometry/solid.h"
#include "strahl/geometry/sphere.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/expression_compiler.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/solids.h"
#include "test_random.h"

namespace strahl::solid_test {
namespace {

using kernel::Solid;
using kernel::SolidKind;

// One solid of each kind it is given, in arrays of its own, as a RenderScene holds them.
struct Solids {
  std::vector<kernel::Box> boxes;
  std::vector<kernel::Cone> cones;
  std::vector<kernel::Disk> disks;
  std::vector<kernel::Torus> tori;
  std::vector<kernel::Quadric> quadrics;
  std::vector<kernel::Implicit> implicits;
  std::vector<kernel::ImplicitTally> tallies;

  kernel::SolidArrays arrays() {
    return {boxes.data(), cones.data(), disks.data(), tori.data(), quadrics.data(), implicits.data(), tallies.data()};
  }
  Solid add(const kernel::Box& b) { boxes.push_back(b); return {SolidKind::Box, std::uint32_t(boxes.size() - 1), 0}; }
  Solid add(const kernel::Cone& c) { cones.push_back(c); return {SolidKind::Cone, std::uint32_t(cones.size() - 1), 0}; }
  Solid add(const kernel::Torus& t) { tori.push_back(t); return {SolidKind::Torus, std::uint32_t(tori.size() - 1), 0}; }
  Solid add(const kernel::Quadric& q) {
    quadrics.push_back(q);
    return {SolidKind::Quadric, std::uint32_t(quadrics.size() - 1), 0};
  }
  Solid add(const kernel::Implicit& s) {
    implicits.push_back(s);
    tallies.push_back({});
    return {SolidKind::Implicit, std::uint32_t(implicits.size() - 1), 0};
  }
};

// Every crossing of the whole ray (t > 0).
std::vector<kernel::SolidCrossing> all_crossings(Solids& s, const Solid& solid, const Ray& ray, Real t_min = 0) {
  std::vector<kernel::SolidCrossing> out;
  kernel::for_each_solid_crossing(s.arrays(), solid, ray, t_min, kInfinity, [&](const kernel::SolidCrossing& c) {
    out.push_back(c);
    return false;
  });
  return out;
}

// Not inlined: GCC 12.2 with -march=native on an AVX-512 machine vectorises the copy of these
// constants after the struct's zero initialisation (SLP, 512-bit stores) into wrong values
// (coefficients 3 to 7 became 1); -fno-tree-slp-vectorize or -mprefer-vector-width=256 avoid it.
__attribute__((noinline)) kernel::Quadric quadric(std::initializer_list<Real> c) {
  kernel::Quadric q;
  std::memcpy(q.coef, c.begin(), sizeof q.coef);
  return q;
}

kernel::Cone cone(const Vec3& base, Real r0, const Vec3& cap, Real r1, bool open = false) {
  kernel::Cone c;
  c.base = base;
  c.height = length(cap - base);
  c.axis = (cap - base) / c.height;
  c.base_radius = r0;
  c.cap_radius = r1;
  c.open = open;
  return c;
}

// ---- quadrics ----

// (x − cx)² + (y − cy)² + (z − cz)² − r² expanded: the analytic sphere's t and normal.
TEST(Quadric, SphereCoefficientsGiveTheAnalyticSphere) {
  test::Random rng(1);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 c = rng.point(-3, 3);
    const Real r = rng.uniform(0.2, 2);
    const kernel::Sphere sphere{c, r, 0};
    Solids s;
    const Solid q = s.add(quadric({1, 1, 1, 0, 0, 0, -2 * c.x, -2 * c.y, -2 * c.z, dot(c, c) - r * r}));
    const Vec3 target = c + rng.direction() * (r * rng.uniform(0, 1.3));
    const Vec3 origin = rng.point(-8, 8);
    const Ray ray{origin, normalize(target - origin)};
    const Real want = kernel::intersect(sphere, ray, 0, kInfinity);
    const kernel::SolidCrossing got = kernel::intersect(s.arrays(), q, ray, 0, kInfinity);
    if (want == kInfinity) {
      // A miss, unless the ray grazes the sphere within rounding.
      if (got.t < kInfinity) {
        EXPECT_NEAR(length(ray.at(got.t) - c), r, 1e-6 * r);
      }
      continue;
    }
    ASSERT_LT(got.t, kInfinity) << i;
    EXPECT_NEAR(got.t, want, 1e-9 * (1 + want)) << i;
    const Vec3 p = ray.at(want);
    const Vec3 n = kernel::normal_at(s.arrays(), q, got.part, ray.at(got.t));
    EXPECT_NEAR(length(n - kernel::normal_at(sphere, p)), 0, 1e-8) << i;
    EXPECT_EQ(got.entering, length_squared(origin - c) > r * r) << i;
  }
}

// Axis-aligned rays: the unit cylinder x² + z² = 1, the double cone x² + z² = y², the
// hyperboloids x² + z² − y² = ±1, at known points.
TEST(Quadric, AxisAlignedRaysIntoCylinderConeAndHyperboloid) {
  struct Case {
    const char* name;
    kernel::Quadric q;
    Ray ray;
    std::vector<Real> t;  // every crossing for t > 0
  };
  const Vec3 x(1, 0, 0), y(0, 1, 0);
  const std::vector<Case> cases = {
      {"cylinder along x", quadric({1, 0, 1, 0, 0, 0, 0, 0, 0, -1}), {{-5, 7, 0}, x}, {4, 6}},
      {"cylinder along its axis", quadric({1, 0, 1, 0, 0, 0, 0, 0, 0, -1}), {{0.5, -5, 0}, y}, {}},
      {"cone at y = 0.5", quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, 0}), {{-5, 0.5, 0}, x}, {4.5, 5.5}},
      {"cone along its axis", quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, 0}), {{0, -5, 0}, y}, {5}},
      {"hyperboloid of one sheet at its waist", quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, -1}), {{-5, 0, 0}, x}, {4, 6}},
      {"hyperboloid of one sheet at y = √3", quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, -1}),
       {{-5, std::sqrt(3.0), 0}, x}, {3, 7}},
      {"hyperboloid of two sheets along its axis", quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, 1}), {{0, -5, 0}, y}, {4, 6}},
      {"hyperboloid of two sheets between them", quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, 1}), {{-5, 0, 0}, x}, {}},
  };
  for (const Case& c : cases) {
    Solids s;
    const Solid q = s.add(c.q);
    const auto got = all_crossings(s, q, c.ray);
    ASSERT_EQ(got.size(), c.t.size()) << c.name;
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i].t, c.t[i], 1e-12) << c.name;
  }
}

// A ray touching the unit sphere at (0, 1, 0): the double root, exactly; a hair above it misses.
TEST(Quadric, TangentRay) {
  Solids s;
  const Solid q = s.add(quadric({1, 1, 1, 0, 0, 0, 0, 0, 0, -1}));
  const auto touch = all_crossings(s, q, {{-5, 1, 0}, {1, 0, 0}});
  ASSERT_FALSE(touch.empty());
  for (const auto& c : touch) EXPECT_EQ(c.t, 5);
  EXPECT_TRUE(all_crossings(s, q, {{-5, 1 + 1e-9, 0}, {1, 0, 0}}).empty());
}

// Clipped: only the part within the box; the rest of the line misses.
TEST(Quadric, ClippedByABox) {
  kernel::Quadric q = quadric({1, 0, 1, 0, 0, 0, 0, 0, 0, -1});  // the cylinder x² + z² = 1
  q.clipped = true;
  q.lo = Vec3(-2, 0, -2);
  q.hi = Vec3(2, 1, 2);
  Solids s;
  const Solid solid = s.add(q);
  EXPECT_EQ(all_crossings(s, solid, {{-5, 0.5, 0}, {1, 0, 0}}).size(), 2u);
  EXPECT_TRUE(all_crossings(s, solid, {{-5, 1.5, 0}, {1, 0, 0}}).empty());
  EXPECT_FALSE(kernel::closed(s.arrays(), solid));
}

// ---- cylinder, cone, box ----

TEST(Cone, AxisAlignedRaysIntoCylinderAndCone) {
  Solids s;
  const Solid cyl = s.add(cone({0, 0, 0}, 1, {0, 2, 0}, 1));
  // Across the side at y = 1, along the axis through both caps, and from inside.
  auto c = all_crossings(s, cyl, {{-5, 1, 0}, {1, 0, 0}});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].t, 4, 1e-12);
  EXPECT_NEAR(c[1].t, 6, 1e-12);
  EXPECT_TRUE(c[0].entering);
  EXPECT_FALSE(c[1].entering);
  EXPECT_EQ(c[0].part, 0);
  c = all_crossings(s, cyl, {{0.5, -5, 0.25}, {0, 1, 0}});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].t, 5);
  EXPECT_EQ(c[1].t, 7);
  EXPECT_EQ(c[0].part, 1);  // the base cap
  EXPECT_EQ(c[1].part, 2);
  EXPECT_EQ(kernel::normal_at(s.arrays(), cyl, c[0].part, Vec3(0.5, 0, 0.25)), Vec3(0, -1, 0));
  c = all_crossings(s, cyl, {{0, 1, 0}, {0, 0, -1}});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].t, 1, 1e-12);
  EXPECT_FALSE(c[0].entering);

  // Open: the same ray along the axis meets nothing.
  const Solid open = s.add(cone({0, 0, 0}, 1, {0, 2, 0}, 1, true));
  EXPECT_TRUE(all_crossings(s, open, {{0.5, -5, 0.25}, {0, 1, 0}}).empty());

  // A pointed cone, radius 1 at y = 0 to 0 at y = 1: at y = 0.5 its radius is 0.5.
  const Solid pointed = s.add(cone({0, 0, 0}, 1, {0, 1, 0}, 0));
  c = all_crossings(s, pointed, {{-5, 0.5, 0}, {1, 0, 0}});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].t, 4.5, 1e-12);
  EXPECT_NEAR(c[1].t, 5.5, 1e-12);
  // Its side normal at (0.5, 0.5, 0): (1, 1, 0)/√2.
  EXPECT_NEAR(length(kernel::normal_at(s.arrays(), pointed, 0, {0.5, 0.5, 0}) - normalize(Vec3(1, 1, 0))), 0, 1e-15);
}

TEST(Box, FacesAndNormals) {
  Solids s;
  const Solid b = s.add(kernel::Box{{-1, -2, -3}, {1, 2, 3}});
  const auto c = all_crossings(s, b, {{0, 0, -10}, {0, 0, 1}});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].t, 7);
  EXPECT_EQ(c[1].t, 13);
  EXPECT_EQ(kernel::normal_at(s.arrays(), b, c[0].part, {}), Vec3(0, 0, -1));
  EXPECT_EQ(kernel::normal_at(s.arrays(), b, c[1].part, {}), Vec3(0, 0, 1));
  // Parallel to a slab and outside it: a miss, whatever the other axes say.
  EXPECT_TRUE(all_crossings(s, b, {{1.5, 0, -10}, {0, 0, 1}}).empty());
}

// ---- torus ----

// The torus's root finder (geometry/polynomial.h) on quartics and cubics with known real roots
// (x − r1)(x − r2)… — spread, with a pair 1e-6 to 1e-4 apart, or of magnitudes from 1e-3 to 50 —:
// every root is found, in order, as near the true one as the rounded coefficients allow, and each
// is bracketed to the last bit: f is 0 there or changes sign between it and a neighbouring double.
TEST(Polynomial, RootsAreFoundToAdjacentDoubles) {
  test::Random rng(11);
  auto changes_sign_at = [](const Real* c, int degree, Real x) {
    const Real f = kernel::polynomial(c, degree, x);
    if (f == 0) return true;
    const Real below = kernel::polynomial(c, degree, std::nextafter(x, -kInfinity));
    const Real above = kernel::polynomial(c, degree, std::nextafter(x, kInfinity));
    return (below < 0) != (f < 0) || (above < 0) != (f < 0);
  };
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const int degree = 3 + i % 2;
    Real r[4];
    for (int k = 0; k < degree; ++k) r[k] = rng.uniform(-1, 1);
    if (i % 3 == 1) r[1] = r[0] + rng.uniform(1e-6, 1e-4);  // a tight pair
    if (i % 3 == 2)                                          // magnitudes from 1e-3 to 50
      for (int k = 0; k < degree; ++k) r[k] = (rng.coin() ? 1 : -1) * rng.log_uniform(1e-3, 50);
    for (int k = 1; k < degree; ++k)
      for (int j = k; j > 0 && r[j] < r[j - 1]; --j) std::swap(r[j], r[j - 1]);
    // c = ∏ (x − r_k), expanded.
    Real c[5] = {1, 0, 0, 0, 0};
    for (int k = 0; k < degree; ++k)
      for (int j = k + 1; j >= 0; --j) c[j] = (j > 0 ? c[j - 1] : 0) - r[k] * c[j];
    Real roots[4];
    const int n = degree == 3 ? kernel::polynomial_roots<3>(c, -100, 100, roots)
                              : kernel::polynomial_roots<4>(c, -100, 100, roots);
    ASSERT_EQ(n, degree) << i;
    for (int k = 0; k < n; ++k) {
      // Within the conditioning of the rounded coefficients: ε·Σ|c_j||r|^j / |f'(r)|, times 64.
      Real slope = 1, size = 0, power = 1;
      for (int j = 0; j < degree; ++j)
        if (j != k) slope *= r[k] - r[j];
      for (int j = 0; j <= degree; ++j, power *= std::fabs(r[k])) size += std::fabs(c[j]) * power;
      EXPECT_NEAR(roots[k], r[k], 64 * 0x1p-52 * size / std::fabs(slope)) << i << " root " << k;
      EXPECT_TRUE(changes_sign_at(c, degree, roots[k])) << i << " root " << k << " = " << roots[k];
      if (k > 0) {
        EXPECT_LT(roots[k - 1], roots[k]) << i;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 70000);
}

// R = 1, r = 0.25 around y, scaled by `scale` and moved to `offset`: a ray along the x axis
// through the centre crosses at x = ±(R + r), ±(R − r); one parallel to the axis at distance R
// crosses at y = ±r. Relative to the torus's size, within 1e-9.
void expect_exact_torus(Real scale, const Vec3& offset) {
  SCOPED_TRACE(testing::Message() << "scale " << scale << ", offset " << offset.x);
  const Real R = scale, r = 0.25 * scale, far = 10 * scale;
  Solids s;
  const Solid t = s.add(kernel::Torus{offset, {0, 1, 0}, R, r});
  const Real tol = 1e-9 * scale;
  auto c = all_crossings(s, t, {offset + Vec3(-far, 0, 0), {1, 0, 0}});
  ASSERT_EQ(c.size(), 4u);
  const Real want[4] = {far - (R + r), far - (R - r), far + (R - r), far + (R + r)};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(c[std::size_t(i)].t, want[i], tol) << i;
    EXPECT_EQ(c[std::size_t(i)].entering, i % 2 == 0) << i;
  }
  c = all_crossings(s, t, {offset + Vec3(R, -far, 0), {0, 1, 0}});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].t, far - r, tol);
  EXPECT_NEAR(c[1].t, far + r, tol);
  // The same along a diagonal direction in the torus's plane.
  const Vec3 d = normalize(Vec3(1, 0, 1));
  c = all_crossings(s, t, {offset - d * far, d});
  ASSERT_EQ(c.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(c[std::size_t(i)].t, want[i], tol) << "diagonal " << i;
}

TEST(Torus, ExactHitsAtEveryScaleAndOffset) {
  expect_exact_torus(1, Vec3(0));
  expect_exact_torus(1e-3, Vec3(0));
  expect_exact_torus(1e4, Vec3(0));
  expect_exact_torus(1, Vec3(1e5, -1e5, 1e5));
  expect_exact_torus(1e4, Vec3(1e5, 0, -1e5));
}

// normal = normalize(p − R·(p projected onto the torus's plane, normalised)), at hits of random
// rays; the hit lies on the surface: its distance from the centre circle is r.
TEST(Torus, NormalFormulaAndHitsOnTheSurface) {
  test::Random rng(7);
  const Vec3 axis = normalize(Vec3(0.3, 1, -0.2));
  const Vec3 center(0.5, -1, 2);
  const Real R = 1.5, r = 0.4;
  Solids s;
  const Solid t = s.add(kernel::Torus{center, axis, R, r});
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 origin = center + rng.point(-5, 5);
    const Vec3 target = center + rng.point(-2, 2);
    const Ray ray{origin, normalize(target - origin)};
    const kernel::SolidCrossing c = kernel::intersect(s.arrays(), t, ray, 0, kInfinity);
    if (c.t == kInfinity) continue;
    ++hits;
    const Vec3 p = ray.at(c.t) - center;
    const Vec3 in_plane = p - axis * dot(p, axis);
    EXPECT_NEAR(length(p - normalize(in_plane) * R), r, 1e-12) << i;
    const Vec3 want = normalize(p - normalize(in_plane) * R);
    EXPECT_NEAR(length(kernel::normal_at(s.arrays(), t, c.part, ray.at(c.t)) - want), 0, 1e-12) << i;
  }
  EXPECT_GT(hits, 1000);
}

// ---- implicit ----

// sqrt(x² + y² + z²) − 1 through the solid interface equals the analytic unit sphere within
// `accuracy`, by every method.
TEST(ImplicitSolid, UnitSphereByEveryMethod) {
  const kernel::RootMethod methods[] = {kernel::RootMethod::Lipschitz, kernel::RootMethod::SphereTrace,
                                        kernel::RootMethod::March};
  for (const kernel::RootMethod m : methods) {
    kernel::Implicit f;
    f.f = compile_expression("sqrt(x^2 + y^2 + z^2) - 1");
    f.lo = Vec3(-1.5);
    f.hi = Vec3(1.5);
    f.method = m;
    f.max_gradient = 1;
    f.accuracy = 1e-4;
    f.step = 0.01;
    Solids s;
    const Solid solid = s.add(f);
    test::Random rng(11);
    for (int i = 0; i < 500; ++i) {
      const Vec3 origin = rng.point(-4, 4);
      const Vec3 target = rng.direction() * rng.uniform(0, 0.95);
      const Ray ray{origin, normalize(target - origin)};
      const Real want = kernel::intersect(kernel::Sphere{Vec3(0), 1, 0}, ray, 0, kInfinity);
      const kernel::SolidCrossing got = kernel::intersect(s.arrays(), solid, ray, 0, kInfinity);
      ASSERT_LT(got.t, kInfinity) << int(m) << " " << i;
      EXPECT_NEAR(got.t, want, f.accuracy) << int(m) << " " << i;
    }
    // A distance's gradient is 1: nothing above max_gradient was met.
    EXPECT_LE(kernel::max_gradient_of(s.tallies[0]), 1 + 1e-9);
  }
}

// ---- invariants over every closed solid ----

struct Shape {
  const char* name;
  Solid solid;
  bool (*analytic)(const Vec3&);  // membership by a formula of its own
};

// inside() agrees with the analytic membership at 100,000 random points per shape, and along a
// random ray from each point the number of crossings is odd exactly when the point is inside
// (and the ray's far end is not: an unbounded quadric).
TEST(Solids, InsideAgreesWithAnalyticMembershipAndCrossingParity) {
  Solids s;
  kernel::Implicit blob;
  blob.f = compile_expression("x^2 + y^2 + z^2 - 1");
  blob.lo = Vec3(-1.2, -1.2, -1.2);
  blob.hi = Vec3(1.2, 0.5, 1.2);  // cut by the bound at y = 0.5
  blob.max_gradient = 2.4 * 1.1;
  blob.accuracy = 1e-6;
  const Shape shapes[] = {
      {"box", s.add(kernel::Box{{-1, -0.5, -0.25}, {1, 0.5, 0.25}}),
       [](const Vec3& p) { return std::fabs(p.x) < 1 && std::fabs(p.y) < 0.5 && std::fabs(p.z) < 0.25; }},
      {"cylinder", s.add(cone({0, -1, 0}, 0.8, {0, 1, 0}, 0.8)),
       [](const Vec3& p) { return std::fabs(p.y) < 1 && p.x * p.x + p.z * p.z < 0.64; }},
      {"cone", s.add(cone({0, -1, 0}, 1.2, {0, 1, 0}, 0.2)),
       [](const Vec3& p) {
         const Real r = 1.2 - 0.5 * (p.y + 1);
         return std::fabs(p.y) < 1 && p.x * p.x + p.z * p.z < r * r;
       }},
      {"tilted cylinder", s.add(cone({-1, -1, -1}, 0.5, {1, 1, 1}, 0.5)),
       [](const Vec3& p) {
         const Vec3 a = normalize(Vec3(1, 1, 1));
         const Real z = dot(p, a);
         return std::fabs(z) < std::sqrt(3.0) && length_squared(p - a * z) < 0.25;
       }},
      {"torus", s.add(kernel::Torus{{0, 0, 0}, {0, 1, 0}, 1, 0.3}),
       [](const Vec3& p) {  // the quartic's sign
         const Real k = dot(p, p) + 1 - 0.09;
         return k * k - 4 * (p.x * p.x + p.z * p.z) < 0;
       }},
      {"sphere quadric", s.add(quadric({1, 1, 1, 0, 0, 0, 0, 0, 0, -1})),
       [](const Vec3& p) { return length_squared(p) < 1; }},
      {"hyperboloid quadric", s.add(quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, -0.25})),
       [](const Vec3& p) { return p.x * p.x + p.z * p.z < 0.25 + p.y * p.y; }},
      {"implicit ball cut by its bound", s.add(blob),
       [](const Vec3& p) { return length_squared(p) < 1 && p.y <= 0.5; }},
  };
  test::Random rng(13);
  for (const Shape& sh : shapes) {
    int inside = 0, mismatches = 0, parity_mismatches = 0;
    for (int i = 0; i < 100000; ++i) {
      const Vec3 p = rng.point(-1.6, 1.6);
      const bool want = sh.analytic(p);
      inside += want;
      mismatches += kernel::inside(s.arrays(), sh.solid, p) != want;
      if (i % 5 != 0) continue;  // the crossing counts at 20,000 of the points
      const Ray ray{p, rng.direction()};
      const int n = kernel::crossings(s.arrays(), sh.solid, ray, 0, kInfinity);
      // Unbounded quadrics may be inside at the ray's far end too.
      parity_mismatches += (n % 2 == 1) != (want != sh.analytic(ray.at(1e8)));
    }
    EXPECT_EQ(mismatches, 0) << sh.name;
    // A point within rounding (or, implicit: within accuracy) of the surface may go either way.
    EXPECT_LE(parity_mismatches, 2) << sh.name;
    EXPECT_GT(inside, 1000) << sh.name;
  }
}

}  // namespace
}  // namespace strahl::solid_test

namespace strahl::solid_test {
namespace {

// x² + y² + z² − 1 in a sphere of radius 1.2 has |∇f| = 2|p| ≤ 2.4: at max_gradient 2.4 it
// renders exactly where the unit sphere does (no holes) and nothing is reported; at 1.1 the render
// ends with the warning, which names the object and a max_gradient above the 2.4 met.
std::string implicit_scene(Real max_gradient) {
  return "camera: {position: [0, 0, 4], look_at: [0, 0, 0], fov: 40}\n"
         "render: {width: 48, height: 48}\n"
         "lights: [{type: point, position: [2, 3, 4]}]\n"
         "objects:\n"
         "  - type: implicit\n"
         "    expression: x^2 + y^2 + z^2 - 1\n"
         "    contained_by: {type: sphere, center: [0, 0, 0], radius: 1.2}\n"
         "    accuracy: 0.0001\n"
         "    max_gradient: " +
         std::to_string(max_gradient) + "\n";
}

TEST(ImplicitSolid, MaxGradientWarningAndNoHoles) {
  const std::string sphere_scene =
      "camera: {position: [0, 0, 4], look_at: [0, 0, 0], fov: 40}\n"
      "render: {width: 48, height: 48}\n"
      "lights: [{type: point, position: [2, 3, 4]}]\n"
      "objects: [{type: sphere, center: [0, 0, 0], radius: 1}]\n";
  const Image want = render(compile(parse_scene(sphere_scene, "sphere.yaml", ".")), {1, 16});
  const RenderScene good = compile(parse_scene(implicit_scene(2.4), "good.yaml", "."));
  const Image got = render(good, {1, 16});
  EXPECT_TRUE(implicit_warnings(good).empty()) << implicit_warnings(good).front();
  // Every pixel the sphere covers is covered (the same colour up to the normal's differences).
  int holes = 0;
  for (int y = 0; y < want.height(); ++y)
    for (int x = 0; x < want.width(); ++x)
      holes += (want.at(x, y).r > 0) != (got.at(x, y).r > 0);
  EXPECT_EQ(holes, 0);

  const RenderScene low = compile(parse_scene(implicit_scene(1.1), "low.yaml", "."));
  (void)render(low, {1, 16});
  const std::vector<std::string> w = implicit_warnings(low);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("low.yaml:5:5: the implicit surface's gradient reached 2."), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("above its max_gradient 1.1"), std::string::npos) << w[0];
  EXPECT_GT(kernel::max_gradient_of(low.implicit_tallies[0]), 1.1);
  EXPECT_LE(kernel::max_gradient_of(low.implicit_tallies[0]), 2.4 + 1e-9);
}

}  // namespace
}  // namespace strahl::solid_test

#if defined(STRAHL_HAVE_EMBREE)
namespace strahl::solid_test {
namespace {

// Embree has no user geometry for solids yet: a scene with solids is built as the BVH and renders
// as it does.
TEST(Solids, EmbreeFallsBackToTheBvh) {
  Scene scene = load_scene(std::string(STRAHL_SOURCE_DIR) + "/scenes/shapes.yaml");
  scene.settings.width = 64;
  scene.settings.height = 36;
  scene.settings.accel = AccelKind::Bvh;
  const Image want = render(compile(scene), {1, 16});
  scene.settings.accel = AccelKind::Embree;
  const RenderScene rs = compile(scene);
  EXPECT_EQ(rs.accel.kind, AccelKind::Bvh);
  EXPECT_TRUE(render(rs, {1, 16}) == want);
}

}  // namespace
}  // namespace strahl::solid_test
#endif

namespace strahl::solid_test {
namespace {

// A shadow ray through a transparent (non-filtering) solid is attenuated once per crossing: twice
// through a box, four times along a torus's diameter, and an unclipped quadric (outside the
// acceleration structure) counts as well; an opaque solid blocks it.
TEST(Solids, ShadowRaysAttenuatedByEveryCrossing) {
  const std::string scene =
      "lights: [{type: point, position: [0, 5, 0]}]\n"
      "materials: {clear: {transparency: 0.5}}\n"
      "objects:\n"
      "  - {type: box, corners: [[-1, -1, -1], [1, 1, 1]], material: clear}\n"
      "  - {type: torus, center: [10, 0, 0], major_radius: 2, minor_radius: 0.5, material: clear}\n"
      "  - {type: quadric, coefficients: [1, 1, 1, 0, 0, 0, 0, 0, -40, 399], material: clear}\n"
      "  - {type: cylinder, base: [0, -1, 30], cap: [0, 1, 30], radius: 1}\n";
  for (AccelKind k : {AccelKind::Naive, AccelKind::Bvh, AccelKind::KdTree, AccelKind::Octree}) {
    Scene sc = parse_scene(scene, "shadow.yaml", ".");
    sc.settings.accel = k;
    const RenderScene rs = compile(sc);
    ASSERT_EQ(rs.bounded_solid_count, 3u);
    const SceneView v = rs.view();
    // Through the box along x, from outside to outside.
    EXPECT_EQ(transmittance(v, {{-5, 0, 0}, {1, 0, 0}}, 10).x, 0.25) << accel_name(k);
    // Along the torus's diameter: four crossings.
    EXPECT_EQ(transmittance(v, {{4, 0, 0}, {1, 0, 0}}, 12).x, 0.0625) << accel_name(k);
    // Through the sphere quadric x² + y² + (z − 20)² = 1: two crossings.
    EXPECT_EQ(transmittance(v, {{0, 0, 15}, {0, 0, 1}}, 10).x, 0.25) << accel_name(k);
    // Into the opaque cylinder: blocked.
    EXPECT_EQ(transmittance(v, {{0, 0, 25}, {0, 0, 1}}, 10).x, 0.0) << accel_name(k);
  }
}

}  // namespace
}  // namespace strahl::solid_test
