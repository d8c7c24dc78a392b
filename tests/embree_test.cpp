// Embree (AccelKind::Embree) against the naive loop: the same nearest hits, occlusion answers and
// shadow crossings on random rays through random spheres and triangles, and a mesh scene that
// renders nearly the same image with either.
//
// What must agree, and why. Spheres go through strahl's own double-precision test inside an
// Embree user geometry, so sphere hits match the naive loop exactly. Triangles are traversed and
// intersected by Embree in float (vertices, ray origin and direction rounded to 24 bits), and the
// nearest triangle's t, b1, b2 are then recomputed in double (embree_accel.h), so:
//   * when both find the same triangle, t and the barycentrics are exactly the naive loop's
//     (before that refinement, Embree's float t was within 1e-6 relative of the double one —
//     |Δt|·|cos θ| / max(1, t) at most 2e-7 here, up to ~3e-6 outright near grazing);
//   * which triangle is hit is float's choice: answers may differ where the ray passes within
//     kEdge (in barycentric coordinates) of a triangle's edge, or meets it at a grazing angle
//     (|cos θ| < kGrazing), or within float rounding (kRelT) of either end of the interval. Such
//     rays are counted and must stay rare (below kMaxEdgeFraction; none were seen in these
//     30,000 rays); any other difference fails.
// Triangle hits near the ray's start are confirmed by strahl's double test (embree_accel.h), so
// secondary rays leaving a surface must not hit it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/image/metrics.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/scene_file.h"

