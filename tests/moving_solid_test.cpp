// Moving solids and instances (geometry/moving_solid.h, geometry/moving_instance.h,
// scene/move_solid.h): a moving box is met exactly where a moving mesh of its faces is (the same
// rays, times, distances and normals, and the same image), and so is a moving instance of a group
// holding that mesh; a solid moving with a velocity is met where the still solid, displaced, is;
// the motion BVH over many turning solids finds what testing each alone finds; and the errors
// name what cannot move.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/scene_hash.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/csg.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "strahl/scene/solids.h"
#include "swept_bounds_check.h"
#include "test_helpers.h"

namespace strahl::moving_solid_test {
namespace {

// The box [lo, hi] as twelve triangles wound outwards.
MeshData box_mesh(const Vec3& lo, const Vec3& hi) {
  MeshData d;
  for (int c = 0; c < 8; ++c) d.positions.push_back(Vec3((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z));
  const Vec3 mid = (lo + hi) * Real(0.5);
  for (int axis = 0; axis < 3; ++axis) {
    const int b = 1 << ((axis + 1) % 3), c = 1 << ((axis + 2) % 3);
    for (int side = 0; side < 2; ++side) {
      const std::uint32_t base = side ? std::uint32_t(1 << axis) : 0;
      const std::uint32_t q[4] = {base, base + std::uint32_t(b), base + std::uint32_t(b + c), base + std::uint32_t(c)};
      for (const auto& [i, j, k] : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
        MeshData::Face f;
        f.v = {q[i], q[j], q[k]};
        const Vec3 a = d.positions[f.v[0]], e = d.positions[f.v[1]], g = d.positions[f.v[2]];
        if (dot(cross(e - a, g - a), a - mid) < 0) std::swap(f.v[1], f.v[2]);
        d.faces.push_back(f);
      }
    }
  }
  return d;
}

Transform keyframe(const Vec3& scale, const Vec3& rotate, const Vec3& translate) {
  Transform t;
  t.scale = scale;
  t.rotate_degrees = rotate;
  t.translate = translate;
  return t;
}

// Random rays from around the camera's place towards the region the shapes sweep, at random times.
struct RayMaker {
  std::mt19937_64 rng{20261206};
  Ray next(const Vec3& target, Real spread, Real shutter = 1) {
    std::uniform_real_distribution<Real> u(-1, 1), t(0, 1);
    const Vec3 origin(u(rng) * 0.5, u(rng) * 0.5, 2 + u(rng) * 0.5);
    const Vec3 aim = target + Vec3(u(rng), u(rng), u(rng)) * spread;
    return Ray{origin, normalize(aim - origin), t(rng) * shutter};
  }
};

const Vec3 kLo(-0.5, -0.4, -0.3), kHi(0.5, 0.4, 0.3);

// The same motion for both: a turn, an uneven scale and a translation between the keys.
Motion box_motion() {
  return Motion::keyframes(keyframe({1, 1, 1}, {0, 0, 0}, {0, 0, -4}),
                           keyframe({1.3, 0.8, 1}, {25, 40, -15}, {0.7, 0.3, -4.6}));
}

// Rays at random times towards where the box moves: scene a (whose hits are of kind `kind`) and
// scene b (the moving mesh) meet them at the same distance with the same normal, and shadow rays
// towards the far side are blocked alike. Returns how many rays hit.
int same_hits(const RenderScene& a, const RenderScene& b, ShapeKind kind) {
  const SceneView va = a.view(), vb = b.view();
  RayMaker rays;
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = rays.next({0.35, 0.15, -4.3}, 1.2);
    const Hit ha = closest_hit(va, ray, 0, kInfinity), hb = closest_hit(vb, ray, 0, kInfinity);
    EXPECT_EQ(ha.found(), hb.found()) << "ray " << i << " at time " << ray.time;
    if (!ha.found() || !hb.found()) continue;
    ++hits;
    EXPECT_EQ(ha.kind, kind);
    EXPECT_NEAR(ha.t, hb.t, 1e-12 * hb.t) << "ray " << i;
    const SurfacePoint sa = surface_at(va, ray, ha), sb = surface_at(vb, ray, hb);
    EXPECT_TRUE(test::vec_near(sa.normal, sb.normal, 1e-12)) << "ray " << i;
    const Ray back{ray.at(ha.t * 0.5), ray.direction, ray.time};
    EXPECT_EQ(transmittance(va, back, ha.t), transmittance(vb, back, hb.t)) << "ray " << i;
    if (::testing::Test::HasFailure()) break;
  }
  return hits;
}

TEST(MovingSolid, BoxIsMetWhereAMovingMeshOfItsFacesIs) {
  Scene solid_scene, mesh_scene;
  Box box(kLo, kHi, Material{});
  box.motion = box_motion();
  solid_scene.add(std::move(box));
  Mesh mesh(box_mesh(kLo, kHi), Material{});
  mesh.motion = box_motion();
  mesh_scene.add(std::move(mesh));
  const RenderScene a = compile(solid_scene), b = compile(mesh_scene);
  ASSERT_EQ(a.moving_solids.size(), 1u);
  ASSERT_TRUE(a.solids.empty());
  // (the mesh turns: it moves as an instance of a group holding it unmoved, by the same map)
  ASSERT_EQ(b.moving_instances.size(), 1u);
  ASSERT_TRUE(b.moving_triangles.empty());
  const int hits = same_hits(a, b, ShapeKind::MovingSolid);
  EXPECT_GT(hits, 2000);
  EXPECT_LT(hits, 18000);
}

// End to end: both scenes render the same picture, moving shadow included, through the same
// samples (times, positions) of the same sampler.
TEST(MovingSolid, BoxRendersAsTheMovingMeshDoes) {
  const auto scene = [](bool as_mesh) {
    Scene s;
    s.add(Plane({0, 1, 0}, -0.9, test::phong(Vec3(0.8), 0.2, 0.8, Vec3(0), 1)));
    const Material m = test::phong({0.9, 0.3, 0.2}, 0.1, 0.7, Vec3(0.4), 40);
    if (as_mesh) {
      Mesh mesh(box_mesh(kLo, kHi), m);
      mesh.motion = box_motion();
      s.add(std::move(mesh));
    } else {
      Box box(kLo, kHi, m);
      box.motion = box_motion();
      s.add(std::move(box));
    }
    s.addLightSource(Vec3(2, 5, 2));
    test::set_camera(s, {0, 0.5, 1}, {0.3, 0, -4.3}, {0, 1, 0}, -0.4, 0.4, -0.3, 0.3, 1, 64, 48);
    s.camera.shutter_open = 0;
    s.camera.shutter_close = 1;
    s.settings.supersample = 3;
    return s;
  };
  const Image a = test::render_image(scene(false)), b = test::render_image(scene(true));
  EXPECT_LE(test::max_abs_diff(a, b), 1e-6f);
  // (and the box does move: frozen at shutter open, the picture differs)
  Scene frozen = scene(false);
  frozen.camera.shutter_close = 0;
  EXPECT_GT(test::max_abs_diff(a, test::render_image(frozen)), 0.1f);
}

// An instance placed by P and moved by A(u) is met where a mesh with P taken into its vertices,
// moved by the same motion, is (A acts after the placement, in world space).
TEST(MovingSolid, InstanceIsMetWhereTheMovingMeshIs) {
  const Transform placement = keyframe({1.2, 0.7, 1}, {10, 20, 30}, {0.2, -0.1, 0.3});
  for (const Motion& motion : {box_motion(), Motion::linear({0.6, -0.2, 0.3})}) {
    Scene instanced, meshed;
    ObjectGroup g;
    g.name = "box";
    g.objects.push_back(std::make_unique<Mesh>(box_mesh(kLo, kHi), Material{}));
    instanced.groups.push_back(std::move(g));
    Instance in(0, placement);
    in.motion = motion;
    if (motion.kind == Motion::Kind::Velocity) in.placement.translate = in.placement.translate + Vec3(0, 0, -4);
    const Transform p = in.placement;
    instanced.add(std::move(in));
    MeshData placed = box_mesh(kLo, kHi);
    for (Vec3& v : placed.positions) v = p.linear() * v + p.translate;
    Mesh mesh(std::move(placed), Material{});
    mesh.motion = motion;
    meshed.add(std::move(mesh));
    for (Scene* s : {&instanced, &meshed}) {
      s->camera.shutter_open = 0;
      s->camera.shutter_close = 1;
    }
    const RenderScene a = compile(instanced), b = compile(meshed);
    ASSERT_EQ(a.moving_instances.size(), 1u);
    ASSERT_TRUE(a.instances.empty());
    EXPECT_GT(same_hits(a, b, ShapeKind::MovingInstance), 1000);
  }
}

// Keyframes that turn carry every point on an arc: keys Rot(a, α)·S₀ and Rot(a, α + θ)·S₁ give
// Rot(a, α + u·θ)·((1 − u)·S₀ + u·S₁) at shutter fraction u (translations blended). A turning box
// is met where the still box, so placed, is — past a quarter turn (whose axis the turn's
// symmetric part gives) and below it, mirrored or not.
TEST(MovingSolid, TurningBoxIsTheStillBoxTurned) {
  struct Case {
    Vec3 axis;
    Real alpha, theta;
    Vec3 s0, s1;
  };
  for (const Case& c : {Case{{0.3, 1, -0.2}, 20, 130, {1, 1, 1}, {1.5, 1, 0.5}},
                        Case{{1, -0.4, 0.5}, -35, 50, {0.8, 1.2, 1}, {1, 1, 1}},
                        Case{{0, 0, 1}, 0, 170, {-1, 1, 1}, {-1.2, 0.9, 1}}}) {
    const Vec3 t0(0.3, 0, -4), t1(-0.2, 0.4, -4.5);
    const auto key = [&](Real degrees, const Vec3& scale, const Vec3& t) {
      return Transform::affine(Mat3::rotation(c.axis, degrees) * Mat3::scale(scale), t);
    };
    Scene moving;
    Box box(kLo, kHi, Material{});
    box.motion = Motion::keyframes(key(c.alpha, c.s0, t0), key(c.alpha + c.theta, c.s1, t1));
    moving.add(std::move(box));
    moving.camera.shutter_open = 0;
    moving.camera.shutter_close = 1;
    const RenderScene rs = compile(moving);
    ASSERT_EQ(rs.moving_solids.size(), 1u);
    EXPECT_NEAR(rs.moving_solids[0].map.angle, c.theta * kPi / 180, 1e-12);
    const SceneView v = rs.view();
    RayMaker rays;
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
      const Ray ray = rays.next({0, 0.2, -4.3}, 0.8);
      Scene still;
      Box turned(kLo, kHi, Material{});
      const Real u = ray.time;
      turned.placement = key(c.alpha + u * c.theta, c.s0 * (1 - u) + c.s1 * u, t0 * (1 - u) + t1 * u);
      still.add(std::move(turned));
      const RenderScene rs_still = compile(still);
      const SceneView w = rs_still.view();
      const Hit a = closest_hit(v, ray, 0, kInfinity), b = closest_hit(w, ray, 0, kInfinity);
      ASSERT_EQ(a.found(), b.found()) << "ray " << i << " at time " << u;
      if (!a.found()) continue;
      ++hits;
      ASSERT_NEAR(a.t, b.t, 1e-12 * b.t) << "ray " << i;
      ASSERT_TRUE(test::vec_near(surface_at(v, ray, a).normal, surface_at(w, ray, b).normal, 1e-12)) << "ray " << i;
    }
    EXPECT_GT(hits, 300);
  }
}

// The box swept by a turning map over a segment of the shutter holds the box's points at every
// time of the segment (maps with turns up to nearly a half turn, uneven scales, a post map), for
// the segments the motion BVH cuts.
TEST(MovingSolid, SweptBoundsOfATurnHoldEveryTime) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> u(-1, 1);
  Camera camera;
  camera.shutter_open = 0;
  camera.shutter_close = 1;
  int turning = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto key = [&] {
      return Transform::affine(Mat3::rotation(Vec3(u(rng), u(rng), u(rng)) + Vec3(0.01), u(rng) * 89) *
                                   Mat3::scale(Vec3(1 + 0.5 * u(rng), 1 + 0.5 * u(rng), 1 + 0.5 * u(rng))),
                               Vec3(u(rng), u(rng), u(rng)) * 3);
    };
    const Affine post{Mat3::rotation(Vec3(1, 2, 3), 25) * Mat3::scale(Vec3(2, 1, 0.5)), Vec3(1, -2, 3)};
    const kernel::MovingMap m =
        moving_map(Motion::keyframes(key(), key()), camera, FileLoc{}, "box", trial % 2 == 0 ? &post : nullptr);
    turning += m.angle != 0;
    const Vec3 lo(u(rng) - 1, u(rng) - 1, u(rng) - 1), hi(u(rng) + 1, u(rng) + 1, u(rng) + 1);
    const std::string miss = test::swept_bounds_miss(m, lo, hi, {1, 2, 4, 8}, 40, rng);
    ASSERT_TRUE(miss.empty()) << "trial " << trial << ", " << miss;
  }
  EXPECT_GT(turning, 290);
}

