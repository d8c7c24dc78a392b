// CSG (geometry/csg.h) against closed forms and cross-checks: a ray through a box minus a sphere
// meets exactly the faces and chord the formulas give, with the sphere's normal flipped; the lens
// of two spheres; A − A is empty; A ∪ B's nearest hit is the nearer of the two; intersection(A, B)
// equals difference(A, inverse(B)) and inverse(inverse(A)) equals A ray for ray; inside() equals
// the operator applied to the operands' membership at random points; every crossing's side agrees
// with inside() between crossings; merge drops inner surfaces that union keeps; lists that
// overflow are evaluated again from where they stopped; an intersection's Skip, the leaves' boxes
// and the groups of operands under boxes change no crossing (chosen trees and random ones); and
// the scene file's errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "strahl/geometry/solid.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/scene_file.h"
#include "test_random.h"

namespace strahl::csg_test {
namespace {

using kernel::SolidCrossing;

const char* kHeader =
    "camera: {position: [0, 1, 6], look_at: [0, 0, 0], fov: 40}\n"
    "render: {width: 32, height: 24}\n"
    "lights:\n  - {type: point, position: [2, 3, 2]}\n"
    "objects:\n";

RenderScene scene_of(const std::string& objects) {
  return compile(parse_scene(std::string(kHeader) + objects, "csg.yaml", "."));
}

std::vector<SolidCrossing> crossings_of(const RenderScene& rs, std::size_t solid, const Ray& ray, Real t_min = 0,
                                        Real t_max = kInfinity) {
  std::vector<SolidCrossing> out;
  kernel::for_each_solid_crossing(rs.shapes(), rs.solids.at(solid), ray, t_min, t_max, [&](const SolidCrossing& c) {
    out.push_back(c);
    return false;
  });
  return out;
}

Vec3 normal_of(const RenderScene& rs, std::size_t solid, const Ray& ray, const SolidCrossing& c) {
  return kernel::normal_at(rs.shapes(), rs.solids.at(solid), int(c.part), ray.at(c.t));
}

constexpr const char* kBox = "{type: box, corners: [[-1, -1, -1], [1, 1, 1]]}";
constexpr const char* kBall = "{type: sphere, center: [0, 0, 0], radius: 1.2}";

TEST(Csg, BoxMinusSphereHitsWhereTheFormulasSay) {
  const RenderScene rs = scene_of(std::string("  - {type: difference, objects: [") + kBox + ", " + kBall + "]}\n");
  ASSERT_EQ(rs.solids.size(), 1u);
  ASSERT_EQ(rs.solids[0].kind, kernel::SolidKind::Csg);
  // Along x at height 0.8: the box face at x = −1 (outside the ball: 1 + 0.64 > 1.44), then the
  // ball's chord x = ±√(1.44 − 0.64) = ±√0.8 cut out, then the far face.
  const Ray ray(Vec3(-5, 0.8, 0), Vec3(1, 0, 0));
  const std::vector<SolidCrossing> c = crossings_of(rs, 0, ray);
  ASSERT_EQ(c.size(), 4u);
  const Real h = std::sqrt(Real(0.8));
  EXPECT_DOUBLE_EQ(c[0].t, 4);
  EXPECT_NEAR(c[1].t, 5 - h, 1e-14);
  EXPECT_NEAR(c[2].t, 5 + h, 1e-14);
  EXPECT_DOUBLE_EQ(c[3].t, 6);
  EXPECT_TRUE(c[0].entering);
  EXPECT_FALSE(c[1].entering);
  EXPECT_TRUE(c[2].entering);
  EXPECT_FALSE(c[3].entering);
  // Normals point out of the solid: the box's faces as they are, the ball's flipped (inwards to
  // its centre, which is outside the difference).
  EXPECT_EQ(normal_of(rs, 0, ray, c[0]), Vec3(-1, 0, 0));
  const Vec3 n1 = normal_of(rs, 0, ray, c[1]), n2 = normal_of(rs, 0, ray, c[2]);
  EXPECT_NEAR(n1.x, h / 1.2, 1e-14);
  EXPECT_NEAR(n1.y, -0.8 / 1.2, 1e-14);
  EXPECT_NEAR(n2.x, -h / 1.2, 1e-14);
  EXPECT_NEAR(n2.y, -0.8 / 1.2, 1e-14);
  EXPECT_EQ(normal_of(rs, 0, ray, c[3]), Vec3(1, 0, 0));
  // The renderer's view: the nearest hit and, from inside the solid, the ball's surface facing
  // the ray (a refracted ray leaves through the cut-out's wall, not through the box's far face).
  const SceneView v = rs.view();
  const Hit hit = closest_hit(v, ray, 0, kInfinity);
  EXPECT_DOUBLE_EQ(hit.t, 4);
  const Ray inner(Vec3(-0.95, 0.8, 0), Vec3(1, 0, 0));
  const Hit out = closest_hit(v, inner, 0, kInfinity);
  EXPECT_NEAR(out.t, 0.95 - h, 1e-14);
  const SurfacePoint sp = surface_at(v, inner, out);
  EXPECT_GT(dot(sp.geometric_normal, inner.direction), 0);  // leaving the solid: normal along the ray
  // Through the middle the ball removes everything; through the corners it removes nothing.
  EXPECT_TRUE(crossings_of(rs, 0, Ray(Vec3(-5, 0, 0), Vec3(1, 0, 0))).empty());
  const std::vector<SolidCrossing> corner = crossings_of(rs, 0, Ray(Vec3(-5, 0.95, 0.95), Vec3(1, 0, 0)));
  ASSERT_EQ(corner.size(), 2u);
  EXPECT_DOUBLE_EQ(corner[0].t, 4);
  EXPECT_DOUBLE_EQ(corner[1].t, 6);
  // A shadow ray through the transparent cut box crosses its four surfaces.
  EXPECT_EQ(kernel::crossings(rs.shapes(), rs.solids[0], ray, 0, 10), 4);
}

TEST(Csg, LensOfTwoSpheresHasTheAnalyticEntryAndExit) {
  // Unit spheres at x = ±0.5: the lens spans x in [−0.5, 0.5] on the axis; off the axis at
  // height y the entry is at x = 0.5 − √(1 − y²) (the right sphere's left side) and the exit
  // mirrored.
  const RenderScene rs = scene_of(
      "  - {type: intersection, objects: [{type: sphere, center: [-0.5, 0, 0], radius: 1}, "
      "{type: sphere, center: [0.5, 0, 0], radius: 1}]}\n");
  for (Real y : {0.0, 0.3, 0.6, 0.86}) {
    const Ray ray(Vec3(-3, y, 0), Vec3(1, 0, 0));
    const std::vector<SolidCrossing> c = crossings_of(rs, 0, ray);
    ASSERT_EQ(c.size(), 2u) << y;
    const Real x = 0.5 - std::sqrt(1 - y * y);
    EXPECT_NEAR(c[0].t, 3 + x, 1e-14) << y;
    EXPECT_NEAR(c[1].t, 3 - x, 1e-14) << y;
    // Entry on the right sphere, its normal pointing away from (0.5, 0, 0).
    const Vec3 n = normal_of(rs, 0, ray, c[0]);
    EXPECT_NEAR(n.x, (x - 0.5), 1e-14);
  }
  EXPECT_TRUE(crossings_of(rs, 0, Ray(Vec3(-3, 0.87, 0), Vec3(1, 0, 0))).empty());  // above √0.75
}

// Random rays through the unit-ish region: origins on a sphere of radius 4 towards random points
// near the middle, and some starting inside.
std::vector<Ray> random_rays(std::uint64_t seed, int n) {
  test::Random rng(seed);
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    const Vec3 o = i % 4 == 0 ? rng.point(-1.2, 1.2) : rng.direction() * 4;
    const Vec3 target = rng.point(-1, 1);
    rays.emplace_back(o, normalize(target - o));
  }
  return rays;
}

// The operands used below, as YAML: a box, a ball, a torus, a cylinder, a cone and an implicit
// sphere, overlapping one another around the origin.
// A solid alone as a CSG of one operand (a top-level sphere would not be a solid).
std::string solo(const std::string& a) { return "{type: union, objects: [" + a + "]}"; }

const std::vector<std::string> kOperands = {
    "{type: box, corners: [[-0.8, -0.6, -0.7], [0.6, 0.9, 0.5]]}",
    "{type: sphere, center: [0.3, 0.2, -0.1], radius: 0.9}",
    "{type: torus, center: [0, 0.1, 0], major_radius: 0.7, minor_radius: 0.3, axis: [0.3, 1, 0.2]}",
    "{type: cylinder, base: [-1, -0.2, 0], cap: [1, 0.3, 0.1], radius: 0.45}",
    "{type: cone, base: [0, -1, 0], base_radius: 0.8, cap: [0.1, 0.9, 0.2], cap_radius: 0.1}",
    "{type: implicit, expression: 'sqrt(x^2 + y^2 + z^2) - 0.75', contained_by: {type: sphere, center: [0, 0, 0], "
    "radius: 1}, method: distance, max_gradient: 1, accuracy: 2e-6}",
};

void expect_same_crossings(const std::vector<SolidCrossing>& a, const std::vector<SolidCrossing>& b, Real tol,
                           const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(a[k].t, b[k].t, tol) << what << " crossing " << k;
    EXPECT_EQ(a[k].entering, b[k].entering) << what << " crossing " << k;
  }
}

