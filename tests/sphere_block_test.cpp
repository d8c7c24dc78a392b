// Spheres eight at a time (accel/sphere_block.h) against the one-by-one loop they replace: the
// same nearest hit (sphere and t, bit for bit), the same occlusion answer and the same crossings,
// on random sphere sets made to be awkward (duplicates, nested, tiny, huge, partial last blocks)
// and rays made to be awkward (starting on a surface, tangent, from inside, axis-parallel with ±0
// components, segments ending on a surface).

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "strahl/accel/accel.h"
#include "test_random.h"

namespace strahl {
namespace {

using test::Random;

PrimitiveSet sphere_set(const std::vector<kernel::Sphere>& spheres) {
  PrimitiveSet p;
  p.spheres = spheres.data();
  p.sphere_count = std::uint32_t(spheres.size());
  return p;
}

bool same_bits(Real a, Real b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::vector<std::pair<std::uint32_t, int>> crossings_of(const AccelView& a, const Ray& ray, Real t_min, Real t_max,
                                                        std::uint32_t stop_at) {
  std::vector<std::pair<std::uint32_t, int>> out;
  auto cross = [&](std::uint32_t prim, int n) {
    out.push_back({prim, n});
    return prim == stop_at;
  };
  for_each_crossing(a, ray, t_min, t_max, cross);
  return out;
}

std::vector<kernel::Sphere> random_spheres(Random& rng, int count) {
  std::vector<kernel::Sphere> s;
  for (int i = 0; i < count; ++i) {
    const int kind = rng.below(5);
    const Vec3 c = rng.point(-2, 2);
    if (kind == 0 && !s.empty()) {
      s.push_back(s[std::size_t(rng.below(int(s.size())))]);  // a duplicate
    } else if (kind == 1 && !s.empty()) {
      kernel::Sphere inner = s.back();  // nested in the previous one
      inner.radius *= 0.5;
      s.push_back(inner);
    } else if (kind == 2) {
      s.push_back({c, 1e-9, 0});
    } else if (kind == 3) {
      s.push_back({c * 1e3, 1e3, 0});
    } else {
      s.push_back({c, rng.uniform(0.05, 1), 0});
    }
  }
  return s;
}

Ray random_ray(Random& rng, const std::vector<kernel::Sphere>& spheres) {
  const kernel::Sphere& s = spheres[std::size_t(rng.below(int(spheres.size())))];
  const Vec3 radial = rng.direction();
  Vec3 d = rng.direction();
  Vec3 o = rng.point(-4, 4);
  switch (rng.below(6)) {
    case 0: o = s.center + radial * s.radius; break;  // on the surface
    case 1:                                            // tangent at a surface point
      o = s.center + radial * s.radius;
      d = normalize(cross(radial, d));
      o = o - d * 3;
      break;
    case 2: o = s.center; break;  // from the centre (inside)
    case 3: d = Vec3{rng.coin() ? 0.0 : -0.0, 0, rng.coin() ? -1.0 : 1.0}; o.x = s.center.x; break;  // axis, ±0
    case 4: d = normalize(s.center - o); break;  // at the centre
    default: break;
  }
  return Ray{o, d};
}

TEST(SphereBlock, AnswersAsTheOneByOneLoopBitForBit) {
  Random rng(20261202);
  int hits = 0, occluded_rays = 0, compared = 0;
  for (int scene = 0; scene < 120; ++scene) {
    const std::vector<kernel::Sphere> spheres = random_spheres(rng, 1 + scene % 20);
    const PrimitiveSet set = sphere_set(spheres);
    for (AccelKind kind : {AccelKind::Naive, AccelKind::Bvh}) {
      const Accel accel = build_accel(kind, set);
      const AccelView blocks = accel.view(set);
      if (kind == AccelKind::Naive || blocks.one_leaf) {
        ASSERT_EQ(blocks.sphere_block_count, (spheres.size() + 7) / 8);
      } else {
        ASSERT_EQ(blocks.sphere_block_count, 0u);  // a real tree: blocks unused
        continue;
      }
      AccelView loop = blocks;  // the same structure, answered one by one
      loop.sphere_blocks = nullptr;
      loop.sphere_block_count = 0;
      for (int r = 0; r < 200; ++r) {
        const Ray ray = random_ray(rng, spheres);
        const Real t_min = r % 3 == 0 ? 0 : rng.uniform(0, 1);
        Real t_max = r % 4 == 0 ? kInfinity : rng.uniform(0.5, 6);
        const NearestHit a = nearest_hit(blocks, ray, t_min, t_max), b = nearest_hit(loop, ray, t_min, t_max);
        ASSERT_TRUE(same_bits(a.hit.t, b.hit.t)) << scene << " " << r;
        ASSERT_EQ(a.prim, b.prim);
        if (a.hit.t < kInfinity) {
          ++hits;
          if (r % 5 == 0) t_max = a.hit.t;  // a segment ending exactly on the surface
        }
        const bool oa = occluded(blocks, ray, t_min, t_max);
        ASSERT_EQ(oa, occluded(loop, ray, t_min, t_max)) << scene << " " << r;
        occluded_rays += oa;
        const std::uint32_t stop_at = r % 2 == 0 ? ~0u : std::uint32_t(r) % std::uint32_t(spheres.size());
        ASSERT_EQ(crossings_of(blocks, ray, t_min, t_max, stop_at), crossings_of(loop, ray, t_min, t_max, stop_at))
            << scene << " " << r;
        ++compared;
      }
    }
  }
  // The rays do meet spheres (the comparisons are not all of misses).
  EXPECT_GT(hits, compared / 4);
  EXPECT_GT(occluded_rays, compared / 4);
}

TEST(SphereBlock, OnlyForSpheresTestedOneByOne) {
  std::vector<kernel::Sphere> spheres = {{Vec3{0, 0, 0}, 1, 0}, {Vec3{3, 0, 0}, 1, 0}};
  PrimitiveSet set = sphere_set(spheres);
  EXPECT_EQ(build_accel(AccelKind::Naive, set).view(set).sphere_block_count, 1u);
  std::vector<kernel::Triangle> triangles(1);
  triangles[0].v1 = {1, 0, 0};
  triangles[0].v2 = {0, 1, 0};
  set.triangles = triangles.data();
  set.triangle_count = 1;
  EXPECT_EQ(build_accel(AccelKind::Naive, set).view(set).sphere_block_count, 0u);  // not spheres only
  // Padding lanes never answer, whatever the ray.
  const std::vector<SphereBlock> b = build_sphere_blocks(spheres.data(), 2);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(sphere_block_candidates(b[0], Ray{Vec3{-5, 0, 0}, Vec3{1, 0, 0}}), 3u);
  EXPECT_EQ(sphere_block_candidates(b[0], Ray{Vec3{0, 0, 0}, Vec3{0, 1, 0}}), 1u);
  EXPECT_EQ(sphere_block_candidates(b[0], Ray{Vec3{0, 5, 0}, Vec3{0, 0, 1}}), 0u);
}

}  // namespace
}  // namespace strahl
