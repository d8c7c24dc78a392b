// The moving shapes' BVH per time segment (accel/motion_bvh.h): a ray at any time finds the same
// nearest moving shape through the trees of 1, 2, …, 16 segments as by testing every shape where
// it is at that time; segment_at picks a segment whose interval holds the time; the build cuts
// the shutter where shapes turn (the motion-blur scene's torus) and not where they barely move.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene_file.h"

namespace strahl::motion_bvh_test {
namespace {

TEST(MotionBvh, SegmentAtHoldsTheTime) {
  MotionBvh bvh;
  bvh.trees.nodes.resize(1);
  bvh.trees.prims.resize(1);
  for (std::uint32_t segments = 1; segments <= kMaxMotionSegments; segments *= 2) {
    bvh.segments = segments;
    for (std::uint32_t k = 0; k < segments; ++k) bvh.first_node[k] = 100 + k;
    const MotionBvhView v = bvh.view();
    const auto segment = [&](Real u) { return std::uint32_t(v.segment_at(u).nodes - v.trees.nodes) - 100; };
    std::mt19937_64 rng(segments);
    std::uniform_real_distribution<Real> uniform(0, 1);
    for (int i = 0; i < 10000; ++i) {
      const Real u = i < 2 ? Real(i) : uniform(rng);
      const std::uint32_t k = segment(u);
      ASSERT_LT(k, segments);
      EXPECT_LE(Real(k) / Real(segments), u);
      EXPECT_LE(u, Real(k + 1) / Real(segments));
    }
    for (std::uint32_t k = 0; k < segments; ++k) EXPECT_EQ(segment(Real(k) / Real(segments)), k);
    EXPECT_EQ(segment(1), segments - 1);
    EXPECT_EQ(segment(std::nan("")), 0u);  // never out of range
  }
  EXPECT_EQ(MotionBvh{}.view().segment_at(0.5).nodes, nullptr);  // nothing moves: no tree
}

// Spheres that travel and grow, triangles that turn about the origin by up to 90° (their
// vertices moving on chords), a few that stand still.
struct MovingScene {
  std::vector<kernel::MovingSphere> spheres;
  std::vector<kernel::MovingTriangle> triangles;
  MotionBvh bvh;

  explicit MovingScene(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<Real> uniform(-1, 1);
    const auto point = [&] { return Vec3(uniform(rng), uniform(rng), uniform(rng)); };
    for (int i = 0; i < 40; ++i) {
      kernel::MovingSphere s;
      s.center0 = point() * 3;
      s.center1 = i % 4 == 0 ? s.center0 : s.center0 + point() * 2;
      s.radius0 = 0.05 + 0.2 * (uniform(rng) + 1);
      s.radius1 = i % 3 == 0 ? s.radius0 : 0.05 + 0.2 * (uniform(rng) + 1);
      spheres.push_back(s);
    }
    for (int i = 0; i < 300; ++i) {
      kernel::MovingTriangle t;
      const Vec3 centre = point() * 3, e1 = point() * 0.4, e2 = point() * 0.4;
      const Real angle = i % 5 == 0 ? 0 : (uniform(rng) + 1) * kPi / 4, c = std::cos(angle), s = std::sin(angle);
      const Vec3 p[3] = {centre, centre + e1, centre + e2};
      for (int k = 0; k < 3; ++k) {
        t.p0[k] = p[k];
        t.p1[k] = Vec3(c * p[k].x - s * p[k].y, s * p[k].x + c * p[k].y, p[k].z);  // turned about z
      }
      triangles.push_back(t);
    }
  }

  void build(std::uint32_t segments) { bvh = build_motion_bvh(spheres, triangles, {}, {}, segments); }

  SceneView view() const {
    SceneView v;
    v.moving_spheres = spheres.data();
    v.moving_sphere_count = static_cast<std::uint32_t>(spheres.size());
    v.moving_triangles = triangles.data();
    v.moving_triangle_count = static_cast<std::uint32_t>(triangles.size());
    v.moving_bvh = bvh.view();
    v.shutter_open = 0;
    v.inv_shutter = 1;
    return v;
  }

