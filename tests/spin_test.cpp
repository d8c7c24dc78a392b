// Spins (scene/scene.h Spin; geometry/moving_map.h): an object spinning by θ about the line
// along `axis` through `center`, carried by a velocity or by keyframes, is at shutter fraction u
// the still object turned by u·θ about that line, then moved — for any θ, several turns too; its
// swept boxes hold it at every time; the map's inverse undoes it; and the scene keys, errors and
// written scene files say so.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/scene_hash.h"
#include "strahl/render/surface_point.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "strahl/scene/solids.h"
#include "swept_bounds_check.h"
#include "test_helpers.h"

namespace strahl::spin_test {
namespace {

Camera shutter(Real open, Real close) {
  Camera c;
  c.shutter_open = open;
  c.shutter_close = close;
  return c;
}

// Where the spin and the motion put the object's point x at shutter fraction u: turned by u·θ about
// the spin's line, then moved by the motion (a velocity, or keys that scale and translate, blended).
Vec3 spun(const Motion& m, const Camera& cam, const Vec3& x, Real u) {
  const Vec3 p = m.spin().center;
  const Vec3 turned = Mat3::rotation(m.spin().axis, u * m.spin().angle) * (x - p);
  switch (m.kind) {
    case Motion::Kind::Velocity:
      return turned + p + m.velocity() * (cam.shutter_open + u * (cam.shutter_close - cam.shutter_open));
    case Motion::Kind::Keyframes: {
      // The keys' blend carries the centre; the turn acts on the blended linear part's image.
      const Mat3 l0 = m.from().linear(), l1 = m.to().linear();
      Mat3 l;
      for (int i = 0; i < 3; ++i) l.row[i] = l0.row[i] * (1 - u) + l1.row[i] * u;
      const Vec3 centre = l * p + m.from().translate * (1 - u) + m.to().translate * u;
      return Mat3::rotation(m.spin().axis, u * m.spin().angle) * (l * (x - p)) + centre;
    }
    case Motion::Kind::None: break;
  }
  return turned + p;
}

Motion motion_of(int kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<Real> s(-1, 1);
  const Spin spin{Vec3(s(rng), s(rng), s(rng)) + Vec3(0.01), s(rng) * 1800, Vec3(s(rng), s(rng), s(rng))};
  if (kind == 0) return Motion::spinning(spin);
  if (kind == 1) return Motion::linear(Vec3(s(rng), s(rng), s(rng))).with_spin(spin);
  Transform from, to;  // keys that scale and translate, with the same rotation
  from.scale = Vec3(1 + 0.3 * s(rng), 1 + 0.3 * s(rng), 1 + 0.3 * s(rng));
  to.scale = Vec3(1 + 0.3 * s(rng), 1 + 0.3 * s(rng), 1 + 0.3 * s(rng));
  from.rotate_degrees = to.rotate_degrees = Vec3(s(rng), s(rng), s(rng)) * 60;
  from.translate = Vec3(s(rng), s(rng), s(rng));
  to.translate = Vec3(s(rng), s(rng), s(rng));
  return Motion::keyframes(from, to).with_spin(spin);
}

// The map is the spin followed by the motion (and a post map, where given), at every time (five
// turns either way), and its inverse (the placement at_time gives) undoes it; the spin's centre goes where the motion takes it (and
// with a velocity, every point on the spin's line).
TEST(Spin, MapIsTheTurnAboutTheLineThenTheMotion) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> s(-1, 1), f(0, 1);
  const Camera cam = shutter(0.25, 1.5);
  for (int trial = 0; trial < 300; ++trial) {
    const Motion motion = motion_of(trial % 3, rng);
    const Motion unturned = motion.with_spin({motion.spin().axis, 0, motion.spin().center});
    // (every other map followed by a post map, as a mesh's motion is by its transform)
    const Affine post{Mat3::rotation(Vec3(1, -2, 1), 35) * Mat3::scale(Vec3(1.5, 1, 0.75)), Vec3(-1, 2, 0.5)};
    const bool posted = trial % 2 == 1;
    const auto after = [&](const Vec3& p) { return posted ? post.m * p + post.t : p; };
    const kernel::MovingMap m = moving_map(motion, cam, FileLoc{}, "box", posted ? &post : nullptr);
    ASSERT_EQ(m.pivot, 1u);
    EXPECT_EQ(m.angle, motion.spin().angle * kPi / 180);
    for (int i = 0; i < 20; ++i) {
      const Vec3 x = Vec3(s(rng), s(rng), s(rng)) * 2;
      const Real u = i == 0 ? 0 : i == 1 ? 1 : f(rng);
      const Vec3 q = kernel::moved_point(m, x, u);
      ASSERT_TRUE(test::vec_near(q, after(spun(motion, cam, x, u)), 1e-12)) << "trial " << trial << " at " << u;
      ASSERT_TRUE(test::vec_near(kernel::object_point(kernel::at_time(m, u), q), x, 1e-12)) << "trial " << trial;
      // (keys that scale take the line's direction away from the axis: their centre is on it)
      const Vec3 on_line =
          motion.spin().center + normalize(motion.spin().axis) * (motion.kind == Motion::Kind::Keyframes ? 0 : s(rng));
      ASSERT_TRUE(test::vec_near(kernel::moved_point(m, on_line, u), after(spun(unturned, cam, on_line, u)), 1e-12))
          << "trial " << trial;
    }
  }
}

// At shutter open the object is where it is written; whole turns bring it back at close.
TEST(Spin, WholeTurnsEndWhereTheyBegan) {
  const Camera cam = shutter(0, 1);
  for (const Real turns : {1.0, 3.0, -2.0}) {
    const Motion motion = Motion::spinning({Vec3(1, 2, -0.5), 360 * turns, Vec3(0.5, -1, 2)});
    const kernel::MovingMap m = moving_map(motion, cam, FileLoc{}, "box");
    for (const Vec3& x : {Vec3(0), Vec3(1, 0, 0), Vec3(-3, 2, 0.25)}) {
      EXPECT_EQ(kernel::moved_point(m, x, 0), x);
      EXPECT_TRUE(test::vec_near(kernel::moved_point(m, x, 1), x, 1e-13)) << turns;
      // half way: turned by half of it (a half turn where the turns are odd)
      EXPECT_TRUE(test::vec_near(kernel::moved_point(m, x, 0.5), spun(motion, cam, x, 0.5), 1e-13));
    }
  }
  // A spin by 0 is no motion.
  EXPECT_FALSE(Motion::spinning({Vec3(0, 0, 1), 0, Vec3(1)}).moving());
}

// The box swept over a segment of the shutter holds the box's points at every time of it: spins of
// up to five turns either way, alone, with a velocity, with keys that scale, with a post map, for
// the segments the motion BVH cuts (a segment turning by several turns, by less than one, by a sliver).
TEST(Spin, SweptBoundsHoldEveryTime) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<Real> s(-1, 1);
  const Camera cam = shutter(0, 1);
  const Affine post{Mat3::rotation(Vec3(1, 2, 3), 25) * Mat3::scale(Vec3(2, 1, 0.5)), Vec3(1, -2, 3)};
  for (int trial = 0; trial < 200; ++trial) {
    const kernel::MovingMap m = moving_map(motion_of(trial % 3, rng), cam, FileLoc{}, "box", trial % 2 ? &post : nullptr);
    const Vec3 lo(s(rng) - 1, s(rng) - 1, s(rng) - 1), hi(s(rng) + 1, s(rng) + 1, s(rng) + 1);
    const std::string miss = test::swept_bounds_miss(m, lo, hi, {1, 3, 16, 64}, 30, rng);
    ASSERT_TRUE(miss.empty()) << "trial " << trial << ", " << miss;
  }
}

