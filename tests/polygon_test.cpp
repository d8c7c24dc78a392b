// Polygons split into triangles (scene/polygon.h) and OBJ faces of many corners (issue 12: one
// polygon of 200,000 corners took minutes in tinyobjloader's quadratic triangulation).
// Invariants of a triangulation of a simple polygon: n − 2 triangles, none turned over, their
// areas summing to the polygon's area (then they cover it without overlap).

#include <gtest/gtest.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

#include "strahl/scene/obj_loader.h"
#include "strahl/scene/polygon.h"
#include "strahl/util/error.h"
#include "test_helpers.h"

namespace strahl::polygon_test {
namespace {

// Twice the signed area in the xy plane.
double area2(const Vec3& a, const Vec3& b, const Vec3& c) {
  return double(b.x - a.x) * double(c.y - a.y) - double(b.y - a.y) * double(c.x - a.x);
}

double polygon_area2(const std::vector<Vec3>& p) {
  double sum = 0;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum += area2(p[0], p[i], p[i + 1]);
  return sum;
}

// Checks the invariants for a counter-clockwise simple polygon in the xy plane.
void expect_valid_triangulation(const std::vector<Vec3>& p, const std::string& what) {
  std::vector<PolygonTriangle> t;
  ASSERT_TRUE(triangulate_polygon(p, t)) << what;
  ASSERT_EQ(t.size(), p.size() - 2) << what;
  double sum = 0, smallest = 0;
  for (const PolygonTriangle& tri : t) {
    for (std::uint32_t k : tri) ASSERT_LT(k, p.size()) << what;
    const double a = area2(p[tri[0]], p[tri[1]], p[tri[2]]);
    smallest = std::min(smallest, a);
    sum += a;
  }
  const double area = polygon_area2(p);
  EXPECT_GE(smallest, -1e-9 * area) << what << ": a triangle is turned over";
  EXPECT_NEAR(sum, area, 1e-9 * area) << what;
}

// A random star-shaped polygon: n corners at increasing angles, radii in [0.2, 1] (many reflex corners).
std::vector<Vec3> random_star(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> radius(0.2, 1);
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    const double r = radius(rng);
    p.emplace_back(r * std::cos(a), r * std::sin(a), 0);
  }
  return p;
}

TEST(Polygon, ConvexPolygonsBecomeFans) {
  std::vector<Vec3> hexagon;
  for (int i = 0; i < 6; ++i) hexagon.emplace_back(std::cos(i * kPi / 3), std::sin(i * kPi / 3), 0);
  std::vector<PolygonTriangle> t;
  ASSERT_TRUE(triangulate_polygon(hexagon, t));
  ASSERT_EQ(t.size(), 4u);
  for (std::uint32_t i = 0; i < 4; ++i) EXPECT_EQ(t[i], (PolygonTriangle{0, i + 1, i + 2}));
  // A convex quad along its shorter diagonal, (1, 3) here.
  t.clear();
  ASSERT_TRUE(triangulate_polygon(std::vector<Vec3>{{0, 0, 0}, {1, -0.2, 0}, {2, 0, 0}, {1, 0.2, 0}}, t));
  EXPECT_EQ(t, (std::vector<PolygonTriangle>{{0, 1, 3}, {1, 2, 3}}));
}

TEST(Polygon, ConcavePolygonsAreSplitWithoutOverlap) {
  // An L shape: a fan from corner 0 would cover the notch.
  expect_valid_triangulation({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, "L");
  // A concave quad (a dart): the diagonal must go through the reflex corner.
  expect_valid_triangulation({{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}}, "dart");
  std::mt19937 rng(12);
  for (int n : {5, 7, 20, 100, 1000}) expect_valid_triangulation(random_star(n, rng), "star " + std::to_string(n));
  // A comb: teeth along the top edge.
  std::vector<Vec3> comb{{0, 0, 0}, {40, 0, 0}};
  for (int i = 19; i >= 0; --i) {
    comb.emplace_back(2 * i + 2, 5, 0);
    comb.emplace_back(2 * i + 1.5, 1, 0);
    comb.emplace_back(2 * i + 0.5, 1, 0);
  }
  expect_valid_triangulation(comb, "comb");
}

TEST(Polygon, OrientationAndPlaneDoNotMatter) {
  std::mt19937 rng(7);
  std::vector<Vec3> star = random_star(50, rng);
  std::vector<Vec3> clockwise(star.rbegin(), star.rend());
  std::vector<PolygonTriangle> t;
  ASSERT_TRUE(triangulate_polygon(clockwise, t));
  double sum = 0;
  for (const PolygonTriangle& tri : t) {
    const double a = area2(clockwise[tri[0]], clockwise[tri[1]], clockwise[tri[2]]);
    EXPECT_LE(a, 1e-12);  // clockwise, like the polygon
    sum += a;
  }
  EXPECT_NEAR(sum, polygon_area2(clockwise), 1e-9);
  // The same star in the yz plane: the same triangles.
  std::vector<Vec3> yz;
  for (const Vec3& p : star) yz.emplace_back(0, p.x, p.y);
  std::vector<PolygonTriangle> a, b;
  ASSERT_TRUE(triangulate_polygon(star, a));
  ASSERT_TRUE(triangulate_polygon(yz, b));
  EXPECT_EQ(a, b);
}

TEST(Polygon, TooManyReflexCornersIsRefusedNotSlow) {
  std::mt19937 rng(3);
  std::vector<PolygonTriangle> t;
  EXPECT_FALSE(triangulate_polygon(random_star(2000, rng), t, 10'000));
  EXPECT_TRUE(t.empty());
}

// The OBJ text of one polygon: a circle of n corners written with 7 significant digits (so the
// corners are convex only up to rounding), plus a notch (one reflex corner) when `notch`.
std::string circle_obj(int n, bool notch) {
  std::ostringstream s;
  s.precision(7);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    const double r = notch && i == n / 2 ? 0.5 : 1.0;
    s << "v " << r * std::cos(a) << ' ' << r * std::sin(a) << " 0\n";
  }
  s << 'f';
  for (int i = 1; i <= n; ++i) s << ' ' << i;
  s << '\n';
  return s.str();
}

// The best of three loads. The loads' memory stays in the heap between them (glibc: no block of
// its own per large allocation, nothing given back at free), so the runs after the first time
// the parsing, not the page faults of fresh memory — 10 µs per 4 KiB page in some virtual
// machines, a quarter of the large load's time there, which pushed its ratio past the bound.
double load_seconds(const std::string& text, std::size_t expected_faces) {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  double best = 1e9;
  for (int run = 0; run < 3; ++run) {
    const auto t0 = std::chrono::steady_clock::now();
    const MeshData mesh = parse_obj(text, "circle.obj");
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    EXPECT_EQ(mesh.faces.size(), expected_faces);
  }
  return best;
}

// Linear, not quadratic: 8 times the corners take well under 64 times as long (the bound, 24,
// leaves room for noise; tinyobjloader's triangulation took 2.8 s for 40,000 corners).
TEST(Polygon, ObjLoadTimeIsLinearInThePolygonsCorners) {
  for (const bool notch : {false, true}) {
    const double small = load_seconds(circle_obj(12'500, notch), 12'498);
    const double large = load_seconds(circle_obj(100'000, notch), 99'998);
    EXPECT_LT(large, 24 * std::max(small, 1e-3)) << (notch ? "notched" : "round") << " circle: " << small << " s for "
                                                  << "12,500 corners, " << large << " s for 100,000";
    EXPECT_LT(large, 5.0);
  }
}

TEST(Polygon, ObjFaceTooConcaveToSplitNamesItsLine) {
  std::ostringstream s;
  const int n = 20'000;  // half of them reflex: about 10,000 × 20,000 steps, over the limit of 5·10^7
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n, r = i % 2 ? 0.5 : 1.0;
    s << "v " << r * std::cos(a) << ' ' << r * std::sin(a) << " 0\n";
  }
  s << "# the face\nf";
  for (int i = 1; i <= n; ++i) s << ' ' << i;
  s << '\n';
  try {
    parse_obj(s.str(), "star.obj");
    FAIL() << "a face of 20,000 corners, 10,000 reflex, was split";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("star.obj:20002:1: a face of 20000 corners with too many reflex"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace strahl::polygon_test
