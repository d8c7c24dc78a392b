// Packets of 8 and 16 rays (accel/packet.h, accel/wide_bvh_packet.h) against the single-ray
// queries, lane for lane: the nearest hit bit for bit (primitive, t, b1, b2) and the occlusion
// answer, on random rays, coherent camera tiles (those straddling the image border with their
// outside lanes off), degenerate rays (zero direction components, ±0, along the axes, origins on
// triangle edges and vertices, rays through shared vertices) and random lane masks; inactive
// lanes' outputs are never written. Where two primitives are hit at exactly the same t, which
// one a ray reports depends on the order it meets the leaves in (wide_bvh_packet.h): such a lane
// must report the same t and a primitive really hit at that t, and the test counts them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/accel/packet.h"
#include "strahl/camera/camera.h"
#include "shape_soup.h"
#include "test_random.h"

namespace strahl::packet_test {
namespace {

using test::Random;

using Prims = test::ShapeSoup;

// A 24×24 grid of unit-spaced quads in the plane z = 0 (x, y ∈ [−1, 1]: shared edges and vertices
// on exact binary fractions), a bumpy grid above it, random triangles and spheres.
Prims scene(std::uint64_t seed) {
  Random rng(seed);
  Prims s;
  const int n = 24;
  const auto at = [&](int i, int j, Real z) { return Vec3(-1 + 2 * Real(i) / n, -1 + 2 * Real(j) / n, z); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      s.triangle(at(i, j, 0), at(i + 1, j, 0), at(i + 1, j + 1, 0));
      s.triangle(at(i, j, 0), at(i + 1, j + 1, 0), at(i, j + 1, 0));
    }
  Vec3 h[17][17];
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; j <= 16; ++j)
      h[i][j] = Vec3(-0.8 + 0.1 * i, -0.8 + 0.1 * j, 0.5 + 0.05 * std::sin(3.0 * i) * std::cos(2.0 * j));
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      s.triangle(h[i][j], h[i + 1][j], h[i + 1][j + 1]);
      s.triangle(h[i][j], h[i + 1][j + 1], h[i][j + 1]);
    }
  for (int i = 0; i < 400; ++i) {
    const Vec3 p = rng.point(-1, 1);
    s.triangle(p, p + rng.direction() * rng.log_uniform(1e-3, 0.3), p + rng.direction() * rng.log_uniform(1e-3, 0.3));
  }
  for (int i = 0; i < 40; ++i) s.spheres.push_back({rng.point(-1, 1), rng.log_uniform(1e-3, 0.15), 0});
  return s;
}

struct Counts {
  std::size_t lanes = 0, hits = 0, ties = 0, occluded = 0;
};

// One packet against the single rays: every active lane's answer, every inactive lane untouched.
template <int N>
void check_packet(const AccelView& v, std::uint32_t active, const Ray* rays, const Real* t_min, const Real* t_max,
                  Counts& c) {
  NearestHit out[N];
  for (NearestHit& h : out) h = NearestHit{0xdeadbeefu, kernel::TriangleHit{-7, -7, -7}};
  nearest_hit_packet<N>(v, active, rays, t_min, t_max, out);
  const std::uint32_t occ = occluded_packet<N>(v, active, rays, t_min, t_max);
  EXPECT_EQ(occ & ~active, 0u);
  for (int i = 0; i < N; ++i) {
    if (((active >> i) & 1u) == 0) {
      EXPECT_EQ(out[i].prim, 0xdeadbeefu) << "inactive lane " << i << " written";
      EXPECT_EQ(out[i].hit.t, -7) << "inactive lane " << i << " written";
      continue;
    }
    ++c.lanes;
    const NearestHit single = nearest_hit(v, rays[i], t_min[i], t_max[i]);
    const bool single_occluded = occluded(v, rays[i], t_min[i], t_max[i]);
    EXPECT_EQ(((occ >> i) & 1u) != 0, single_occluded) << "lane " << i;
    c.occluded += single_occluded;
    ASSERT_EQ(out[i].hit.t, single.hit.t) << "lane " << i << " of " << N;  // bit for bit (t is never NaN)
    if (!(single.hit.t < kInfinity)) continue;
    ++c.hits;
    if (out[i].prim != single.prim) {
      // Another primitive at exactly the same t: it must really be hit there.
      ++c.ties;
      const kernel::TriangleHit h = intersect_primitive(v.prims, out[i].prim, rays[i],
                                                        kernel::ray_shear(rays[i].direction), t_min[i], t_max[i]);
      EXPECT_EQ(h.t, out[i].hit.t) << "lane " << i << ": primitive " << out[i].prim << " is not hit at that t";
      EXPECT_EQ(std::memcmp(&h, &out[i].hit, sizeof h), 0);
      continue;
    }
    EXPECT_EQ(std::memcmp(&out[i].hit, &single.hit, sizeof single.hit), 0)
        << "lane " << i << ": b1 " << out[i].hit.b1 << " vs " << single.hit.b1 << ", b2 " << out[i].hit.b2 << " vs "
        << single.hit.b2;
  }
}