// A spinning box, a spinning sphere off its axis and a spinning mesh (an instance of itself) are met
// where the still shapes, turned and moved to the ray's time, are: same distance, same normal.
TEST(Spin, SpinningShapesAreTheStillShapesTurned) {
  const Camera cam = shutter(0, 1);
  const Motion motion = Motion::linear(Vec3(0.4, 0, 0)).with_spin({Vec3(0.2, 1, 0.1), 900, Vec3(0.1, 0, -4)});
  const auto place = [&](Real u) {
    const Mat3 r = Mat3::rotation(motion.spin().axis, u * motion.spin().angle);
    return Transform::affine(r, motion.spin().center - r * motion.spin().center + motion.velocity() * u);
  };
  const Vec3 lo(-0.6, -0.3, -4.2), hi(0.7, 0.4, -3.9);
  for (int shape = 0; shape < 3; ++shape) {
    const auto add = [&](Scene& scene, const Motion& m, const Transform& placement) {
      if (shape == 0) {
        Box b(lo, hi, Material{});
        b.motion = m;
        b.placement = placement;
        scene.add(std::move(b));
      } else if (shape == 1) {
        Sphere sp(Vec3(0.5, 0.2, -4.1), 0.3, Material{});
        sp.motion = m;
        sp.placement = placement;
        scene.add(std::move(sp));
      } else {
        MeshData d;
        d.positions = {lo, Vec3(hi.x, lo.y, lo.z), Vec3(lo.x, hi.y, hi.z), hi};
        d.faces.resize(2);
        d.faces[0].v = {0, 1, 2};
        d.faces[1].v = {1, 3, 2};
        Mesh mesh(std::move(d), Material{});
        mesh.motion = m;
        mesh.transform = placement;
        scene.add(std::move(mesh));
      }
    };
    Scene moving;
    moving.camera.shutter_open = cam.shutter_open;
    moving.camera.shutter_close = cam.shutter_close;
    add(moving, motion, Transform{});
    const RenderScene rs = compile(moving);
    EXPECT_EQ(rs.moving_solids.size() + rs.moving_instances.size(), 1u);
    const SceneView v = rs.view();
    std::mt19937_64 rng(shape + 1);
    std::uniform_real_distribution<Real> s(-1, 1), f(0, 1);
    int hits = 0;
    for (int i = 0; i < 1500; ++i) {
      const Real u = f(rng);
      const Vec3 origin(s(rng) * 0.3, s(rng) * 0.3, 0);
      const Ray ray{origin, normalize(Vec3(0.2, 0, -4) + Vec3(s(rng), s(rng), s(rng)) * 0.9 - origin), u};
      Scene still;
      add(still, Motion{}, place(u));
      const RenderScene rs_still = compile(still);
      const SceneView w = rs_still.view();
      const Hit a = closest_hit(v, ray, 0, kInfinity), b = closest_hit(w, ray, 0, kInfinity);
      ASSERT_EQ(a.found(), b.found()) << "shape " << shape << ", ray " << i << " at time " << u;
      if (!a.found()) continue;
      ++hits;
      ASSERT_NEAR(a.t, b.t, 1e-11 * b.t) << "shape " << shape << ", ray " << i;
      ASSERT_TRUE(test::vec_near(surface_at(v, ray, a).normal, surface_at(w, ray, b).normal, 1e-10))
          << "shape " << shape << ", ray " << i;
    }
    EXPECT_GT(hits, 100) << "shape " << shape;
  }
}