// A velocity displaces the solid by velocity·τ at shutter time τ: a torus is met where the still
// torus with its centre displaced is, with the same normal.
TEST(MovingSolid, VelocityDisplacesTheSolid) {
  const Vec3 center(0.2, -0.1, -4), velocity(0.8, -0.3, 0.5), axis(0.3, 1, 0.2);
  const Real open = 0.5, close = 2;
  Scene moving;
  Torus torus(center, 0.6, 0.2, Material{}, axis);
  torus.motion = Motion::linear(velocity);
  moving.add(std::move(torus));
  moving.camera.shutter_open = open;
  moving.camera.shutter_close = close;
  const RenderScene rs = compile(moving);
  ASSERT_EQ(rs.moving_solids.size(), 1u);
  const SceneView v = rs.view();
  RayMaker rays;
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    Ray ray = rays.next(center + velocity * 1.2, 1);
    ray.time = open + ray.time * (close - open);
    Scene still;
    still.add(Torus(center + velocity * ray.time, 0.6, 0.2, Material{}, axis));
    const RenderScene rs_still = compile(still);
    const SceneView s = rs_still.view();
    const Hit hm = closest_hit(v, ray, 0, kInfinity), hs = closest_hit(s, ray, 0, kInfinity);
    ASSERT_EQ(hm.found(), hs.found()) << "ray " << i;
    if (!hm.found()) continue;
    ++hits;
    ASSERT_NEAR(hm.t, hs.t, 1e-9 * hs.t) << "ray " << i;
    ASSERT_TRUE(test::vec_near(surface_at(v, ray, hm).normal, surface_at(s, ray, hs).normal, 1e-9)) << "ray " << i;
  }
  EXPECT_GT(hits, 500);
}