  // Every shape tested where it is at the ray's time: the nearest t, and the shapes there.
  Real nearest(const Ray& ray) const {
    Real best = kInfinity;
    for (const kernel::MovingSphere& s : spheres)
      best = std::fmin(best, kernel::intersect(kernel::at_time(s, ray.time), ray, 0, best));
    for (const kernel::MovingTriangle& t : triangles)
      best = std::fmin(best, kernel::intersect(kernel::at_time(t, ray.time), ray, 0, best).t);
    return best;
  }
};

TEST(MotionBvh, SegmentTreesFindTheNearestShapeAtEveryTime) {
  MovingScene scene(7);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> uniform(-1, 1), time(0, 1);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin(uniform(rng) * 6, uniform(rng) * 6, 8);
    const Vec3 target(uniform(rng) * 3, uniform(rng) * 3, uniform(rng) * 3);
    // Times on the segments' ends too (exactly k/16), where a ray picks one of two trees.
    rays.push_back({origin, normalize(target - origin), i % 4 == 0 ? Real(i % 17) / 16 : time(rng)});
  }
  std::vector<Real> expected;
  int hits = 0;
  for (const Ray& ray : rays) {
    expected.push_back(scene.nearest(ray));
    hits += expected.back() < kInfinity;
  }
  EXPECT_GT(hits, 5000);  // the rays meet the shapes often enough to test something
  for (std::uint32_t segments : {1u, 2u, 4u, 8u, 16u, 0u}) {
    scene.build(segments);
    ASSERT_EQ(scene.bvh.segments, segments == 0 ? scene.bvh.segments : segments);
    const SceneView v = scene.view();
    int wrong = 0, wrong_shadow = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      Hit hit;
      closest_moving_hit(v, rays[i], 0, hit);
      wrong += hit.t != expected[i];
      // A shadow ray to just past the nearest shape is blocked, one to just short of it is not.
      if (expected[i] < kInfinity) {
        int crossed_far = 0, crossed_near = 0;
        auto count_far = [&](std::uint32_t, int) { return ++crossed_far, true; };
        auto count_near = [&](std::uint32_t, int) { return ++crossed_near, true; };
        for_each_moving_crossing(v, rays[i], expected[i] * (1 + 1e-9), count_far);
        for_each_moving_crossing(v, rays[i], expected[i] * (1 - 1e-9), count_near);
        wrong_shadow += crossed_far != 1 || crossed_near != 0;
      }
    }
    EXPECT_EQ(wrong, 0) << segments << " segments";
    EXPECT_EQ(wrong_shadow, 0) << segments << " segments";
  }
  EXPECT_GT(scene.bvh.segments, 1u);  // the build cut the shutter: the triangles turn far
}

// A few shapes make one leaf: no nodes, no box test, every shape tested; the answers the same.
TEST(MotionBvh, FewShapesAreOneLeafWithoutNodes) {
  MovingScene scene(5);
  scene.spheres.resize(3);
  scene.triangles.resize(2);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<Real> uniform(-1, 1), time(0, 1);
  for (std::uint32_t segments : {1u, 4u}) {
    scene.build(segments);
    EXPECT_EQ(scene.bvh.trees.root_leaf_count, 5u);
    EXPECT_TRUE(scene.bvh.trees.nodes.empty());
    const SceneView v = scene.view();
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
      // Aimed near a shape, so that many rays meet one.
      const Vec3 near = i % 2 == 0 ? scene.spheres[i % 3].center0 : scene.triangles[i % 2].p0[i % 3];
      const Vec3 origin(uniform(rng) * 4, uniform(rng) * 4, 8);
      const Vec3 jitter(uniform(rng), uniform(rng), uniform(rng));
      const Ray ray{origin, normalize(near + jitter * Real(0.3) - origin), time(rng)};
      Hit hit;
      closest_moving_hit(v, ray, 0, hit);
      const Real expected = scene.nearest(ray);
      ASSERT_EQ(hit.t, expected) << i;
      hits += expected < kInfinity;
    }
    EXPECT_GT(hits, 500);
  }
}