// Packets of N from a list of rays (t_min 0 unless given), all lanes active.
template <int N>
Counts check_all(const AccelView& v, const std::vector<Ray>& rays, const std::vector<Real>& t_max) {
  Counts c;
  for (std::size_t first = 0; first + N <= rays.size(); first += N) {
    Real t_min[N] = {};
    check_packet<N>(v, (1u << N) - 1, rays.data() + first, t_min, t_max.data() + first, c);
  }
  return c;
}

struct Built {
  Prims prims;
  Accel accel;
  AccelView view;
  explicit Built(std::uint64_t seed, AccelKind kind = AccelKind::Bvh) : prims(scene(seed)) {
    accel = build_accel(kind, prims.set());
    view = accel.view(prims.set());
  }
};

TEST(Packet, RandomRaysMatchSingleRays) {
  const Built b(1);
  ASSERT_FALSE(b.view.one_leaf);
  Random rng(2);
  std::vector<Ray> rays;
  std::vector<Real> t_max;
  for (int i = 0; i < 8192; ++i) {
    rays.push_back(Ray{rng.point(-1.5, 1.5), rng.direction()});
    t_max.push_back(rng.coin() ? kInfinity : rng.uniform(0.1, 3));
  }
  const Counts c8 = check_all<8>(b.view, rays, t_max), c16 = check_all<16>(b.view, rays, t_max);
  EXPECT_EQ(c8.lanes, rays.size());
  EXPECT_GT(c8.hits, rays.size() / 10);  // the rays meet the scene
  EXPECT_GT(c8.occluded, rays.size() / 8);
  EXPECT_LT(c8.occluded, rays.size());
  EXPECT_EQ(c16.hits, c8.hits);
  EXPECT_LE(c8.ties + c16.ties, rays.size() / 1000);
}

// Neighbouring rays, as packets are meant for: bundles from one origin in a narrow cone, and the
// same with origins spread (shadow rays towards one point).
TEST(Packet, CoherentBundlesMatchSingleRays) {
  const Built b(3);
  Random rng(4);
  std::vector<Ray> rays;
  std::vector<Real> t_max;
  for (int k = 0; k < 400; ++k) {
    const Vec3 o = rng.point(-1.5, 1.5), d = rng.direction();
    const Vec3 light = rng.point(-1.5, 1.5);
    for (int i = 0; i < 16; ++i) {
      rays.push_back(Ray{o, normalize(d + rng.direction() * 0.02)});
      t_max.push_back(kInfinity);
    }
    for (int i = 0; i < 16; ++i) {
      const Vec3 p = o + rng.direction() * 0.05;
      rays.push_back(Ray{p, normalize(light - p)});
      t_max.push_back(length(light - p));
    }
  }
  const Counts c8 = check_all<8>(b.view, rays, t_max), c16 = check_all<16>(b.view, rays, t_max);
  EXPECT_GT(c8.hits, rays.size() / 4);
  EXPECT_EQ(c16.hits, c8.hits);
  EXPECT_LE(c8.ties + c16.ties, rays.size() / 1000);
}

