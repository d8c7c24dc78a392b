// surface_lanes() (render/surface_lanes.h) against surface_at(), lane for lane: every field of the
// surface point bit for bit (point, normals, texture coordinate, material, time, offset) on random
// rays through scenes of spheres and planes at scales 1e-3 … 1e4 and 1e5 from the origin, with
// lanes that miss, inactive lanes and packets whose lanes all hit one shape (fetched once); the
// hits in lane form (HitLanes) give each lane's Hit back, and a lane that hit another kind of
// shape makes the lane form decline.

#include <gtest/gtest.h>

#include <cstring>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/surface_lanes.h"
#include "test_helpers.h"
#include "test_random.h"

namespace strahl::surface_lanes_test {
namespace {

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }
bool same_bits(Real a, Real b) { return std::memcmp(&a, &b, sizeof(Real)) == 0; }

// Spheres and tilted planes (with their texture frames) inside a box of half-size `scale` at `shift`.
Scene scene_at(Real scale, const Vec3& shift, std::uint64_t seed) {
  test::Random rng(seed);
  Scene s;
  for (int k = 0; k < 24; ++k)
    s.add(Sphere(shift + rng.point(-1, 1) * scale, rng.log_uniform(1e-2, 0.5) * scale,
                 test::phong(Vec3(0.5), 0.1, 0.7, Vec3(0.3), 10)));
  for (int k = 0; k < 3; ++k) {
    const Vec3 n = rng.direction();
    s.add(Plane(n, dot(n, shift) + rng.uniform(-1, 1) * scale, test::phong(Vec3(0.4), 0.1, 0.7, Vec3(0), 1)));
  }
  return s;
}

template <int N>
void check(Real scale, const Vec3& shift, std::uint64_t seed, std::size_t& spheres, std::size_t& planes,
           std::size_t& uniform) {
  const RenderScene rs = compile(scene_at(scale, shift, seed));
  const SceneView view = rs.view();
  test::Random rng(seed + 1);
  for (int packet = 0; packet < 200; ++packet) {
    Ray rays[N];
    Hit hits[N];
    const Vec3 o = shift + rng.point(-1.5, 1.5) * scale, d = rng.direction();
    for (int i = 0; i < N; ++i) {
      // One origin or many; every third packet a narrow cone, whose lanes mostly hit one shape.
      const Vec3 dir = packet % 3 == 2 ? normalize(d + rng.direction() * 1e-4) : rng.direction();
      rays[i] = Ray{packet % 2 ? o : shift + rng.point(-1.5, 1.5) * scale, dir, rng.uniform(0, 1)};
      hits[i] = closest_hit(view, rays[i], 0, kInfinity);
    }
    int same = 1;
    for (int i = 1; i < N; ++i) same &= int(hits[i].kind == hits[0].kind && hits[i].index == hits[0].index);
    uniform += same && hits[0].found();
    const std::uint32_t active = packet % 3 == 0 ? std::uint32_t(rng.uniform(1, double(1u << N))) : (1u << N) - 1;
    const PacketRays<N> r(rays);
    HitLanes<N> hit_lanes;
    ASSERT_TRUE(hit_lanes.set(active, hits));
    for (int i = 0; i < N; ++i) {  // the lane form gives each active lane's Hit back
      const Hit h = hit_lanes.hit(i);
      if (!((active >> i) & 1u)) continue;
      EXPECT_EQ(h.kind, hits[i].kind) << "lane " << i;
      EXPECT_EQ(h.index, hits[i].index) << "lane " << i;
      EXPECT_TRUE(same_bits(h.t, hits[i].t)) << "lane " << i;
    }
    SurfaceLanes<N> lanes;
    std::uint32_t lit = ~0u;
    surface_lanes<N>(view, active, r, hit_lanes, lanes, lit);
    for (int i = 0; i < N; ++i) {
      const bool on = (active >> i) & 1u;
      ASSERT_EQ(((lit >> i) & 1u) != 0, on && hits[i].found()) << "lane " << i;
      if (!on || !hits[i].found()) continue;
      spheres += hits[i].kind == ShapeKind::Sphere;
      planes += hits[i].kind == ShapeKind::Plane;
      SurfacePoint want, got;
      surface_at(view, rays[i], hits[i], want);
      lanes.get(i, rays[i].time, got);
      EXPECT_TRUE(same_bits(got.p, want.p)) << "lane " << i;
      EXPECT_TRUE(same_bits(got.geometric_normal, want.geometric_normal)) << "lane " << i;
      EXPECT_TRUE(same_bits(got.normal, want.normal)) << "lane " << i;
      EXPECT_TRUE(same_bits(got.texcoord, want.texcoord)) << "lane " << i;
      EXPECT_EQ(got.material, want.material) << "lane " << i;
      EXPECT_TRUE(same_bits(got.time, want.time)) << "lane " << i;
      ASSERT_TRUE(same_bits(got.offset, want.offset)) << "lane " << i << ": " << got.offset << " vs " << want.offset;
    }
    // Another kind of shape in an active lane: the lane form declines (an inactive lane's is ignored).
    const int j = packet % N;
    hits[j].kind = ShapeKind::Triangle;
    EXPECT_EQ(hit_lanes.set(active, hits), ((active >> j) & 1u) == 0);
  }
}

TEST(SurfaceLanes, EqualSurfaceAtBitForBit) {
  std::size_t spheres = 0, planes = 0, uniform = 0;  // uniform: packets whose lanes all hit one shape
  std::uint64_t seed = 11;
  for (const Real scale : {1e-3, 1.0, 1e4})
    for (const Vec3& shift : {Vec3(0), Vec3(1e5, -1e5, 1e5)}) {
      check<16>(scale, shift, seed++, spheres, planes, uniform);
      check<8>(scale, shift, seed++, spheres, planes, uniform);
    }
  EXPECT_GT(spheres, 1000u);
  EXPECT_GT(planes, 5000u);
  EXPECT_GT(uniform, 250u);
}

}  // namespace
}  // namespace strahl::surface_lanes_test