// A sphere whose keys scale it unevenly is an ellipsoid that changes shape over the shutter: at
// each time it is met where the still sphere, placed by that time's map, is.
TEST(MovingSolid, SphereScaledUnevenlyByItsKeysIsAMovingEllipsoid) {
  const Vec3 center(0.2, -0.1, -4);
  Scene moving;
  Sphere sphere(center, 0.7, Material{});
  Transform from, to;
  from.scale = Vec3(1, 0.5, 1);
  to.scale = Vec3(2, 1.5, 0.75);
  to.translate = Vec3(0.5, 0, 0);
  sphere.motion = Motion::keyframes(from, to);
  moving.add(std::move(sphere));
  const RenderScene rs = compile(moving);
  ASSERT_EQ(rs.moving_solids.size(), 1u);
  const SceneView v = rs.view();
  RayMaker rays;
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Real u = Real(i % 7) / 6;  // the keys' linear parts blend linearly (no turn): scale(u)
    Ray ray = rays.next(Vec3(center.x * 1.5, center.y, center.z * 0.9), 1.5);
    ray.time = u;
    Scene still;
    Sphere s(center, 0.7, Material{});
    s.placement.scale = from.scale * (1 - u) + to.scale * u;
    s.placement.translate = to.translate * u;
    still.add(std::move(s));
    const RenderScene rs_still = compile(still);
    const SceneView w = rs_still.view();
    const Hit hm = closest_hit(v, ray, 0, kInfinity), hs = closest_hit(w, ray, 0, kInfinity);
    ASSERT_EQ(hm.found(), hs.found()) << "ray " << i;
    if (!hm.found()) continue;
    ++hits;
    ASSERT_NEAR(hm.t, hs.t, 1e-9 * hs.t) << "ray " << i;
    ASSERT_TRUE(test::vec_near(surface_at(v, ray, hm).normal, surface_at(w, ray, hs).normal, 1e-9)) << "ray " << i;
  }
  EXPECT_GT(hits, 300);
}