// set_lanes() (SIMD where built) gives every active lane exactly set_lane()'s figures (ray_boxes(),
// round_down / round_up of the interval), bit for bit: random rays, zero and tiny components,
// origins far out, and interval ends that are exact floats, ±0, subnormal, beyond float, ±∞.
template <int N>
void check_set_lanes(std::uint64_t seed) {
  using namespace wide_bvh_packet_detail;
  Random rng(seed);
  const Real ends[] = {0.0, -0.0, 1.0, 0.1, 1e-300, -1e-300, 1e-40, -1e-40, 3e38, 4e38, -4e38, 1e300, -1e300,
                       kInfinity, -kInfinity, Real(std::numeric_limits<float>::max()),
                       Real(std::numeric_limits<float>::denorm_min()), 0x1.000001p0, -0x1.000001p0, 5.5};
  const int n_ends = int(sizeof ends / sizeof ends[0]);
  WideBvhView view;
  for (int a = 0; a < 3; ++a) view.extent[a] = float(rng.log_uniform(1e-3, 1e3));
  for (int trial = 0; trial < 2000; ++trial) {
    Ray rays[N];
    Real t_min[N], t_max[N];
    for (int i = 0; i < N; ++i) {
      Real d[3], o[3];
      for (int a = 0; a < 3; ++a) {
        const int kind = int(rng.uniform(0, 6));
        d[a] = kind == 0 ? 0.0 : kind == 1 ? -0.0 : kind == 2 ? rng.uniform(-1, 1) * 1e-40 : rng.uniform(-1, 1);
        if (trial % 3 == 0) d[a] = a == 1 ? -std::fabs(d[a]) - 0.5 : std::fabs(d[a]);  // signs shared by the lanes
        o[a] = rng.coin() ? rng.uniform(-2, 2) : rng.uniform(-1, 1) * rng.log_uniform(1e-3, 1e40);
      }
      rays[i] = Ray{Vec3(o[0], o[1], o[2]), Vec3(d[0], d[1], d[2])};
      t_min[i] = rng.coin() ? ends[int(rng.uniform(0, n_ends))] : rng.uniform(-1, 1) * rng.log_uniform(1e-45, 1e45);
      t_max[i] = rng.coin() ? ends[int(rng.uniform(0, n_ends))] : rng.uniform(-1, 1) * rng.log_uniform(1e-45, 1e45);
    }
    const std::uint32_t active = trial % 2 ? std::uint32_t(rng.uniform(1, double(1u << N))) : (1u << N) - 1;
    PacketBoxes<N> p, q;
    set_lanes(p, active, view, rays, t_min, t_max);
    int any_sign = 0, all_sign = 7;  // the signs the lanes share
    for (int i = 0; i < N; ++i)
      if ((active >> i) & 1u) {
        const Vec3& d = rays[i].direction;
        const int sign = (std::signbit(d.x) ? 1 : 0) | (std::signbit(d.y) ? 2 : 0) | (std::signbit(d.z) ? 4 : 0);
        any_sign |= sign;
        all_sign &= sign;
      }
    ASSERT_EQ(p.signs, any_sign == all_sign ? all_sign : -1) << "trial " << trial;
    for (int i = 0; i < N; ++i) {
      if (((active >> i) & 1u) == 0) continue;
      set_lane(q, i, view, rays[i], t_min[i], t_max[i]);
      const auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
      for (int a = 0; a < 3; ++a) {
        ASSERT_TRUE(same(p.inv[a][i], q.inv[a][i])) << "trial " << trial << " lane " << i << " axis " << a;
        ASSERT_TRUE(same(p.near_offset[a][i], q.near_offset[a][i])) << "trial " << trial << " lane " << i;
        ASSERT_TRUE(same(p.far_offset[a][i], q.far_offset[a][i])) << "trial " << trial << " lane " << i;
      }
      ASSERT_TRUE(same(p.t_min[i], q.t_min[i])) << "t_min " << t_min[i] << ": " << p.t_min[i] << " vs " << q.t_min[i];
      ASSERT_TRUE(same(p.t_max[i], q.t_max[i])) << "t_max " << t_max[i] << ": " << p.t_max[i] << " vs " << q.t_max[i];
    }
  }
}

TEST(Packet, SetLanesMatchesSetLane) {
  check_set_lanes<8>(51);
  check_set_lanes<16>(52);
}