namespace strahl::embree_test {
namespace {

constexpr Real kRelT = 1e-6;
constexpr Real kEdge = 1e-5;
constexpr Real kGrazing = 1e-3;  // |cos| of the angle between ray and triangle normal
constexpr double kMaxEdgeFraction = 2e-3;

struct Random {
  std::mt19937_64 gen;
  explicit Random(std::uint64_t seed) : gen(seed) {}
  Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(gen); }
  Vec3 in_box(Real h) { return {uniform(-h, h), uniform(-h, h), uniform(-h, h)}; }
  Vec3 direction() {
    for (;;) {
      const Vec3 v = in_box(1);
      const Real l2 = length_squared(v);
      if (l2 > 1e-4 && l2 <= 1) return v / std::sqrt(l2);
    }
  }
};

struct Prims {
  std::vector<kernel::Sphere> spheres;
  std::vector<kernel::Triangle> triangles;
  PrimitiveSet set() const {
    return {spheres.data(), std::uint32_t(spheres.size()), triangles.data(), std::uint32_t(triangles.size()), nullptr, 0, {}};
  }
};

// Spheres and triangles of assorted sizes scattered in [-1, 1]³, plus a closed octahedron made of
// triangles that share their edges (as a mesh's do).
Prims random_prims(std::uint64_t seed, int spheres, int triangles) {
  Random rng(seed);
  Prims p;
  for (int i = 0; i < spheres; ++i) p.spheres.push_back({rng.in_box(1), rng.uniform(0.02, 0.2), 0});
  for (int i = 0; i < triangles; ++i) {
    const Vec3 a = rng.in_box(1);
    const Real size = rng.uniform(0.02, 0.3);
    const Vec3 e1 = rng.direction() * size, e2 = rng.direction() * size;
    if (length_squared(cross(e1, e2)) > 1e-12) p.triangles.push_back({a, a + e1, a + e2, 0, -1, 0});
  }
  const Vec3 c(0.2, -0.1, 0.3);
  const Vec3 ax[6] = {{0.4, 0, 0}, {-0.4, 0, 0}, {0, 0.4, 0}, {0, -0.4, 0}, {0, 0, 0.4}, {0, 0, -0.4}};
  for (int x : {0, 1})
    for (int y : {2, 3})
      for (int z : {4, 5}) {
        const Vec3 v0 = c + ax[x], v1 = c + ax[y], v2 = c + ax[z];
        p.triangles.push_back({v0, v1, v2, 0, -1, 0});
      }
  return p;
}

// Does the ray pass within kEdge of the triangle's boundary (barycentric), or graze it?
bool near_edge(const kernel::Triangle& tri, const Ray& ray) {
  const Vec3 e1 = tri.edge1(), e2 = tri.edge2();
  const Vec3 n = cross(e1, e2);
  if (std::fabs(dot(normalize(n), ray.direction)) < kGrazing) return true;
  const Vec3 pvec = cross(ray.direction, e2);
  const Real inv_det = 1 / dot(e1, pvec);
  const Vec3 tvec = ray.origin - tri.v0;
  const Real b1 = dot(tvec, pvec) * inv_det;
  const Real b2 = dot(ray.direction, cross(tvec, e1)) * inv_det;
  const Real margin = std::min({b1, b2, 1 - b1 - b2});
  return std::fabs(margin) < kEdge;
}

// A difference between Embree and the naive loop on this ray that float rounding explains: some
// triangle the ray passes near the edge of (or grazes) within the interval, or meets right at
// either end of it.
bool explained(const PrimitiveSet& prims, const Ray& ray, Real t_min, Real t_max) {
  for (std::uint32_t i = 0; i < prims.triangle_count; ++i) {
    const kernel::Triangle& tri = prims.triangles[i];
    // Where the ray meets the triangle's plane, if it does within the interval (a little widened).
    const Vec3 n = cross(tri.edge1(), tri.edge2());
    const Real denom = dot(n, ray.direction);
    if (denom == 0) continue;
    const Real t = dot(n, tri.v0 - ray.origin) / denom;
    const Real slack = 4 * kRelT * std::max(Real(1), std::fabs(t_max));
    if (!(t > t_min - slack && t < t_max + slack)) continue;
    if (near_edge(tri, ray)) return true;
    // Inside the triangle, right at either end of the interval.
    const kernel::TriangleHit h = kernel::intersect(tri, ray, -kInfinity, kInfinity);
    if (h.t < kInfinity && (t < t_min + slack || t > t_max - slack)) return true;
  }
  return false;
}

struct Agreement {
  int rays = 0, explained = 0, unexplained = 0, same_triangle = 0;
};

TEST(Embree, RegisteredAsAnAccelerator) {
  ASSERT_TRUE(accel_from_name("embree").has_value());
  EXPECT_EQ(*accel_from_name("embree"), AccelKind::Embree);
  EXPECT_EQ(accel_name(AccelKind::Embree), "embree");
  EXPECT_NE(accel_names().find("embree"), std::string::npos);
}

TEST(Embree, EmptySceneHasNoHits) {
  const Prims p;
  const Accel accel = build_accel(AccelKind::Embree, p.set());
  const AccelView view = accel.view(p.set());
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  EXPECT_EQ(nearest_hit(view, ray, 0, kInfinity).hit.t, kInfinity);
  EXPECT_FALSE(occluded(view, ray, 0, kInfinity));
}

TEST(Embree, NearestHitAgreesWithNaive) {
  const Prims p = random_prims(7, 60, 3000);
  const PrimitiveSet prims = p.set();
  const Accel naive = build_accel(AccelKind::Naive, prims);
  const Accel embree = build_accel(AccelKind::Embree, prims);
  const AccelView nv = naive.view(prims), ev = embree.view(prims);
  Random rng(11);
  Agreement a;
  int hits = 0, sphere_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray{rng.in_box(1.5), rng.direction()};
    const NearestHit n = nearest_hit(nv, ray, 0, kInfinity);
    const NearestHit e = nearest_hit(ev, ray, 0, kInfinity);
    ++a.rays;
    hits += n.hit.t < kInfinity;
    if (n.hit.t < kInfinity && e.hit.t < kInfinity && n.prim == e.prim) {
      if (prims.is_sphere(n.prim)) {
        ++sphere_hits;
        EXPECT_EQ(e.hit.t, n.hit.t) << "ray " << i << ": sphere hits are exact";
        continue;
      }
      // Refined in double: the naive loop's own numbers (the same arithmetic; 4 ulps allowed).
      EXPECT_DOUBLE_EQ(e.hit.t, n.hit.t) << "ray " << i;
      EXPECT_DOUBLE_EQ(e.hit.b1, n.hit.b1) << "ray " << i;
      EXPECT_DOUBLE_EQ(e.hit.b2, n.hit.b2) << "ray " << i;
      ++a.same_triangle;
      continue;
    }
    const bool both = n.hit.t < kInfinity && e.hit.t < kInfinity;
    // Two primitives at the same distance (within float) are both right.
    if (both && std::fabs(e.hit.t - n.hit.t) <= kRelT * std::max(Real(1), n.hit.t)) continue;
    if (n.hit.t == kInfinity && e.hit.t == kInfinity) continue;
    const Real t_max = std::max(n.hit.t < kInfinity ? n.hit.t : 0, e.hit.t < kInfinity ? e.hit.t : 0);
    if (explained(prims, ray, 0, t_max)) {
      ++a.explained;
    } else {
      ++a.unexplained;
      ADD_FAILURE() << "ray " << i << ": naive prim " << n.prim << " t " << n.hit.t << ", embree prim " << e.prim
                    << " t " << e.hit.t;
    }
  }
  EXPECT_GT(hits, 2000);  // the scene is actually hit, spheres included
  EXPECT_GT(sphere_hits, 200);
  EXPECT_EQ(a.unexplained, 0);
  EXPECT_LE(a.explained, kMaxEdgeFraction * a.rays);
  RecordProperty("hits", hits);
  RecordProperty("sphere_hits", sphere_hits);
  RecordProperty("near_edge_differences", a.explained);
  RecordProperty("same_triangle", a.same_triangle);
}