// Many solids of every kind, turning and travelling: the scene's query through the motion BVH
// (its boxes over what each solid sweeps per time segment) finds the nearest of the hits that
// testing every solid alone finds, and shadow rays count every crossing.
TEST(MovingSolid, MotionBvhFindsWhatEverySolidAloneFinds) {
  Scene s;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  Material glass;
  glass.transparency = 0.5;
  for (int i = 0; i < 60; ++i) {
    const Vec3 at(u(rng) * 2, u(rng) * 1.5, -5 + u(rng));
    std::unique_ptr<SceneObject> o;
    switch (i % 5) {
      case 0: o = std::make_unique<Box>(Vec3(-0.2, -0.15, -0.1), Vec3(0.2, 0.15, 0.1), glass); break;
      case 1: o = std::make_unique<Torus>(Vec3(0), 0.2, 0.06, glass, Vec3(u(rng), 1, u(rng))); break;
      case 2: o = std::make_unique<Cone>(Cone::cylinder({0, -0.2, 0}, {0, 0.2, 0}, 0.1, glass)); break;
      case 3: {
        auto e = std::make_unique<Sphere>(Vec3(0), 0.2, glass);
        e->placement.scale = Vec3(1, 0.5, 0.8);  // an ellipsoid
        o = std::move(e);
        break;
      }
      default: {
        std::vector<std::unique_ptr<SceneObject>> parts;
        parts.push_back(std::make_unique<Box>(Vec3(-0.2), Vec3(0.2), Material{}));
        parts.push_back(std::make_unique<Sphere>(Vec3(0.2, 0.2, 0.2), 0.2, Material{}));
        o = std::make_unique<Csg>(CsgOperation::Difference, std::move(parts), glass);
      }
    }
    o->motion = i % 3 == 0 ? Motion::linear(Vec3(u(rng), u(rng), u(rng)) * 0.6)
                           : Motion::keyframes(keyframe(Vec3(1), {0, 0, 0}, at),
                                               keyframe(Vec3(1 + u(rng) * 0.3), Vec3(u(rng), u(rng), u(rng)) * 80,
                                                        at + Vec3(u(rng), u(rng), u(rng)) * 0.4));
    if (i % 3 == 0) o->placement.translate = at;
    s.addSceneObject(o.release());
  }
  s.camera.shutter_open = 0;
  s.camera.shutter_close = 1;
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.moving_solids.size(), 60u);
  EXPECT_GT(rs.moving_bvh.segments, 1u) << "turning solids sweep large boxes: the build cuts the shutter";
  const SceneView v = rs.view();
  const kernel::SolidArrays shapes = rs.shapes();
  RayMaker rays;
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = rays.next({0, 0, -5}, 2.2);
    const Real u_time = shutter_fraction(v, ray.time);
    Real nearest = kInfinity;
    int crossings = 0;
    for (const kernel::MovingSolid& m : rs.moving_solids) {
      const Ray r = kernel::object_ray(kernel::at_time(m, u_time), ray);
      nearest = std::fmin(nearest, kernel::intersect(shapes, m.solid, r, 0, kInfinity).t);
      crossings += kernel::crossings(shapes, m.solid, r, 0, 100);
    }
    const Hit h = closest_hit(v, ray, 0, kInfinity);
    ASSERT_EQ(h.t, nearest) << "ray " << i;
    hits += h.found();
    ASSERT_EQ(transmittance(v, ray, 100).x, std::pow(Real(0.5), crossings)) << "ray " << i;
  }
  EXPECT_GT(hits, 2000);
}