TEST(Spin, SceneKeysAndErrors) {
  const RenderScene rs = compile(parse_scene(R"(
camera: {shutter: [0, 1]}
groups:
  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}]
objects:
  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 1, 0], angle: 720}}}
  - {type: sphere, center: [2, 0, 0], radius: 1, motion: {velocity: [1, 0, 0], spin: {axis: [0, 1, 0], angle: 90, center: [0, 0, 0]}}}
  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], motion: {spin: {axis: [0, 0, 1], angle: -400}}}
  - {type: instance, of: g, motion: {from: {translate: [0, 1, 0]}, to: {scale: 2}, spin: {axis: [1, 0, 0], angle: 180, center: [0.5, 0.5, 0.5]}}}
  - {type: sphere, center: [0, 5, 0], radius: 1, motion: {spin: {axis: [0, 1, 0], angle: 0}}}
)",
                                             "ok.yaml", "."));
  EXPECT_EQ(rs.moving_solids.size(), 2u);     // the box, the sphere (off its axis: it circles)
  EXPECT_EQ(rs.moving_instances.size(), 2u);  // the triangle (an instance of itself), the instance
  EXPECT_EQ(rs.spheres.size(), 1u);           // a spin by 0 stands still
  const kernel::MovingMap& m = rs.moving_solids[1].map;
  EXPECT_TRUE(test::vec_near(kernel::moved_point(m, Vec3(2, 0, 0), 1), Vec3(1, 0, -2), 1e-15));
  EXPECT_EQ(test::compile_error("objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 0, 0], "
                     "angle: 90}}}\n"),
            "bad.yaml:2:72: spin axis must not be zero");
  EXPECT_EQ(test::compile_error("objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 1, 0]}}}\n"),
            "bad.yaml:2:65: motion spin needs 'angle'");
  EXPECT_NE(test::compile_error("objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 1, 0], "
                     "angle: 9, speed: 1}}}\n")
                .find("bad.yaml:2:"),
            std::string::npos);
  // The keyframes may scale and translate, but the turn is the spin's alone.
  EXPECT_EQ(test::compile_error("objects:\n  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {to: {rotate: [0, 30, 0]}, "
                     "spin: {axis: [0, 1, 0], angle: 90}}}\n"),
            "bad.yaml:2:5: the keyframes of the solid turn, and so does its spin: give the keyframes the same rotation "
            "and the whole turn to the spin");
  EXPECT_EQ(test::compile_error("groups:\n  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 1, 0], "
                     "angle: 90}}}]\nobjects:\n  - {type: instance, of: g}\n"),
            "no error");  // a group's moving shape (tests/instance_test.cpp)
  EXPECT_NE(test::compile_error("objects:\n  - {type: plane, normal: [0, 1, 0], distance: 0, motion: {spin: {axis: [0, 1, 0], "
                     "angle: 90}}}\n"),
            "no error");
}