TEST(Embree, OccludedAndCrossingsAgreeWithNaive) {
  const Prims p = random_prims(8, 60, 3000);
  const PrimitiveSet prims = p.set();
  const Accel naive = build_accel(AccelKind::Naive, prims);
  const Accel embree = build_accel(AccelKind::Embree, prims);
  const AccelView nv = naive.view(prims), ev = embree.view(prims);
  Random rng(12);
  Agreement occ, cross;
  int occluded_count = 0, multi_crossings = 0;
  for (int i = 0; i < 10000; ++i) {
    const Ray ray{rng.in_box(1.5), rng.direction()};
    const Real t_max = rng.uniform(0.05, 3);
    const bool n = occluded(nv, ray, 0, t_max), e = occluded(ev, ray, 0, t_max);
    ++occ.rays;
    occluded_count += n;
    if (n != e) {
      if (explained(prims, ray, 0, t_max)) {
        ++occ.explained;
      } else {
        ++occ.unexplained;
        ADD_FAILURE() << "ray " << i << ": occluded naive " << n << ", embree " << e;
      }
    }
    // Shadow crossings: every surface crossing in (0, t_max), each primitive's count.
    std::vector<int> count_n(prims.size()), count_e(prims.size());
    auto count_into = [](std::vector<int>& counts) {
      return [&counts](std::uint32_t prim, int k) {
        counts[prim] += k;
        return false;
      };
    };
    auto cn = count_into(count_n);
    auto ce = count_into(count_e);
    for_each_crossing(nv, ray, 0, t_max, cn);
    for_each_crossing(ev, ray, 0, t_max, ce);
    ++cross.rays;
    int total = 0;
    for (int c : count_n) total += c;
    multi_crossings += total >= 2;
    if (count_n != count_e) {
      if (explained(prims, ray, 0, t_max)) {
        ++cross.explained;
      } else {
        ++cross.unexplained;
        ADD_FAILURE() << "ray " << i << ": crossings differ";
      }
    }
  }
  EXPECT_GT(occluded_count, 1000);
  EXPECT_GT(multi_crossings, 250);
  EXPECT_EQ(occ.unexplained, 0);
  EXPECT_EQ(cross.unexplained, 0);
  EXPECT_LE(occ.explained, kMaxEdgeFraction * occ.rays);
  EXPECT_LE(cross.explained, kMaxEdgeFraction * cross.rays);
  RecordProperty("occluded", occluded_count);
  RecordProperty("two_or_more_crossings", multi_crossings);
  RecordProperty("occluded_near_edge_differences", occ.explained);
  RecordProperty("crossings_near_edge_differences", cross.explained);
}

TEST(Embree, CrossingsStopWhenAsked) {
  const Prims p = random_prims(9, 0, 0);  // the octahedron alone
  const PrimitiveSet prims = p.set();
  const Accel embree = build_accel(AccelKind::Embree, prims);
  const Ray ray{{0.21, -0.09, -2}, {0, 0, 1}};  // through the octahedron: two crossings
  int calls = 0;
  auto all = [&](std::uint32_t, int) { ++calls; return false; };
  for_each_crossing(embree.view(prims), ray, 0, kInfinity, all);
  EXPECT_EQ(calls, 2);
  calls = 0;
  auto first = [&](std::uint32_t, int) { ++calls; return true; };
  for_each_crossing(embree.view(prims), ray, 0, kInfinity, first);
  EXPECT_EQ(calls, 1);
}