TEST(MovingSolid, ZeroLengthShutterFreezesTheSolidAtOpen) {
  Scene s;
  Box box({-0.5, -0.5, -5.5}, {0.5, 0.5, -4.5}, test::emissive_like(Vec3(1)));
  box.motion = Motion::linear({10, 0, 0});
  s.add(std::move(box));
  test::one_ray_camera(s, {0, 0, 0}, {1, 0, -5});
  s.camera.shutter_open = s.camera.shutter_close = 0.1;  // the box sits at x = 1
  EXPECT_EQ(test::pixel(s), Vec3(1));
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -5});
  s.camera.shutter_open = s.camera.shutter_close = 0.1;
  EXPECT_EQ(test::pixel(s), Vec3(0));
}

TEST(MovingSolid, SceneKeysAndErrors) {
  // Every solid takes `motion`, as does the outermost CSG node and an ellipsoid.
  const std::string ok = R"(
objects:
  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {velocity: [1, 0, 0]}}
  - {type: cylinder, base: [0, 0, 0], cap: [0, 1, 0], radius: 0.5, motion: {to: {rotate: [0, 0, 30]}}}
  - {type: cone, base: [0, 0, 0], cap: [0, 1, 0], base_radius: 0.5, cap_radius: 0, motion: {velocity: [0, 1, 0]}}
  - {type: disk, center: [0, 0, 0], normal: [0, 1, 0], radius: 1, motion: {velocity: [0, 1, 0]}}
  - {type: torus, center: [0, 0, 0], major_radius: 1, minor_radius: 0.2, motion: {to: {scale: [1, 2, 1]}}}
  - {type: quadric, coefficients: [1, 1, 1, 0, 0, 0, 0, 0, 0, -1], clipped_by: {type: box, corners: [[-1, -1, -1], [1, 1, 1]]}, motion: {velocity: [1, 0, 0]}}
  - {type: implicit, expression: "x^2 + y^2 + z^2 - 1", contained_by: {type: sphere, center: [0, 0, 0], radius: 2}, motion: {velocity: [1, 0, 0]}}
  - {type: sphere, center: [0, 0, 0], radius: 1, scale: [1, 2, 1], motion: {velocity: [1, 0, 0]}}
  - {type: union, objects: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}, {type: sphere, center: [0, 0, 0], radius: 1}], motion: {velocity: [1, 0, 0]}}
)";
  const RenderScene rs = compile(parse_scene(ok, "ok.yaml", "."));
  EXPECT_EQ(rs.moving_solids.size(), 9u);
  EXPECT_TRUE(rs.solids.empty());
  EXPECT_EQ(test::compile_error("objects:\n  - {type: quadric, coefficients: [1, 1, 0, 0, 0, 0, 0, 0, 0, -1], motion: {velocity: "
                     "[1, 0, 0]}}\n"),
            "bad.yaml:2:5: a solid without bounds cannot move (an unclipped quadric, or a CSG tree around an inverse: "
            "clip it, or intersect it with a box)");
  EXPECT_EQ(test::compile_error("objects:\n  - type: union\n    objects:\n      - {type: box, corners: [[0, 0, 0], [1, 1, 1]], "
                     "motion: {velocity: [1, 0, 0]}}\n"),
            "bad.yaml:4:9: an operand of union cannot move on its own (give the motion to the outermost CSG node)");
  EXPECT_NE(test::compile_error("objects:\n  - type: union\n    objects:\n      - {type: intersection, objects: [{type: box, corners: "
                     "[[0, 0, 0], [1, 1, 1]]}], motion: {velocity: [1, 0, 0]}}\n")
                .find("bad.yaml:4:"),
            std::string::npos);
  // Keyframes a half turn apart leave open which way the solid turns; other turns take the shorter
  // way (200° moves as −160° does).
  const std::string turn = "objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {to: {rotate: [0, ";
  EXPECT_EQ(test::compile_error(turn + "180, 0]}}}\n"),
            "bad.yaml:2:5: the keyframes of the solid are a half turn apart, so which way it turns is open: turn it by "
            "less within the shutter, or give the turn as a spin");
  EXPECT_NE(test::compile_error(turn + "540, 0]}}}\n").find("half turn"), std::string::npos);
  EXPECT_EQ(test::compile_error(turn + "90, 0]}}}\n"), "no error");
  EXPECT_EQ(test::compile_error(turn + "179, 0]}}}\n"), "no error");
  EXPECT_EQ(test::compile_error(turn + "200, 0]}}}\n"), "no error");
  // Instances move too, under the same rule.
  const std::string group = "groups:\n  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}]\nobjects:\n";
  EXPECT_EQ(test::compile_error(group + "  - {type: instance, of: g, motion: {velocity: [1, 0, 0]}}\n"), "no error");
  EXPECT_NE(test::compile_error(group + "  - {type: instance, of: g, motion: {to: {rotate: [180, 0, 0]}}}\n")
                .find("bad.yaml:4:5: the keyframes of the instance are a half turn apart"),
            std::string::npos);
  // A group keeps only still shapes: a moving solid in it is refused, not dropped, and a moving
  // instance in it is a nested instance.
  EXPECT_EQ(test::compile_error("groups:\n  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {velocity: [1, 0, 0]}}]\n"
                     "objects:\n  - {type: instance, of: g}\n"),
            "no error");  // a group's moving shape (tests/instance_test.cpp)
  EXPECT_EQ(test::compile_error("groups:\n  g: [{type: sphere, center: [0, 0, 0], radius: 1, scale: [1, 2, 1], motion: {velocity: "
                     "[1, 0, 0]}}]\nobjects:\n  - {type: instance, of: g}\n"),
            "no error");  // a group's moving shape (tests/instance_test.cpp)
  EXPECT_EQ(test::compile_error("groups:\n  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}]\n  h: [{type: instance, of: g, "
                     "motion: {velocity: [1, 0, 0]}}]\nobjects:\n  - {type: instance, of: h, motion: {spin: {axis: [0, 1, 0], angle: 10}}}\n"),
            "no error");  // two motions compose (tests/instance_test.cpp); a third that turns is refused there
  // A scale changing sign on one axis passes through 0 there.
  EXPECT_NE(test::compile_error("objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {to: {scale: [1, -1, 1]}}}\n")
                .find("flattens"),
            std::string::npos);
}