// The frustum pre-test (wide_bvh_packet.h frustum_children()) never drops a child some lane
// meets: random boxes (and empty slots) against packets of random, coherent and degenerate rays,
// before and after some lanes' t_max are lowered. Every child child_test() finds met by a lane
// must pass the frustum, else traversal would miss leaves.
template <int N>
void check_frustum(std::uint64_t seed) {
  using namespace wide_bvh_packet_detail;
  Random rng(seed);
  std::size_t passed = 0, met = 0, culled = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    WideBvhNode n;
    WideBvhView view;
    for (int a = 0; a < 3; ++a) view.extent[a] = 0;
    for (int k = 0; k < kWideBvhWidth; ++k) {
      n.count[k] = 1;
      n.child[k] = rng.uniform(0, 1) < 0.1 ? kWideBvhEmpty : std::uint32_t(k);
      const Vec3 c = rng.point(-2, 2);
      const Real size = rng.log_uniform(1e-4, 1);
      for (int a = 0; a < 3; ++a) {
        const Real h = size * rng.uniform(0, 1);
        n.lo[a][k] = n.child[k] == kWideBvhEmpty ? std::numeric_limits<float>::infinity() : float(c[a] - h);
        n.hi[a][k] = n.child[k] == kWideBvhEmpty ? -std::numeric_limits<float>::infinity() : float(c[a] + h);
        if (n.child[k] != kWideBvhEmpty)
          view.extent[a] = std::max({view.extent[a], std::fabs(n.lo[a][k]), std::fabs(n.hi[a][k])});
      }
    }
    Ray rays[N];
    Real t_min[N], t_max[N];
    const int kind = trial % 4;
    const Vec3 o = rng.point(-3, 3), d = rng.direction(), target = rng.point(-1, 1);
    for (int i = 0; i < N; ++i) {
      if (kind == 0) {  // random
        rays[i] = Ray{rng.point(-3, 3), rng.direction()};
      } else if (kind == 1) {  // a narrow cone from one origin
        rays[i] = Ray{o, normalize(d + rng.direction() * 0.05)};
      } else if (kind == 2) {  // spread origins towards one point (shadow rays)
        const Vec3 p = o + rng.direction() * 0.3;
        rays[i] = Ray{p, normalize(target - p)};
      } else {  // zero components (±0) and axis-aligned directions
        Real dir[3] = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        const int zero = int(rng.uniform(0, 3));
        dir[zero] = rng.coin() ? 0.0 : -0.0;
        if (rng.coin()) dir[(zero + 1) % 3] = rng.coin() ? 0.0 : -0.0;
        rays[i] = Ray{rng.point(-2, 2), Vec3(dir[0], dir[1], dir[2])};
      }
      t_min[i] = rng.coin() ? 0 : rng.uniform(0, 2);
      t_max[i] = rng.coin() ? kInfinity : t_min[i] + rng.uniform(0, 4);
    }
    const std::uint32_t active = trial % 3 == 0 ? std::uint32_t(rng.uniform(1, double(1u << N))) : (1u << N) - 1;
    PacketBoxes<N> p;
    set_lanes(p, active, view, rays, t_min, t_max);
    for (int round = 0; round < 2; ++round) {
      if (round == 1) {  // some lanes' nearest hit found
        for (int i = 0; i < N; ++i)
          if (((active >> i) & 1u) && rng.coin()) p.t_max[i] = std::min(p.t_max[i], float(rng.uniform(0, 3)));
        lower_frustum(p, active);
      }
      float t_front[kWideBvhWidth];
      const unsigned frustum = frustum_children(n, p, t_front);
      for (int k = 0; k < kWideBvhWidth; ++k) {
        if (n.child[k] == kWideBvhEmpty) {
          EXPECT_EQ((frustum >> k) & 1u, 0u) << "empty slot " << k;
          continue;
        }
        float t = 0;
        const std::uint32_t lanes = child_test<N>(n, k, p, active, t);
        met += lanes != 0;
        passed += (frustum >> k) & 1u;
        culled += lanes == 0 && ((frustum >> k) & 1u) == 0;
        if (lanes != 0) {
          ASSERT_TRUE((frustum >> k) & 1u) << "trial " << trial << " child " << k << ": lanes " << lanes
                                            << " meet it, the frustum culls it";
        }
      }
    }
  }
  EXPECT_GT(met, 1000u);     // the boxes are met
  EXPECT_GT(culled, 1000u);  // and the frustum culls some
  EXPECT_GE(passed, met);    // (every child a lane meets passes)
}