TEST(Csg, DifferenceOfIdenticalSolidsIsEmpty) {
  for (const std::string& a : kOperands) {
    const RenderScene rs = scene_of("  - {type: difference, objects: [" + a + ", " + a + "]}\n");
    for (const Ray& ray : random_rays(5, 2000)) ASSERT_TRUE(crossings_of(rs, 0, ray).empty()) << a;
    // … and A ∩ A = A ∪ A's outline = merge(A, A) = A.
    const RenderScene same = scene_of("  - {type: intersection, objects: [" + a + ", " + a + "]}\n  - " + solo(a) +
                                      "\n  - {type: merge, objects: [" + a + ", " + a + "]}\n");
    ASSERT_EQ(same.solids.size(), 3u) << a;
    for (const Ray& ray : random_rays(6, 500)) {
      const std::vector<SolidCrossing> one = crossings_of(same, 1, ray);
      expect_same_crossings(crossings_of(same, 0, ray), one, 0, "A ∩ A vs A: " + a);
      expect_same_crossings(crossings_of(same, 2, ray), one, 0, "merge(A, A) vs A: " + a);
    }
  }
}

TEST(Csg, UnionHitIsTheNearerOperand) {
  for (std::size_t i = 0; i < kOperands.size(); ++i) {
    const std::string& a = kOperands[i];
    const std::string& b = kOperands[(i + 1) % kOperands.size()];
    const RenderScene rs =
        scene_of("  - {type: union, objects: [" + a + ", " + b + "]}\n  - " + solo(a) + "\n  - " + solo(b) + "\n");
    int hits = 0;
    for (const Ray& ray : random_rays(7 + i, 3000)) {
      const SolidCrossing u = kernel::intersect(rs.shapes(), rs.solids[0], ray, 0, kInfinity);
      const SolidCrossing ha = kernel::intersect(rs.shapes(), rs.solids[1], ray, 0, kInfinity);
      const SolidCrossing hb = kernel::intersect(rs.shapes(), rs.solids[2], ray, 0, kInfinity);
      ASSERT_EQ(u.t, std::fmin(ha.t, hb.t)) << a << " ∪ " << b;
      hits += u.t < kInfinity;
      // Union keeps every surface: as many crossings as both operands have.
      ASSERT_EQ(kernel::crossings(rs.shapes(), rs.solids[0], ray, 0, kInfinity),
                kernel::crossings(rs.shapes(), rs.solids[1], ray, 0, kInfinity) +
                    kernel::crossings(rs.shapes(), rs.solids[2], ray, 0, kInfinity));
    }
    EXPECT_GT(hits, 1000);
  }
}