// A keyframe is any transform, as a placement is: a matrix, a transform list, an axis-and-angle
// rotation. A sphere's must keep it a sphere (a similarity); its radius scales with it.
TEST(MovingSolid, KeyframesTakeAnyTransform) {
  const RenderScene rs = compile(parse_scene(R"(
objects:
  - type: box
    corners: [[0, 0, 0], [1, 1, 1]]
    motion:
      from: {matrix: [[1, 0.5, 0, 1], [0, 1, 0, 2], [0, 0, 2, 3]]}
      to: {transform: [{scale: 2}, {rotate: {axis: [0, 0, 1], angle: 30}}, {translate: [1, 0, 0]}]}
  - {type: sphere, center: [1, 0, 0], radius: 1, motion: {to: {rotate: {axis: [1, 1, 0], angle: 40}, scale: 3}}}
)",
                                             "ok.yaml", "."));
  // (the sphere turns: it moves as a solid sphere, its centre on an arc)
  ASSERT_EQ(rs.moving_solids.size(), 2u);
  ASSERT_TRUE(rs.moving_spheres.empty());
  const kernel::MovingMap& m = rs.moving_solids[0].map;
  const Mat3 from{{Vec3(1, 0.5, 0), Vec3(0, 1, 0), Vec3(0, 0, 2)}};
  const Mat3 to = Mat3::rotation(Vec3(0, 0, 1), 30) * Mat3::scale(Vec3(2));
  for (const Vec3& p : {Vec3(0), Vec3(1, 0, 0), Vec3(0.3, -2, 5)}) {
    EXPECT_EQ(kernel::moved_point(m, p, 0), from * p + Vec3(1, 2, 3));
    EXPECT_TRUE(test::vec_near(kernel::moved_point(m, p, 1), to * p + Vec3(1, 0, 0), 1e-12));
  }
  const kernel::MovingMap& s = rs.moving_solids[1].map;
  const Vec3 c1 = kernel::moved_point(s, Vec3(1, 0, 0), 1), rim = kernel::moved_point(s, Vec3(2, 0, 0), 1);
  EXPECT_TRUE(test::vec_near(c1, Mat3::rotation(Vec3(1, 1, 0), 40) * Vec3(3, 0, 0), 1e-12));
  EXPECT_NEAR(length(rim - c1), 3, 1e-12);  // the radius scaled by 3
  EXPECT_EQ(test::compile_error("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, motion: {to: {matrix: [[1, 0.1, 0], "
                     "[0, 1, 0], [0, 0, 1]]}}}\n"),
            "no error");  // a sheared sphere: a moving ellipsoid
  EXPECT_NE(test::compile_error("objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {to: {matrix: [[1, 0, 0], "
                     "[0, 1, 0]]}}}\n")
                .find("bad.yaml:2:"),
            std::string::npos);
}