TEST(Packet, FrustumKeepsEveryChildALaneMeets) {
  check_frustum<8>(41);
  check_frustum<16>(42);
}

// The sphere pre-test (packet.h packet_cone(), cone_may_meet()) never skips a sphere that some
// active lane's ray meets, as the lane tests compute it: packets from one origin, shadow-ray-like
// packets (spread origins towards one point), parallel rays, unnormalised directions, at scales
// 1e-3…1e4 and 1e5 from the origin, against random spheres and spheres tangent to one lane's ray
// (their radius off by a few ulps either way: the lane test's rounding decides those).
template <int N>
void check_cone(std::uint64_t seed) {
  Random rng(seed);
  std::size_t met = 0, culled = 0, tangent_met = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Real scale = rng.log_uniform(1e-3, 1e4);
    const Vec3 shift = trial % 5 == 0 ? Vec3(1e5, -1e5, 1e5) : Vec3(0);
    const int kind = trial % 4;
    const Vec3 o = rng.point(-1, 1) * scale + shift, d = rng.direction(), target = rng.point(-1, 1) * scale + shift;
    const Real width = rng.log_uniform(1e-6, 0.5);
    Ray rays[N];
    Real t_min[N], t_max[N];
    for (int i = 0; i < N; ++i) {
      if (kind == 0) {  // one origin, a cone of directions
        rays[i] = Ray{o, normalize(d + rng.direction() * width)};
      } else if (kind == 1) {  // spread origins towards one point
        const Vec3 p = o + rng.direction() * (width * scale);
        rays[i] = Ray{p, normalize(target - p)};
      } else if (kind == 2) {  // parallel rays
        rays[i] = Ray{o + rng.direction() * (width * scale), d};
      } else {  // unnormalised directions
        rays[i] = Ray{o + rng.direction() * (width * scale * 1e-3), (d + rng.direction() * width) * rng.uniform(0.5, 2)};
      }
      t_min[i] = rng.coin() ? 0 : rng.uniform(0, 1) * scale;
      t_max[i] = rng.coin() ? kInfinity : t_min[i] + rng.uniform(0, 4) * scale;
    }
    const std::uint32_t active = trial % 3 == 0 ? std::uint32_t(rng.uniform(1, double(1u << N))) : (1u << N) - 1;
    PacketRays<N> r(rays);
    r.unit = kind != 3;  // (unit directions: the cone takes them as they are)
    const PacketCone cone = packet_cone<N>(r, active, t_min);
    for (int k = 0; k < 16; ++k) {
      kernel::Sphere sphere;
      const bool tangent = k % 2 == 1;
      if (!tangent) {
        sphere.center = rng.point(-2, 2) * scale + shift;
        sphere.radius = rng.log_uniform(1e-4, 1) * scale;
      } else {  // touching lane j's ray at t (its radius a few ulps off either way)
        int j = int(rng.below(N));
        while (((active >> j) & 1u) == 0) j = (j + 1) % N;
        const Vec3 dir = normalize(rays[j].direction);
        const Vec3 p = rays[j].origin + dir * (rng.uniform(0, 3) * scale);
        const Vec3 u = normalize(cross(dir, rng.direction()));
        const Real radius = rng.log_uniform(1e-4, 1) * scale;
        sphere.center = p + u * radius;
        sphere.radius = radius * (1 + Real(rng.uniform(-8, 8)) * 1.1e-16);
      }
      bool some_lane_meets = false;
      for (int i = 0; i < N; ++i)
        if ((active >> i) & 1u)
          some_lane_meets |= kernel::intersect(sphere, rays[i], t_min[i], t_max[i]) < kInfinity ||
                             kernel::crossings(sphere, rays[i], t_min[i], t_max[i]) > 0;
      const bool may_meet = cone_may_meet(cone, sphere);
      met += some_lane_meets;
      tangent_met += tangent && some_lane_meets;
      culled += !may_meet;
      if (some_lane_meets) {
        ASSERT_TRUE(may_meet) << "trial " << trial << " sphere " << k << (tangent ? " (tangent)" : "")
                              << ": a lane meets it, the cone skips it";
      }
    }
  }
  EXPECT_GT(met, 5000u);          // spheres are met
  EXPECT_GT(tangent_met, 2000u);  // tangent ones too, by the lanes' rounding
  EXPECT_GT(culled, 10000u);      // and the cone skips many others
}