TEST(Csg, DeMorganCrossChecksRayForRay) {
  for (std::size_t i = 0; i < kOperands.size(); ++i) {
    const std::string& a = kOperands[i];
    const std::string& b = kOperands[(i + 2) % kOperands.size()];
    const RenderScene rs = scene_of("  - {type: intersection, objects: [" + a + ", " + b + "]}\n" +
                                    "  - {type: difference, objects: [" + a + ", {type: inverse, objects: [" + b +
                                    "]}]}\n" + "  - {type: inverse, objects: [{type: inverse, objects: [" + a +
                                    "]}]}\n  - " + solo(a) + "\n" +
                                    // A − B = inverse(inverse(A) ∪ B) as sets (merge: no inner surfaces)
                                    "  - {type: difference, objects: [" + a + ", " + b + "]}\n" +
                                    "  - {type: inverse, objects: [{type: merge, objects: [{type: inverse, objects: [" +
                                    a + "]}, " + b + "]}]}\n");
    // Inverses are unbounded and go after the bounded solids: A ∩ B, A − inverse(B), A, A − B,
    // inverse(inverse(A)), inverse(inverse(A) ∪ B).
    ASSERT_EQ(rs.bounded_solid_count, 4u);
    int crossings = 0;
    for (const Ray& ray : random_rays(11 + i, 2000)) {
      const std::vector<SolidCrossing> x = crossings_of(rs, 0, ray);
      crossings += int(x.size());
      expect_same_crossings(x, crossings_of(rs, 1, ray), 0, "A ∩ B vs A − inverse(B)");
      expect_same_crossings(crossings_of(rs, 4, ray), crossings_of(rs, 2, ray), 0, "inverse(inverse(A)) vs A");
      expect_same_crossings(crossings_of(rs, 3, ray), crossings_of(rs, 5, ray), 0, "A − B vs inverse(inverse(A) ∪ B)");
      // Normals agree too (the flip follows the inverse).
      const std::vector<SolidCrossing> y = crossings_of(rs, 1, ray);
      for (std::size_t k = 0; k < x.size() && k < y.size(); ++k)
        ASSERT_EQ(normal_of(rs, 0, ray, x[k]), normal_of(rs, 1, ray, y[k]));
    }
    EXPECT_GT(crossings, 200) << a << " ∩ " << b;
  }
}

// Two compilations of the same trees give the same crossings, bit for bit, over whole rays and
// pieces of them that may start inside an operand, and the same nearest hit: counts of crossings,
// of rays with none, and of pieces wholly inside a tree.
struct TreeComparison {
  int crossings = 0, empty = 0, inside_pieces = 0;
};
TreeComparison expect_same_trees(const RenderScene& with, const RenderScene& without, std::uint64_t seed,
                                 const std::vector<Ray>& extra_rays = {}) {
  test::Random rng(seed);
  TreeComparison n;
  for (std::size_t s = 0; s < with.solids.size(); ++s) {
    std::vector<Ray> rays = random_rays(seed + s, 3000);
    rays.insert(rays.end(), extra_rays.begin(), extra_rays.end());
    for (const Ray& ray : rays) {
      const Real t0 = rng.uniform(0, 6), t1 = rng.coin() ? kInfinity : t0 + rng.uniform(0, 0.5);
      for (const auto& [lo, hi] : {std::pair<Real, Real>(0, kInfinity), std::pair<Real, Real>(t0, t1)}) {
        const std::vector<SolidCrossing> x = crossings_of(with, s, ray, lo, hi), y = crossings_of(without, s, ray, lo, hi);
        EXPECT_EQ(x.size(), y.size()) << s;
        if (x.size() != y.size()) return n;
        for (std::size_t k = 0; k < x.size(); ++k) {
          EXPECT_EQ(x[k].t, y[k].t) << s;
          EXPECT_EQ(x[k].part, y[k].part) << s;
          EXPECT_EQ(x[k].entering, y[k].entering) << s;
        }
        EXPECT_EQ(kernel::intersect(with.shapes(), with.solids[s], ray, lo, hi).t,
                  kernel::intersect(without.shapes(), without.solids[s], ray, lo, hi).t);
        n.crossings += int(x.size());
        n.empty += x.empty();
        n.inside_pieces += x.empty() && kernel::inside(with.shapes(), with.solids[s], ray.at(lo));
      }
    }
  }
  return n;
}

// An intersection's Skip (geometry/csg_program.h) leaves out its other operand where the first
// is nowhere on the ray: the same trees run with and without the Skip instructions give the same
// crossings, bit for bit.
TEST(Csg, SkippingAnIntersectionsOtherOperandChangesNoCrossing) {
  const std::string a = kOperands[0], b = kOperands[1], c = kOperands[2], d = kOperands[3], e = kOperands[4],
                    f = kOperands[5];
  const std::string objects =
      "  - {type: difference, objects: [" + a + ", " + b + ", " + c + "]}\n" +
      "  - {type: intersection, objects: [" + b + ", {type: inverse, objects: [" + c + "]}, " + d + "]}\n" +
      "  - {type: difference, objects: [{type: merge, objects: [" + a + ", " + d + "]}, {type: intersection, objects: [" +
      b + ", " + c + "]}]}\n" + "  - {type: intersection, objects: [{type: union, objects: [" + e + ", " + a +
      "]}, {type: difference, objects: [" + f + ", " + c + "]}]}\n" +
      "  - {type: intersection, objects: [" + c + ", " + e + "]}\n" +
      "  - {type: intersection, objects: [{type: inverse, objects: [" + c + "]}, " + a + "]}\n";
  const RenderScene with = scene_of(objects);
  RenderScene without = scene_of(objects);
  // The programs without their Skip instructions.
  std::vector<kernel::CsgInstruction> code;
  int skips = 0;
  for (kernel::Csg& g : without.csgs) {
    const std::uint32_t first = std::uint32_t(code.size());
    for (std::uint32_t i = g.first_instruction; i < g.first_instruction + g.instruction_count; ++i) {
      if (without.csg_code[i].op == kernel::CsgOp::Skip) ++skips;
      else code.push_back(without.csg_code[i]);
    }
    g.first_instruction = first;
    g.instruction_count = std::uint32_t(code.size()) - first;
  }
  without.csg_code = code;
  ASSERT_EQ(with.solids.size(), 6u);
  EXPECT_EQ(skips, 2 + 2 + 2 + 2 + 1 + 1);
  const TreeComparison n = expect_same_trees(with, without, 31);
  EXPECT_GT(n.crossings, 10000);
  EXPECT_GT(n.empty, 1000);         // rays the shortcut can skip for
  EXPECT_GT(n.inside_pieces, 100);  // pieces wholly inside a tree
}