// A moving solid or instance costs more than a box test (at_time(), then its own test): it is
// never visited without one. One turning solid alone is a root node over its leaf in each
// segment; with spheres beside it, each sits in a leaf of its own.
TEST(MotionBvh, SolidsAndInstancesAreBehindABox) {
  const auto tree_of = [](const std::string& objects) {
    return compile(parse_scene("camera: {shutter: [0, 1]}\nobjects:\n" + objects, "t.yaml", ".")).moving_bvh;
  };
  const std::string torus =
      "  - {type: torus, center: [0, 0, 0], major_radius: 1, minor_radius: 0.2, motion: {to: {rotate: [0, 0, 60]}}}\n";
  const std::string sphere = "  - {type: sphere, center: [3, 0, 0], radius: 1, motion: {velocity: [0, 1, 0]}}\n";
  const MotionBvh one = tree_of(torus);
  EXPECT_EQ(one.trees.root_leaf_count, 0u);
  EXPECT_EQ(one.trees.nodes.size(), one.segments);  // a root node in each segment
  const MotionBvh three = tree_of(torus + sphere + sphere);
  EXPECT_EQ(three.trees.root_leaf_count, 0u);
  EXPECT_FALSE(three.trees.nodes.empty());
  EXPECT_EQ(tree_of(sphere + sphere).trees.root_leaf_count, 2u);  // cheap shapes: one leaf, as before
}

// The trees are 8-wide: their nodes hold far fewer than the binary tree's 2·leaves − 1, and
// every shape sits in exactly one leaf of each segment's tree.
TEST(MotionBvh, SegmentTreesAreWideAndHoldEveryShapeOnce) {
  MovingScene scene(9);
  scene.build(4);
  const MotionBvhView v = scene.bvh.view();
  const std::size_t shapes = scene.spheres.size() + scene.triangles.size();
  for (std::uint32_t k = 0; k < 4; ++k) {
    const IndexTreeView tree = v.segment_at((Real(k) + Real(0.5)) / 4);
    std::vector<int> seen(shapes, 0);
    std::size_t nodes = 0, leaves = 0;
    std::vector<std::uint32_t> stack = {0};
    while (!stack.empty()) {
      const WideBvhNode& n = tree.nodes[stack.back()];
      stack.pop_back();
      ++nodes;
      for (int c = 0; c < kWideBvhWidth; ++c) {
        if (n.child[c] == kWideBvhEmpty) continue;
        if (n.count[c] == 0) {
          stack.push_back(n.child[c]);
          continue;
        }
        ++leaves;
        for (std::uint32_t i = 0; i < n.count[c]; ++i) ++seen[tree.leaves[n.child[c] + i]];
      }
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(shapes)) << k;
    EXPECT_LT(nodes * 3, 2 * leaves - 1) << k;
  }
}

// Where shapes barely move, one tree: more would cost memory and time for nothing.
TEST(MotionBvh, OneSegmentWhereShapesBarelyMove) {
  MovingScene scene(3);
  for (kernel::MovingTriangle& t : scene.triangles)
    for (int k = 0; k < 3; ++k) t.p1[k] = t.p0[k] + Vec3(0.01, 0, 0);
  for (kernel::MovingSphere& s : scene.spheres) s.center1 = s.center0 + Vec3(0, 0.01, 0), s.radius1 = s.radius0;
  scene.build(0);
  EXPECT_EQ(scene.bvh.segments, 1u);
  EXPECT_GT(scene.bvh.swept_area[0], 0);
  EXPECT_GT(scene.bvh.swept_area[1], 0.8 * scene.bvh.swept_area[0]);
}

// The motion-blur scene's torus (a mesh) turns by 60° during the shutter (a moving instance of
// itself, one box, beside two fast spheres): the boxes shrink with every segment, and the build
// takes several.
TEST(MotionBvh, MotionBlurSceneIsCut) {
  const RenderScene rs = compile(load_scene(std::string(STRAHL_SOURCE_DIR) + "/scenes/motion-blur.yaml"));
  ASSERT_EQ(rs.moving_instances.size(), 1u);
  ASSERT_EQ(rs.groups.size(), 1u);
  ASSERT_GT(rs.groups[0].triangles.size(), 100u);
  const MotionBvh& bvh = rs.moving_bvh;
  // (three shapes: trees that cost next to nothing take any halving that cuts the area by a twentieth)
  for (int i = 1; (1u << i) <= bvh.segments; ++i) EXPECT_LE(bvh.swept_area[i], 0.95 * bvh.swept_area[i - 1]) << i;
  EXPECT_GE(bvh.segments, 4u);
  // (the whole shutter's box already follows the torus's arcs in eighth turns: four segments
  // cut a quarter of it; 0.73 here)
  EXPECT_LT(bvh.swept_area[2], 0.75 * bvh.swept_area[0]);
}

}  // namespace
}  // namespace strahl::motion_bvh_test