TEST(Packet, ConeKeepsEverySphereALaneMeets) {
  check_cone<8>(43);
  check_cone<16>(44);
}

// Zero direction components (+0 and −0), rays along the axes, origins exactly on the grid's edges
// and vertices and in its plane, rays through its shared vertices and along its edges.
TEST(Packet, DegenerateRaysMatchSingleRays) {
  const Built b(5);
  Random rng(6);
  std::vector<Ray> rays;
  const Real zeros[2] = {0.0, -0.0};
  const auto grid = [&](int i) { return -1 + 2 * Real(i) / 24; };
  for (int k = 0; k < 2048; ++k) {
    Vec3 o = rng.point(-1.2, 1.2), d = rng.direction();
    switch (k % 8) {
      case 0: d = Vec3(zeros[k / 8 % 2], zeros[k / 16 % 2], k / 32 % 2 ? 1 : -1); break;  // along z
      case 1: d = Vec3(k / 8 % 2 ? 1 : -1, zeros[k / 16 % 2], zeros[k / 32 % 2]); break;  // along x
      case 2: d = normalize(Vec3(d.x, zeros[k / 8 % 2], d.z)); break;                    // one zero component
      case 3: o = Vec3(grid(rng.below(25)), grid(rng.below(25)), 0); break;               // origin on a vertex
      case 4: o = Vec3(grid(rng.below(25)), rng.uniform(-1, 1), 0); break;                // origin on an edge
      case 5: {                                                                           // through a vertex
        const Vec3 target(grid(rng.below(25)), grid(rng.below(25)), 0);
        o = target + d * rng.uniform(0.5, 2);
        d = -d;
        break;
      }
      case 6: o = Vec3(grid(rng.below(25)), rng.uniform(-1.5, 1.5), 0); d = Vec3(0, k / 8 % 2 ? 1 : -1, 0); break;  // along an edge
      case 7: o = Vec3(o.x, o.y, 0); d = normalize(Vec3(d.x, d.y, zeros[k / 8 % 2])); break;  // in the grid's plane
    }
    rays.push_back(Ray{o, d});
  }
  const std::vector<Real> t_max(rays.size(), kInfinity);
  const Counts c8 = check_all<8>(b.view, rays, t_max), c16 = check_all<16>(b.view, rays, t_max);
  EXPECT_GT(c8.hits, rays.size() / 4);
  EXPECT_EQ(c16.hits, c8.hits);
  // Rays through shared vertices may meet several triangles at one t: ties, each checked above.
  std::printf("degenerate rays: %zu hits, ties %zu (8) and %zu (16)\n", c8.hits, c8.ties, c16.ties);
}

// Random masks, single lanes, no lane, and per-lane intervals (t_min > 0, empty ones).
TEST(Packet, PartiallyActiveLanes) {
  const Built b(7);
  Random rng(8);
  Counts c;
  for (int k = 0; k < 2000; ++k) {
    Ray rays[16];
    Real t_min[16], t_max[16];
    const Vec3 o = rng.point(-1.5, 1.5), d = rng.direction();
    for (int i = 0; i < 16; ++i) {
      rays[i] = Ray{k % 2 ? o : rng.point(-1.5, 1.5), normalize(d + rng.direction() * (k % 3 ? 0.05 : 1.0))};
      t_min[i] = rng.coin() ? 0 : rng.uniform(0, 1);
      t_max[i] = rng.coin() ? kInfinity : t_min[i] + rng.uniform(-0.1, 2);  // sometimes empty
    }
    const std::uint32_t masks[] = {std::uint32_t(rng.below(1 << 16)), 1u << rng.below(16), 0u,
                                   std::uint32_t(rng.below(1 << 16)) & std::uint32_t(rng.below(1 << 16))};
    const std::uint32_t mask = masks[k % 4];
    check_packet<16>(b.view, mask, rays, t_min, t_max, c);
    check_packet<8>(b.view, mask & 0xffu, rays, t_min, t_max, c);
    check_packet<8>(b.view, mask >> 8, rays + 8, t_min + 8, t_max + 8, c);
  }
  EXPECT_GT(c.hits, c.lanes / 16);
}