// The trees' programs without their boxes: every one (the leaves' and the groups') or only the
// groups' (entries past a tree's leaves). Returns how many were dropped.
enum class BoxesToDrop { All, Groups };
int drop_boxes(RenderScene& rs, BoxesToDrop which) {
  int dropped = 0;
  for (const kernel::Csg& g : rs.csgs) {
    for (std::uint32_t i = g.first_instruction; i < g.first_instruction + g.instruction_count; ++i) {
      kernel::CsgInstruction& in = rs.csg_code[i];
      if (in.op != kernel::CsgOp::Skip || in.box == kernel::kNoCsgBox) continue;
      if (which == BoxesToDrop::Groups && in.box < g.leaf_count) continue;
      in.box = kernel::kNoCsgBox;
      dropped += which == BoxesToDrop::Groups;
    }
    if (which == BoxesToDrop::All)
      for (std::uint32_t k = 0; k < g.leaf_count; ++k) {
        dropped += int(rs.csg_leaves[g.first_leaf + k].boxed);
        rs.csg_leaves[g.first_leaf + k].boxed = 0;
      }
  }
  return dropped;
}

// The boxes that the trees' Skips name past their leaves: groups of operands, node operands.
std::vector<Bounds> group_boxes_of(const RenderScene& rs) {
  std::vector<Bounds> boxes;
  for (const kernel::Csg& g : rs.csgs)
    for (std::uint32_t i = g.first_instruction; i < g.first_instruction + g.instruction_count; ++i) {
      const kernel::CsgInstruction& in = rs.csg_code[i];
      if (in.op == kernel::CsgOp::Skip && in.box != kernel::kNoCsgBox && in.box >= g.leaf_count)
        boxes.push_back(rs.csg_leaves[g.first_leaf + in.box].box);
    }
  return boxes;
}

// How often random rays miss the boxes (tests that compare trees with and without boxes say
// little unless that is often).
int missed_by_random_rays(const std::vector<Bounds>& boxes, std::uint64_t seed) {
  int missed = 0;
  for (const Ray& ray : random_rays(seed, 3000)) {
    const Vec3 inverse(1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z);
    for (const Bounds& box : boxes) missed += !hits(box, ray.origin, inverse, 0, kInfinity);
  }
  return missed;
}

// A leaf's box (CsgLeaf: cones, cylinders, tori, placed shapes) stands for its crossings where the
// ray's range misses it: the same trees with and without the boxes give the same crossings, bit
// for bit, also for rays along the axes (a direction component 0) and grazing the boxes' faces.
TEST(Csg, LeafBoxesChangeNoCrossing) {
  const std::string a = kOperands[0], b = kOperands[1], c = kOperands[2], d = kOperands[3], e = kOperands[4],
                    f = kOperands[5];
  // Small leaves among large ones, as in scenes/csg.yaml: most rays through a tree miss them.
  const std::string small_torus = "{type: torus, center: [0.2, 0.6, 0.1], major_radius: 0.15, minor_radius: 0.05}";
  const std::string small_cylinder = "{type: cylinder, base: [-0.2, -0.5, 0], cap: [-0.2, 0.5, 0], radius: 0.1}";
  const std::string turned_box = "{type: box, corners: [[-0.3, -0.1, -0.2], [0.3, 0.1, 0.2]], rotate: [20, 45, 0]}";
  const std::string egg = "{type: sphere, center: [0, 0, 0], radius: 0.3, scale: [1, 1.4, 1], translate: [0.3, -0.2, 0.1]}";
  const std::string objects =
      "  - {type: difference, objects: [" + a + ", " + small_torus + ", " + small_cylinder + ", " + turned_box + "]}\n" +
      "  - {type: intersection, objects: [" + b + ", {type: inverse, objects: [" + c + "]}, " + d + "]}\n" +
      "  - {type: union, objects: [" + e + ", " + small_torus + ", " + f + "]}\n" +
      "  - {type: merge, objects: [" + small_cylinder + ", " + turned_box + ", " + egg + "]}\n" +
      "  - {type: difference, objects: [" + b + ", " + egg + ", " + small_cylinder + "], rotate: [0, 30, 10]}\n" +
      "  - {type: intersection, objects: [" + b + ", " + small_cylinder + "]}\n";
  const RenderScene with = scene_of(objects);
  RenderScene without = scene_of(objects);
  const int boxed = drop_boxes(without, BoxesToDrop::All);
  ASSERT_EQ(with.solids.size(), 6u);
  EXPECT_GE(boxed, 11);
  // Rays along each axis, and rays in the planes of the small leaves' boxes' faces.
  std::vector<Ray> extra;
  test::Random rng(9);
  for (int i = 0; i < 600; ++i) {
    const Vec3 o = rng.point(-1.2, 1.2);
    const Vec3 axis = i % 3 == 0 ? Vec3(1, 0, 0) : i % 3 == 1 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    extra.emplace_back(o - axis * 3, axis);
    for (const kernel::CsgLeaf& leaf : with.csg_leaves)
      if (leaf.boxed && i % 20 == 0) {
        const Vec3 on_face(leaf.box.hi.x, o.y, o.z);
        extra.emplace_back(on_face - Vec3(0, 0, 3), Vec3(0, 0, 1));
        extra.emplace_back(on_face - Vec3(0, 3, 0), normalize(Vec3(0, 1, 0.3)));
      }
  }
  const TreeComparison n = expect_same_trees(with, without, 57, extra);
  EXPECT_GT(n.crossings, 10000);
  EXPECT_GT(n.inside_pieces, 100);
  std::vector<Bounds> boxes;
  for (const kernel::CsgLeaf& leaf : with.csg_leaves)
    if (leaf.boxed) boxes.push_back(leaf.box);
  EXPECT_GT(missed_by_random_rays(boxes, 5), 5000);
}