// A scene of moving solids is written with their motions and reads back to the same scene.
TEST(MovingSolid, WrittenAndReadBack) {
  const std::string text = R"(
camera: {shutter: [0, 1]}
objects:
  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], rotate: [0, 30, 0], motion: {velocity: [1, 0, 0]}}
  - {type: torus, center: [0, 0, 0], major_radius: 1, minor_radius: 0.2, motion: {from: {translate: [0, 1, 0]}, to: {rotate: [0, 0, 30]}}}
  - {type: difference, objects: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}, {type: sphere, center: [1, 1, 1], radius: 0.5}], motion: {velocity: [0, 0, 1]}}
  - {type: instance, of: g, translate: [2, 0, 0], motion: {from: {rotate: [0, 10, 0]}, to: {translate: [0, 1, 0]}}}
  - {type: cone, base: [0, 0, 0], cap: [0, 1, 0], base_radius: 1, cap_radius: 0, motion: {from: {matrix: [[1, 0.25, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.125]]}, to: {rotate: {axis: [1, 2, 3], angle: 20}}}}
  - {type: sphere, center: [3, 0, 0], radius: 1, motion: {to: {transform: [{rotate: {axis: [1, 1, 0], angle: 40}}, {scale: 3}]}}}
  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], motion: {to: {rotate: [0, 0, 40]}}}
groups:
  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}]
)";
  const Scene a = parse_scene(text, "a.yaml", ".");
  const Scene b = parse_scene(scene_to_yaml(a), "b.yaml", ".");
  const RenderScene ra = compile(a), rb = compile(b);
  ASSERT_EQ(ra.moving_solids.size(), 5u);  // (the sphere turns: a solid sphere)
  ASSERT_EQ(ra.moving_instances.size(), 2u);  // (the turning triangle: an instance of itself)
  EXPECT_NE(scene_to_yaml(a).find("to: {matrix: [["), std::string::npos);
  EXPECT_EQ(scene_hash(ra), scene_hash(rb));
}

}  // namespace
}  // namespace strahl::moving_solid_test