// A camera's tiles of 4×2 and 4×4 pixels over an image whose size is no multiple of the tile:
// the border tiles' lanes outside the image are off.
TEST(Packet, CameraTilesStraddlingTheBorder) {
  const Built b(9);
  Camera cam;
  cam.eye = Vec3(0.3, -0.4, 2.5);
  cam.basis = Frame::look_at(cam.eye, Vec3(0, 0, 0.3), Vec3(0, 1, 0));
  cam.l = cam.b = -0.6;
  cam.r = cam.t = 0.6;
  cam.nx = 37;
  cam.ny = 23;
  Counts c;
  for (int size : {8, 16}) {
    const int tw = 4, th = size / 4;
    for (int ty = 0; ty < cam.ny; ty += th)
      for (int tx = 0; tx < cam.nx; tx += tw) {
        Ray rays[16];
        Real t_min[16] = {}, t_max[16];
        std::uint32_t active = 0;
        for (int i = 0; i < size; ++i) {
          const int x = tx + i % tw, y = ty + i / tw;
          t_max[i] = kInfinity;
          rays[i] = cam.generate_ray(Real(std::min(x, cam.nx - 1)) + 0.5, Real(std::min(y, cam.ny - 1)) + 0.5);
          if (x < cam.nx && y < cam.ny) active |= 1u << i;
        }
        if (size == 8)
          check_packet<8>(b.view, active, rays, t_min, t_max, c);
        else
          check_packet<16>(b.view, active, rays, t_min, t_max, c);
      }
  }
  EXPECT_EQ(c.lanes, std::size_t(2 * cam.nx * cam.ny));
  EXPECT_GT(c.hits, c.lanes / 3);
}

// The other structures, a one-leaf BVH and an empty scene answer lane by lane: the same.
TEST(Packet, OtherStructuresAndTinyScenes) {
  Random rng(10);
  std::vector<Ray> rays;
  for (int i = 0; i < 256; ++i) rays.push_back(Ray{rng.point(-1.5, 1.5), rng.direction()});
  const std::vector<Real> t_max(rays.size(), kInfinity);
  for (AccelKind kind : {AccelKind::Naive, AccelKind::KdTree, AccelKind::Octree}) {
    const Built b(11, kind);
    EXPECT_GT(check_all<8>(b.view, rays, t_max).hits, 0u);
    check_all<16>(b.view, rays, t_max);
  }
  // One leaf of spheres and triangles (one_leaf_occluded_packet: the spheres side by side, the
  // triangles lane by lane), rays ending short of it too.
  Prims tiny;
  tiny.triangle(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0));
  tiny.spheres.push_back({Vec3(0, 0, 0.5), 0.3, 0});
  tiny.spheres.push_back({Vec3(0.8, 0.5, -0.4), 0.4, 0});
  tiny.spheres.push_back({Vec3(-0.9, 0.2, 0.1), 0.25, 0});
  tiny.triangle(Vec3(-1, 1, -1), Vec3(1, 1, -1), Vec3(0, 1.2, 1));
  const Accel one = build_accel(AccelKind::Bvh, tiny.set());
  const AccelView one_view = one.view(tiny.set());
  ASSERT_TRUE(one_view.one_leaf);
  std::vector<Real> short_of(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) short_of[i] = i % 3 == 0 ? Real(0.5) : kInfinity;
  const Counts c8 = check_all<8>(one_view, rays, short_of);
  EXPECT_GT(c8.occluded, rays.size() / 8);
  EXPECT_LT(c8.occluded, rays.size());
  check_all<16>(one_view, rays, t_max);
  const Prims none;
  const Accel empty = build_accel(AccelKind::Bvh, none.set());
  EXPECT_EQ(check_all<16>(empty.view(none.set()), rays, t_max).hits, 0u);
}