// Groups of many small operands (geometry/csg_program.h): a Skip whose box holds several steps'
// operands stands for all of them where the ray's range misses it. The same trees with and without
// the groups' boxes (and the nodes' own) give the same crossings, bit for bit: differences,
// unions, merges and intersections of spheres, boxes, cylinders, cones, tori and nodes of them,
// placed and not, runs of them broken by an operand that cannot join a group; rays along the axes
// (through the holes' axes) and in the planes of the groups' boxes' faces.
TEST(Csg, OperandGroupsChangeNoCrossing) {
  auto num = [](Real v) { return std::to_string(v); };
  // A plate with a 6×6 grid of holes: cylinders, every fifth a sphere or a box, one a torus. The
  // plate is a box united with itself: its list has coincident crossings (it is not simple), which
  // a difference folds into one where it runs.
  const std::string slab = "{type: box, corners: [[-1, -0.15, -1], [1, 0.15, 1]]}";
  std::string plate = "{type: difference, objects: [{type: union, objects: [" + slab + ", " + slab + "]}";
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const Real x = -0.85 + 0.34 * i, z = -0.85 + 0.34 * j;
      const int k = 6 * i + j;
      if (k == 17) plate += ", {type: torus, center: [" + num(x) + ", 0.15, " + num(z) + "], major_radius: 0.1, minor_radius: 0.04}";
      else if (k % 5 == 1) plate += ", {type: sphere, center: [" + num(x) + ", 0.1, " + num(z) + "], radius: 0.12}";
      else if (k % 5 == 3)
        plate += ", {type: box, corners: [[" + num(x - 0.1) + ", -0.2, " + num(z - 0.1) + "], [" + num(x + 0.1) + ", 0.2, " +
                 num(z + 0.1) + "]]}";
      else
        plate += ", {type: cylinder, base: [" + num(x) + ", -0.3, " + num(z) + "], cap: [" + num(x) + ", 0.3, " + num(z) +
                 "], radius: 0.1}";
    }
  // A ring of small spheres and tori (a union's steps), and overlapping boxes (a merge's).
  std::string ring = "{type: union, objects: [{type: sphere, center: [0, 0, 0], radius: 0.3}";
  std::string stack = "{type: merge, objects: [{type: box, corners: [[-0.9, -0.9, -0.2], [-0.6, -0.6, 0.2]]}";
  for (int k = 0; k < 14; ++k) {
    const Real a = 0.45 * k, x = 0.8 * std::cos(a), y = 0.8 * std::sin(a);
    ring += k % 4 == 3 ? ", {type: torus, center: [" + num(x) + ", " + num(y) + ", 0], major_radius: 0.1, minor_radius: 0.04}"
                       : ", {type: sphere, center: [" + num(x) + ", " + num(y) + ", 0.05], radius: 0.14}";
    stack += ", {type: box, corners: [[" + num(-0.9 + 0.12 * k) + ", " + num(-0.9 + 0.1 * k) + ", -0.2], [" +
             num(-0.6 + 0.12 * k) + ", " + num(-0.6 + 0.1 * k) + ", 0.2]]}";
  }
  // A ball cut by a cluster of small spheres (an intersection's steps: where the ray misses them,
  // the ball's list becomes empty), and a placed difference whose run of holes an implicit operand
  // (no group) breaks in two.
  std::string cut = "{type: intersection, objects: [" + std::string(kBall);
  for (int k = 0; k < 5; ++k)
    cut += ", {type: sphere, center: [" + num(0.3 + 0.05 * k) + ", " + num(0.2 - 0.04 * k) + ", 0], radius: 0.4}";
  cut += "]}";
  std::string placed = "{type: difference, rotate: [10, 30, 0], translate: [0.1, 0, 0], objects: [" + std::string(kBox);
  for (int k = 0; k < 12; ++k) {
    if (k == 6) placed += ", " + kOperands[5];
    placed += ", {type: cylinder, base: [" + num(-0.8 + 0.14 * k) + ", -2, 0.3], cap: [" + num(-0.8 + 0.14 * k) +
              ", 2, 0.3], radius: 0.05}";
  }
  // A bar with countersunk holes (each a node: a cylinder and a cone), one a sphere minus a box,
  // one holding an implicit surface and an inverse box that trims the bar's ends (no box: inside
  // everywhere outside the box; both break the run).
  std::string sunk = "{type: difference, objects: [{type: box, corners: [[-1, -0.1, -0.2], [1, 0.1, 0.2]]}";
  for (int k = 0; k < 10; ++k) {
    const std::string x = num(-0.9 + 0.2 * k);
    if (k == 3) sunk += ", {type: difference, objects: [{type: sphere, center: [" + x + ", 0.1, 0], radius: 0.08}, {type: box, corners: [[-2, 0.12, -2], [2, 2, 2]]}]}";
    else if (k == 9) sunk += ", {type: inverse, objects: [{type: box, corners: [[-0.95, -0.3, -0.3], [0.95, 0.3, 0.3]]}]}";
    else if (k == 7) sunk += ", {type: intersection, objects: [" + kOperands[5] + ", {type: box, corners: [[" + x + ", -2, -0.05], [" + num(-0.8 + 0.2 * k) + ", 2, 0.05]]}]}";
    else
      sunk += ", {type: union, objects: [{type: cylinder, base: [" + x + ", -0.2, 0], cap: [" + x + ", 0.2, 0], radius: 0.04}, "
              "{type: cone, base: [" + x + ", 0.02, 0], base_radius: 0.04, cap: [" + x + ", 0.11, 0], cap_radius: 0.08}]}";
  }
  const std::string objects = "  - " + plate + "]}\n  - " + ring + "]}\n  - " + stack + "]}\n  - " + cut + "\n  - " +
                              placed + "]}\n  - " + sunk + "]}\n";
  const RenderScene with = scene_of(objects);
  RenderScene without = scene_of(objects);
  const int groups = drop_boxes(without, BoxesToDrop::Groups);
  ASSERT_EQ(with.solids.size(), 6u);
  EXPECT_GE(groups, 12 + 4 + 4 + 1 + 2 + 8 + 1);  // 36, 14, 14, 5 and 2 × 6 steps; 8 nodes, 7 steps
  // Rays along each axis (through the holes' axes, along the plate's faces), and rays in the
  // planes of the groups' boxes' faces.
  std::vector<Ray> extra;
  test::Random rng(13);
  for (int i = 0; i < 36; ++i) {
    const Vec3 hole(-0.85 + 0.34 * (i / 6), 0, -0.85 + 0.34 * (i % 6));
    extra.emplace_back(hole - Vec3(0, 3, 0), Vec3(0, 1, 0));
    extra.emplace_back(hole + Vec3(0.1, 3, 0), Vec3(0, -1, 0));
  }
  for (int i = 0; i < 900; ++i) {
    const Vec3 o = rng.point(-1.2, 1.2);
    const Vec3 axis = i % 3 == 0 ? Vec3(1, 0, 0) : i % 3 == 1 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    extra.emplace_back(o - axis * 3, axis);
    if (i % 10 == 0)
      for (const Bounds& box : group_boxes_of(with)) {
        extra.emplace_back(Vec3(o.x, box.hi.y, o.z) - Vec3(3, 0, 0), Vec3(1, 0, 0));
        extra.emplace_back(Vec3(box.lo.x, o.y, o.z) - Vec3(0, 0, 3), normalize(Vec3(0, 0.2, 1)));
      }
  }
  const TreeComparison n = expect_same_trees(with, without, 71, extra);
  EXPECT_GT(n.crossings, 20000);
  EXPECT_GT(n.inside_pieces, 100);
  EXPECT_GT(missed_by_random_rays(group_boxes_of(with), 7), 20000);
}