// A moving instance's shift (the largest coordinate its map's translation reaches, which sizes its
// hits' ray offsets) holds at every time, where a spin about a far centre swings the group's
// origin twice that far out.
TEST(Spin, InstanceShiftHoldsAtEveryTime) {
  const RenderScene rs = compile(parse_scene(R"(
groups:
  g: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}]
objects:
  - {type: instance, of: g, translate: [3, 0, 0], motion: {velocity: [0, 1, 0], spin: {axis: [0, 0, 1], angle: 300, center: [100, 0, 0]}}}
)",
                                             "ok.yaml", "."));
  ASSERT_EQ(rs.moving_instances.size(), 1u);
  const kernel::MovingInstance& mi = rs.moving_instances[0];
  Real reached = 0;
  for (int i = 0; i <= 100; ++i)
    reached = std::fmax(reached, max_abs_component(kernel::moved_point(mi.map, mi.instance.to_object.translate, i / 100.0)));
  EXPECT_GT(reached, 190);
  EXPECT_GE(mi.shift, reached);
}

// A scene with spins is written with them and reads back to the same scene, bit for bit.
TEST(Spin, WrittenAndReadBack) {
  const Scene a = parse_scene(R"(
camera: {shutter: [0, 1]}
objects:
  - {type: torus, center: [0, 0, 0], major_radius: 1, minor_radius: 0.2, motion: {spin: {axis: [0, 1, 0.1], angle: 1234.5, center: [0.1, 0, 0]}}}
  - {type: sphere, center: [3, 0, 0], radius: 1, motion: {velocity: [0, 0, 1], spin: {axis: [0, 1, 0], angle: -90}}}
  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {from: {translate: [0, 1, 0]}, to: {scale: 2}, spin: {axis: [1, 0, 0], angle: 30}}}
)",
                              "a.yaml", ".");
  const std::string text = scene_to_yaml(a);
  EXPECT_NE(text.find("spin: {axis: [0, 1, 0.1], angle: 1234.5, center: [0.1, 0, 0]}"), std::string::npos) << text;
  const Scene b = parse_scene(text, "b.yaml", ".");
  EXPECT_EQ(scene_hash(compile(a)), scene_hash(compile(b)));
  EXPECT_EQ(compile(a).moving_solids.size(), 3u);
}

}  // namespace
}  // namespace strahl::spin_test