// A secondary ray leaves a surface from a point pushed off it by only kRayEpsilon (relative),
// (render/surface_point.h), which float cannot represent: Embree must still not hit the surface the ray starts on.
TEST(Embree, SecondaryRaysDoNotHitTheSurfaceTheyLeave) {
  const Prims p = random_prims(9, 0, 0);  // the octahedron alone: convex and closed
  const PrimitiveSet prims = p.set();
  const Accel naive = build_accel(AccelKind::Naive, prims);
  const Accel embree = build_accel(AccelKind::Embree, prims);
  Random rng(13);
  for (int i = 0; i < 5000; ++i) {
    const kernel::Triangle& tri = p.triangles[std::size_t(i) % p.triangles.size()];
    Real u = rng.uniform(0, 1), v = rng.uniform(0, 1);
    if (u + v > 1) { u = 1 - u; v = 1 - v; }
    const Vec3 point = tri.v0 + tri.edge1() * u + tri.edge2() * v;
    Vec3 n = kernel::geometric_normal(tri);
    if (dot(n, point - Vec3(0.2, -0.1, 0.3)) < 0) n = -n;  // outwards from the octahedron's centre
    Vec3 d = rng.direction();
    // The renderer's offset for a triangle hit (render/surface_point.h): relative to the vertices.
    const Real offset = kRayEpsilon * vertex_magnitude(tri.v0, tri.v1, tri.v2);
    const Ray out = spawn_ray(point, n, dot(d, n) > 0 ? d : -d, 0, offset);
    const Ray in = spawn_ray(point, n, dot(d, n) > 0 ? -d : d, 0, offset);
    EXPECT_EQ(nearest_hit(embree.view(prims), out, 0, kInfinity).hit.t, kInfinity) << "ray " << i;
    EXPECT_FALSE(occluded(embree.view(prims), out, 0, 10)) << "ray " << i;
    const NearestHit e = nearest_hit(embree.view(prims), in, 0, kInfinity);
    const NearestHit r = nearest_hit(naive.view(prims), in, 0, kInfinity);
    ASSERT_LT(r.hit.t, kInfinity);
    EXPECT_NEAR(e.hit.t, r.hit.t, 1e-5) << "ray " << i;  // the far side, not the start
  }
}

TEST(Embree, CopiesAndMovesShareTheScene) {
  const Prims p = random_prims(10, 5, 50);
  const PrimitiveSet prims = p.set();
  Accel original = build_accel(AccelKind::Embree, prims);
  const Ray ray{{0.2, -0.1, -3}, {0, 0, 1}};
  const Real t = nearest_hit(original.view(prims), ray, 0, kInfinity).hit.t;
  ASSERT_LT(t, kInfinity);
  Accel copy = original;
  Accel moved = std::move(original);
  original = Accel{};  // the source is released; the copies keep the scene alive
  EXPECT_EQ(nearest_hit(copy.view(prims), ray, 0, kInfinity).hit.t, t);
  EXPECT_EQ(nearest_hit(moved.view(prims), ray, 0, kInfinity).hit.t, t);
}

TEST(Embree, MeshSceneRendersAsWithTheBvh) {
  Scene scene = load_scene(STRAHL_SOURCE_DIR "/scenes/mesh.yaml");
  scene.settings.width = 240;
  scene.settings.height = 135;
  scene.settings.supersample = 1;
  scene.settings.accel = AccelKind::Bvh;
  const Image bvh = render(compile(scene), {});
  scene.settings.accel = AccelKind::Embree;
  const Image embree = render(compile(scene), {});
  // Pixels may differ only where a ray grazes an edge; count those that differ visibly.
  int differing = 0;
  for (std::size_t i = 0; i < bvh.pixels().size(); ++i) {
    const Rgb &a = bvh.pixels()[i], &b = embree.pixels()[i];
    differing += std::max({std::fabs(a.r - b.r), std::fabs(a.g - b.g), std::fabs(a.b - b.b)}) > 1e-3f;
  }
  EXPECT_LE(differing, int(bvh.pixels().size() / 200)) << "over 0.5% of the pixels differ";
  EXPECT_LT(rmse(bvh, embree), 5e-3);
  RecordProperty("differing_pixels", differing);
}

}  // namespace
}  // namespace strahl::embree_test