// Random trees — every operation, inverses, nodes within nodes, transforms, small and large
// operands of every kind — with every box (the leaves', the groups', the nodes') and without any:
// the same crossings, bit for bit.
std::string random_operand(test::Random& rng, int depth) {
  auto num = [](Real v) { return std::to_string(v); };
  auto vec = [&](const Vec3& p) { return "[" + num(p.x) + ", " + num(p.y) + ", " + num(p.z) + "]"; };
  const Vec3 c = rng.point(-0.8, 0.8);
  const Real r = rng.coin() ? rng.uniform(0.03, 0.15) : rng.uniform(0.15, 0.7);
  const std::string turn = rng.below(5) == 0 ? ", rotate: " + vec(rng.point(-90, 90)) : "";
  const int kind = rng.below(depth < 3 ? 8 : 6);
  switch (kind) {
    case 0: return "{type: sphere, center: " + vec(c) + ", radius: " + num(r) + turn + "}";
    case 1: return "{type: box, corners: [" + vec(c - rng.point(0.2, 1) * r) + ", " + vec(c + rng.point(0.2, 1) * r) + "]" + turn + "}";
    case 2: return "{type: cylinder, base: " + vec(c) + ", cap: " + vec(c + rng.direction() * (3 * r)) + ", radius: " + num(r / 2) + "}";
    case 3:
      return "{type: cone, base: " + vec(c) + ", base_radius: " + num(r / 2) + ", cap: " + vec(c + rng.direction() * (2 * r)) +
             ", cap_radius: " + num(r / 5) + "}";
    case 4:
      return "{type: torus, center: " + vec(c) + ", major_radius: " + num(r) + ", minor_radius: " + num(r / 3) +
             ", axis: " + vec(rng.direction()) + "}";
    case 5:
      return "{type: implicit, expression: 'sqrt(x^2 + y^2 + z^2) - " + num(r) + "', contained_by: {type: sphere, center: [0, 0, 0], radius: " +
             num(1.2 * r) + "}, method: distance, max_gradient: 1, accuracy: 2e-6, translate: " + vec(c) + "}";
    default: {
      const char* ops[] = {"union", "intersection", "difference", "merge", "inverse"};
      const int op = rng.below(10) == 0 ? 4 : rng.below(4);
      const int n = op == 4 ? 1 : 2 + rng.below(depth == 1 ? 9 : 4);
      std::string node = std::string("{type: ") + ops[op] + turn + ", objects: [";
      for (int k = 0; k < n; ++k) node += (k ? ", " : "") + random_operand(rng, depth + 1);
      return node + "]}";
    }
  }
}

TEST(Csg, RandomTreesGiveTheSameCrossingsWithAndWithoutBoxes) {
  test::Random rng(2026);
  std::string objects;
  for (int tree = 0; tree < 32; ++tree) {
    std::string node = random_operand(rng, 1);
    if (node.rfind("{type: union", 0) != 0 && node.rfind("{type: intersection", 0) != 0 &&
        node.rfind("{type: difference", 0) != 0 && node.rfind("{type: merge", 0) != 0)
      node = "{type: difference, objects: [" + std::string(kBox) + ", " + node + "]}";  // a leaf: as an operand
    objects += "  - " + node + "\n";
  }
  const RenderScene with = scene_of(objects);
  RenderScene without = scene_of(objects);
  const int dropped = drop_boxes(without, BoxesToDrop::All);
  const std::size_t groups = group_boxes_of(with).size();
  ASSERT_GE(with.solids.size(), 24u);
  EXPECT_GT(dropped, 20);
  EXPECT_GT(groups, 10u);
  const TreeComparison n = expect_same_trees(with, without, 83);
  EXPECT_GT(n.crossings, 20000);
  EXPECT_GT(n.inside_pieces, 100);
}

// csg_shortcut's answers (a combination with an operand without crossings, taken without
// running csg_combine) are csg_combine's results, bit for bit: random lists, simple and not
// (coincident crossings, sides repeated), complete or cut short, against plain operands inside and
// outside, complete or cut short, on either side, for every operation.
kernel::CsgList random_list(test::Random& rng, bool plain) {
  kernel::CsgList l;
  l.start_inside = rng.coin();
  l.valid_until = rng.below(4) == 0 ? rng.uniform(0, 10) : kInfinity;
  if (plain) return l;
  const bool simple = rng.coin();
  bool side = l.start_inside;
  Real t = rng.uniform(-1, 1);
  for (int k = 0, n = rng.below(kernel::kMaxCsgCrossings + 1); k < n; ++k) {
    if (simple || rng.below(3) != 0) t += rng.uniform(0, 1);  // else a crossing at the same t as the last
    const bool entering = simple || rng.coin() ? !side : side;
    if (!l.add(t, std::uint32_t(rng.below(1 << 20)), entering)) break;
    side = entering;
  }
  return l;
}

void expect_same_list(const kernel::CsgList& a, const kernel::CsgList& b, const std::string& what) {
  ASSERT_EQ(a.n, b.n) << what;
  ASSERT_EQ(a.start_inside, b.start_inside) << what;
  ASSERT_EQ(std::memcmp(&a.valid_until, &b.valid_until, sizeof(Real)), 0) << what;
  for (int k = 0; k < a.n; ++k) {
    ASSERT_EQ(a.c[k].t, b.c[k].t) << what << " " << k;
    ASSERT_EQ(a.c[k].part, b.c[k].part) << what << " " << k;
    ASSERT_EQ(a.c[k].entering, b.c[k].entering) << what << " " << k;
  }
}