// The BVH's packet traversal itself on a one-leaf tree (root_leaf_count > 0, no nodes): what
// packet.h never calls it with (it answers one-leaf scenes ray by ray), but the kernel allows.
TEST(Packet, WideBvhPacketOnOneLeafTree) {
  Prims tiny;
  tiny.triangle(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0));
  tiny.triangle(Vec3(-1, -1, 0.2), Vec3(1, -1, 0.2), Vec3(0, 1, 0.2));
  const Accel a = build_accel(AccelKind::Bvh, tiny.set());
  ASSERT_GT(a.bvh.root_leaf_count, 0u);
  Random rng(12);
  for (int k = 0; k < 100; ++k) {
    Ray rays[8];
    Real t_min[8] = {}, t_max[8], t_far[8];
    std::uint32_t prim[8] = {};
    kernel::TriangleHit hit[8];
    for (int i = 0; i < 8; ++i) {
      rays[i] = Ray{rng.point(-1, 1) + Vec3(0, 0, 2), normalize(Vec3(0, 0, -1) + rng.direction() * 0.3)};
      t_max[i] = t_far[i] = kInfinity;
    }
    wide_bvh_nearest_packet<8>(a.bvh.view(), tiny.set(), 0xffu, rays, t_min, t_far, prim, hit);
    const std::uint32_t occ = wide_bvh_occluded_packet<8>(a.bvh.view(), tiny.set(), 0xffu, rays, t_min, t_max);
    for (int i = 0; i < 8; ++i) {
      std::uint32_t p = 0;
      kernel::TriangleHit h;
      wide_bvh_nearest(a.bvh.view(), tiny.set(), rays[i], 0, kInfinity, p, h);
      EXPECT_EQ(std::memcmp(&h, &hit[i], sizeof h), 0);
      if (h.t < kInfinity) {
        EXPECT_EQ(p, prim[i]);
      }
      EXPECT_EQ(((occ >> i) & 1u) != 0, h.t < kInfinity);
    }
  }
}

#if defined(STRAHL_HAVE_EMBREE)
// Embree's packets (rtcIntersect8/16, rtcOccluded8/16) against its own single rays: the same
// primitive (or, on a grazing ray, a hit at the same distance) and the same occlusion.
TEST(Packet, EmbreePacketsMatchEmbreeSingleRays) {
  const Built b(13, AccelKind::Embree);
  Random rng(14);
  std::size_t lanes = 0, differ = 0, hits = 0;
  for (int k = 0; k < 1000; ++k) {
    Ray rays[16];
    Real t_min[16], t_max[16];
    const Vec3 o = rng.point(-1.5, 1.5), d = rng.direction();
    for (int i = 0; i < 16; ++i) {
      rays[i] = Ray{o, normalize(d + rng.direction() * (k % 2 ? 0.05 : 1.0))};
      t_min[i] = 0;
      t_max[i] = k % 3 ? kInfinity : rng.uniform(0.1, 2);
    }
    const std::uint32_t active = k % 5 ? 0xffffu : std::uint32_t(rng.below(1 << 16));
    for (int n : {8, 16}) {
      NearestHit out[16];
      bool occ[16] = {};
      embree_nearest_hit_packet(b.view, n, active, rays, t_min, t_max, out);
      embree_occluded_packet(b.view, n, active, rays, t_min, t_max, occ);
      for (int i = 0; i < n; ++i) {
        if (((active >> i) & 1u) == 0) continue;
        ++lanes;
        const NearestHit s = nearest_hit(b.view, rays[i], t_min[i], t_max[i]);
        hits += s.hit.t < kInfinity;
        const bool same = (out[i].hit.t < kInfinity) == (s.hit.t < kInfinity) &&
                          (!(s.hit.t < kInfinity) || out[i].prim == s.prim ||
                           std::fabs(out[i].hit.t - s.hit.t) <= 1e-6 * s.hit.t);
        differ += !same;
        differ += occ[i] != occluded(b.view, rays[i], t_min[i], t_max[i]);
      }
    }
  }
  EXPECT_GT(hits, lanes / 8);
  EXPECT_LE(differ, lanes / 2000) << differ << " of " << lanes << " lanes differ";
  NearestHit out[16];
  Real zero[16] = {};
  Ray rays[16];
  EXPECT_THROW(embree_nearest_hit_packet(b.view, 4, 1u, rays, zero, zero, out), std::invalid_argument);
}
#endif

}  // namespace
}  // namespace strahl::packet_test