TEST(Csg, ShortcutsAreTheCombinationsResults) {
  test::Random rng(71);
  int taken[4] = {0, 0, 0, 0};
  for (int i = 0; i < 200000; ++i) {
    const int plain = rng.below(3);  // 0: a, 1: b, 2: both
    const kernel::CsgList a = random_list(rng, plain != 1), b = random_list(rng, plain != 0);
    const kernel::CsgOp op = std::array{kernel::CsgOp::Union, kernel::CsgOp::Intersection, kernel::CsgOp::Merge}[std::size_t(rng.below(3))];
    const kernel::CsgShortcut cut = kernel::csg_shortcut(op, a, b);
    ++taken[int(cut)];
    if (cut == kernel::CsgShortcut::None) continue;
    kernel::CsgList combined;
    kernel::csg_combine(op, a, b, combined);
    kernel::CsgList shortcut = cut == kernel::CsgShortcut::Second ? b : a;
    if (cut == kernel::CsgShortcut::Empty) {  // as csg_evaluate writes it
      shortcut.start_inside = b.n == 0 ? b.start_inside : a.start_inside;
      shortcut.n = 0;
      shortcut.valid_until = std::min(a.valid_until, b.valid_until);
    }
    expect_same_list(shortcut, combined, "op " + std::to_string(int(op)) + ", shortcut " + std::to_string(int(cut)));
    if (HasFatalFailure()) return;
  }
  for (const int n : taken) EXPECT_GT(n, 5000);  // every answer, None too, many times
}

TEST(Csg, InsideIsTheOperatorOverTheOperands) {
  test::Random rng(3);
  const std::string a = kOperands[0], b = kOperands[1], c = kOperands[2];
  const RenderScene rs = scene_of("  - " + solo(a) + "\n  - " + solo(b) + "\n  - " + solo(c) + "\n" +
                                  "  - {type: union, objects: [" + a + ", " + b + ", " + c + "]}\n" +
                                  "  - {type: intersection, objects: [" + a + ", " + b + ", " + c + "]}\n" +
                                  "  - {type: difference, objects: [" + a + ", " + b + ", " + c + "]}\n" +
                                  "  - {type: merge, objects: [" + a + ", " + b + ", " + c + "]}\n" +
                                  "  - {type: inverse, objects: [" + a + "]}\n" +
                                  "  - {type: difference, objects: [{type: union, objects: [" + a + ", " + c +
                                  "]}, {type: intersection, objects: [" + b + ", " + c + "]}]}\n");
  // The inverse is unbounded: it comes last; the others keep their order.
  ASSERT_EQ(rs.solids.size(), 9u);
  EXPECT_EQ(rs.bounded_solid_count, 8u);
  const std::size_t leaf[3] = {0, 1, 2}, U = 3, I = 4, D = 5, M = 6, X = 7, N = 8;
  int in = 0;
  for (int i = 0; i < 100000; ++i) {
    const Vec3 p = rng.point(-1.3, 1.3);
    const auto at = [&](std::size_t s) { return kernel::inside(rs.shapes(), rs.solids[s], p); };
    const bool ia = at(leaf[0]), ib = at(leaf[1]), ic = at(leaf[2]);
    ASSERT_EQ(at(U), ia || ib || ic);
    ASSERT_EQ(at(I), ia && ib && ic);
    ASSERT_EQ(at(D), ia && !ib && !ic);
    ASSERT_EQ(at(M), ia || ib || ic);
    ASSERT_EQ(at(N), !ia);
    ASSERT_EQ(at(X), (ia || ic) && !(ib && ic));
    in += at(D);
  }
  EXPECT_GT(in, 1000);
}

// Between consecutive crossings, the side the crossing list says equals inside() at the midpoint.
TEST(Csg, CrossingSidesAgreeWithInside) {
  const std::string a = kOperands[0], b = kOperands[1], c = kOperands[2], d = kOperands[3];
  const RenderScene rs = scene_of(
      "  - {type: difference, objects: [{type: merge, objects: [" + a + ", " + d + "]}, {type: intersection, objects: [" +
      b + ", " + c + "]}]}\n  - {type: intersection, objects: [" + b + ", {type: inverse, objects: [" + c + "]}, " + d +
      "]}\n");
  for (std::size_t s = 0; s < 2; ++s) {
    int checked = 0;
    for (const Ray& ray : random_rays(21 + s, 3000)) {
      const std::vector<SolidCrossing> x = crossings_of(rs, s, ray);
      for (std::size_t k = 0; k + 1 < x.size(); ++k) {
        if (x[k + 1].t - x[k].t < 1e-6) continue;
        ASSERT_EQ(x[k].entering, kernel::inside(rs.shapes(), rs.solids[s], ray.at((x[k].t + x[k + 1].t) / 2)));
        ++checked;
      }
      if (!x.empty()) {
        ASSERT_NE(x.front().entering, kernel::inside(rs.shapes(), rs.solids[s], ray.at(x.front().t * 0.5)));
        ASSERT_FALSE(x.back().entering);  // bounded: the ray ends outside
      }
    }
    EXPECT_GT(checked, 500);
  }
}

TEST(Csg, MergeDropsTheInnerSurfacesUnionKeeps) {
  const std::string two = "[{type: sphere, center: [-0.5, 0, 0], radius: 1}, {type: sphere, center: [0.5, 0, 0], radius: 1}]";
  const RenderScene rs = scene_of("  - {type: union, objects: " + two + "}\n  - {type: merge, objects: " + two + "}\n");
  const Ray ray(Vec3(-3, 0, 0), Vec3(1, 0, 0));
  const std::vector<SolidCrossing> u = crossings_of(rs, 0, ray), m = crossings_of(rs, 1, ray);
  ASSERT_EQ(u.size(), 4u);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_DOUBLE_EQ(m[0].t, 1.5);
  EXPECT_DOUBLE_EQ(m[1].t, 4.5);
  EXPECT_DOUBLE_EQ(u[1].t, 2.5);  // the right sphere's near side, inside the left one
  EXPECT_DOUBLE_EQ(u[2].t, 3.5);
  // Two boxes sharing a face merge without a surface there.
  const RenderScene boxes = scene_of(
      "  - {type: merge, objects: [{type: box, corners: [[-1, -1, -1], [0, 1, 1]]}, {type: box, corners: [[0, -1, -1], "
      "[1, 1, 1]]}]}\n");
  EXPECT_EQ(crossings_of(boxes, 0, Ray(Vec3(-3, 0.1, 0.2), Vec3(1, 0, 0))).size(), 2u);
}

// More crossings than one list holds (kernel::kMaxCsgCrossings): the tree is evaluated again
// from where its lists stopped, and every crossing is found, in order.
TEST(Csg, LongListsAreEvaluatedInRounds) {
  std::string beads;
  const int n = 3 * kernel::kMaxCsgCrossings;
  for (int i = 0; i < n; ++i)
    beads += std::string(i ? ", " : "") + "{type: sphere, center: [" + std::to_string(i) + ", 0, 0], radius: 0.25}";
  const RenderScene rs = scene_of("  - {type: union, objects: [" + beads + "]}\n" +
                                  "  - {type: intersection, objects: [{type: union, objects: [" + beads +
                                  "]}, {type: box, corners: [[-1, -1, -1], [" + std::to_string(n) + ", 0.1, 1]]}]}\n");
  const Ray ray(Vec3(-5, 0, 0), Vec3(1, 0, 0));
  for (std::size_t s = 0; s < 2; ++s) {
    const std::vector<SolidCrossing> c = crossings_of(rs, s, ray);
    ASSERT_EQ(int(c.size()), 2 * n) << s;
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(c[2 * i].t, 5 + i - 0.25, 1e-12);
      EXPECT_NEAR(c[2 * i + 1].t, 5 + i + 0.25, 1e-12);
    }
  }
  // From inside the 40th bead: its far side first.
  const Ray inner(Vec3(40.1, 0, 0), Vec3(1, 0, 0));
  EXPECT_NEAR(kernel::intersect(rs.shapes(), rs.solids[0], inner, 0, kInfinity).t, 0.15, 1e-12);
}

TEST(Csg, AcceleratorsAgreeOnCsgScenes) {
  std::string objects;
  for (int i = 0; i < 4; ++i) {
    const std::string off = "[" + std::to_string(i * 2.5 - 4) + ", 0, 0]";
    objects += "  - {type: difference, objects: [{type: box, corners: [[" + std::to_string(i * 2.5 - 5) +
               ", -1, -1], [" + std::to_string(i * 2.5 - 3) + ", 1, 1]]}, {type: sphere, center: " + off +
               ", radius: 1.25}]}\n";
  }
  objects += "  - {type: merge, objects: [" + kOperands[1] + ", " + kOperands[2] + ", " + kOperands[3] + "]}\n";
  objects += "  - {type: sphere, center: [0, 2, 0], radius: 0.5}\n";
  const std::string scene = std::string(kHeader) + objects;
  std::vector<Hit> want;
  const std::vector<Ray> rays = random_rays(31, 4000);
  for (const char* accel : {"naive", "bvh", "kdtree", "octree"}) {
    Scene sc = parse_scene(scene, "accel.yaml", ".");
    sc.settings.accel = accel_from_name(accel).value();
    const RenderScene rs = compile(sc);
    const SceneView v = rs.view();
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Ray r(rays[i].origin * 2, rays[i].direction);
      const Hit h = closest_hit(v, r, 0, kInfinity);
      if (want.size() < rays.size()) {
        want.push_back(h);
        continue;
      }
      ASSERT_EQ(h.t, want[i].t) << accel << " ray " << i;
      ASSERT_EQ(h.index, want[i].index) << accel << " ray " << i;
      ASSERT_EQ(h.b1, want[i].b1) << accel << " ray " << i;
    }
  }
}

std::string error_of(const std::string& objects) {
  try {
    scene_of(objects);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Csg, BadInputNamesTheNode) {
  EXPECT_EQ(error_of("  - {type: union, objects: []}\n"), "csg.yaml:6:28: empty union: it needs at least one object");
  EXPECT_EQ(error_of("  - {type: merge}\n"), "csg.yaml:6:5: merge needs 'objects' (the solids it combines)");
  EXPECT_NE(error_of("  - {type: inverse, objects: [" + std::string(kBox) + ", " + kBall + "]}\n")
                .find("csg.yaml:6:30: inverse takes exactly one object (got 2)"),
            std::string::npos);
  EXPECT_NE(error_of("  - {type: union, objects: [{type: disk, center: [0, 0, 0], normal: [0, 1, 0], radius: 1}]}\n")
                .find("csg.yaml:6:36: 'disk' cannot be an object of union"),
            std::string::npos);
  EXPECT_NE(error_of("  - {type: union, objects: [{type: cylinder, base: [0, 0, 0], cap: [0, 1, 0], radius: 1, open: "
                     "true}]}\n")
                .find("csg.yaml:6:29: an open cylinder or cone has no inside"),
            std::string::npos);
  EXPECT_NE(error_of("  - {type: union, objects: [{type: box, corners: [[0, 0, 0], [1, 1, 1]], material: {color: [1, 0, "
                     "0]}}]}\n")
                .find("csg.yaml:6:84: an object of a CSG takes the CSG's material"),
            std::string::npos);
  // Nested eight deep: refused at the eighth node.
  std::string deep = std::string(kBox);
  for (int i = 0; i < 8; ++i) deep = "{type: union, objects: [" + deep + "]}";
  EXPECT_EQ(error_of("  - " + deep + "\n"),
            "csg.yaml:6:173: union is nested too deeply: CSG nodes may be nested at most 7 levels deep");
  std::string ok = std::string(kBox);
  for (int i = 0; i < 7; ++i) ok = "{type: union, objects: [" + ok + "]}";
  EXPECT_EQ(error_of("  - " + ok + "\n"), "(no error)");
  // Operands are checked as at the top level.
  EXPECT_NE(error_of("  - {type: union, objects: [{type: sphere, center: [0, 0, 0], radius: -1}]}\n")
                .find("csg.yaml:6:71: sphere radius must be positive"),
            std::string::npos);
}

TEST(Csg, DisjointIntersectionWarnsAndRendersNothing) {
  const RenderScene rs = scene_of(
      "  - {type: intersection, objects: [{type: sphere, center: [-3, 0, 0], radius: 1}, {type: sphere, center: [3, "
      "0, 0], radius: 1}]}\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n");
  EXPECT_TRUE(rs.solids.empty());
  ASSERT_FALSE(rs.warnings.empty());
  EXPECT_NE(rs.warnings.back().find("csg.yaml:6:5: intersection is empty"), std::string::npos);
}

}  // namespace
}  // namespace strahl::csg_test
