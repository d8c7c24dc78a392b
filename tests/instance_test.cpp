// Instances (docs/scene-format.md, "Instances"; scene/instances.h, render/instance_queries.h):
// an instance with the identity transform renders the same image, bit for bit, as its group's
// objects written in place; a transformed instance agrees with the same objects with the same
// transform written on each (hit t, normals, shadow rays through opaque and transparent
// objects, CSG), for every accelerator; the group's geometry is held once however many
// instances place it. Nested instances (a group placing earlier groups) are unfolded into one
// record per group reached: the same bits as those records written at one level, and the objects
// where both transforms in turn put them.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/render/surface_point.h"
#include "strahl/render/scene_hash.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "test_helpers.h"
#include "test_random.h"

namespace strahl::instance_test {
namespace {

const std::string kHead =
    "camera: {position: [0, 2, 7], look_at: [0, 0.5, 0], fov: 45}\n"
    "render: {width: 48, height: 32, max_depth: 4}\n"
    "materials:\n"
    "  red: {color: [0.9, 0.2, 0.1], reflectivity: 0.3}\n"
    "  glass: {color: [0.6, 0.9, 1], transparency: 0.7, ior: 1.4, filter: true}\n"
    "lights:\n  - {type: point, position: [3, 5, 4]}\n  - {type: point, position: [-4, 3, 2], intensity: 0.5}\n";

// The objects of the group, each line an element of a list at the given indentation, with
// `extra` (a transform) added to every object's map.
std::string group_objects(const std::string& indent, const std::string& extra) {
  const char* objects[] = {
      "{type: sphere, center: [-1, 0.5, 0], radius: 0.5, material: red",
      "{type: box, corners: [[0.2, 0, -0.4], [1, 0.8, 0.4]], material: glass",
      "{type: triangle, vertices: [[-2, 0, -1], [2, 0, -1], [0, 2, -1.5]]",
      "{type: difference, material: red, objects: [{type: sphere, center: [0, 1.6, 0.5], radius: 0.4}, "
      "{type: cylinder, base: [0, 1.6, 0], cap: [0, 1.6, 1], radius: 0.2}]",
      "{type: torus, center: [1.6, 0.3, 0.8], major_radius: 0.3, minor_radius: 0.1, material: glass",
  };
  std::string s;
  for (const char* o : objects) s += indent + "- " + o + (extra.empty() ? "" : ", " + extra) + "}\n";
  return s;
}

const std::string kFloor = "  - {type: plane, normal: [0, 1, 0], distance: -0.5}\n";

RenderScene direct(const std::string& extra, AccelKind accel = AccelKind::Bvh) {
  Scene s = parse_scene(kHead + "objects:\n" + kFloor + group_objects("  ", extra), "direct.yaml", ".");
  s.settings.accel = accel;
  return compile(s);
}
RenderScene instanced(const std::string& transform, AccelKind accel = AccelKind::Bvh) {
  Scene s = parse_scene(kHead + "groups:\n  g:\n" + group_objects("    ", "") + "objects:\n" + kFloor +
                            "  - {type: instance, of: g" + (transform.empty() ? "" : ", " + transform) + "}\n",
                        "instanced.yaml", ".");
  s.settings.accel = accel;
  return compile(s);
}

Image render_of(const RenderScene& rs) {
  RenderOptions o;
  o.threads = 2;
  return render(rs, o);
}


struct Compared {
  int rays = 0, both = 0, disagree = 0;
  Real max_t = 0, max_normal = 0;
  int shadowed = 0, shadow_disagree = 0;  // compare_in_time: the rays' transmittance over 16 units
};

// Nearest hits along random rays towards the objects, and their surface normals.
Compared compare(const RenderScene& x, const RenderScene& y, std::uint64_t seed) {
  const SceneView vx = x.view(), vy = y.view();
  test::Random rng(seed);
  Compared c;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 o = Vec3(0, 0.8, 0) + rng.direction() * 8;
    const Ray ray{o, normalize(Vec3(0, 0.8, 0) + rng.point(-2.5, 2.5) - o)};
    const Hit hx = closest_hit(vx, ray, 0, kInfinity), hy = closest_hit(vy, ray, 0, kInfinity);
    ++c.rays;
    if (hx.found() != hy.found() || (hx.found() && std::fabs(hx.t - hy.t) > 1e-6 * hx.t)) {
      ++c.disagree;  // a grazing ray may pass on either side of an edge
      continue;
    }
    if (!hx.found()) continue;
    ++c.both;
    c.max_t = std::fmax(c.max_t, std::fabs(hx.t - hy.t) / hx.t);
    const SurfacePoint sx = surface_at(vx, ray, hx), sy = surface_at(vy, ray, hy);
    c.max_normal = std::fmax(c.max_normal, length(sx.normal - sy.normal));
    c.max_normal = std::fmax(c.max_normal, length(sx.geometric_normal - sy.geometric_normal));
    EXPECT_EQ(x.materials[sx.material].color, y.materials[sy.material].color);  // (the indices differ)
    EXPECT_EQ(x.materials[sx.material].transparency, y.materials[sy.material].transparency);
  }
  return c;
}

TEST(Instance, IdentityInstanceRendersTheSameBitsAsItsObjects) {
  const RenderScene a = direct(""), b = instanced("");
  ASSERT_EQ(b.instances.size(), 1u);
  ASSERT_TRUE(b.triangles.empty());
  ASSERT_TRUE(b.spheres.empty());
  const Image ia = render_of(a), ib = render_of(b);
  EXPECT_TRUE(ia == ib) << "max difference " << test::max_abs_diff(ia, ib);
  // And it is not a blank picture that would agree with anything.
  EXPECT_GT(test::max_abs_diff(ia, render_of(direct("translate: [0.05, 0, 0]"))), 0.1);
  // The image is float: the hits themselves, in double, are the same bits too.
  const Compared c = compare(a, b, 5);
  EXPECT_GT(c.both, 1000);
  EXPECT_EQ(c.disagree, 0);
  EXPECT_EQ(c.max_t, 0);
  EXPECT_EQ(c.max_normal, 0);
}

TEST(Instance, TransformedInstanceEqualsTheObjectsTransformedInPlace) {
  for (const char* t : {"translate: [0.3, -0.2, 0.7]", "rotate: {axis: [1, 2, 0.5], angle: 37}",
                        "transform: [{scale: [1.5, 0.7, 1.2]}, {rotate: [10, 20, 30]}, {translate: [0.1, 0.2, -0.3]}]",
                        "scale: [-1, 1, 1]", "matrix: [[1, 0.3, 0, 0.2], [0, 1, 0, 0], [0.1, 0, 0.8, -0.1]]"}) {
    const Compared c = compare(direct(t), instanced(t), 7);
    EXPECT_GT(c.both, 1000) << t;
    EXPECT_LE(c.disagree, 4) << t;
    EXPECT_LT(c.max_t, 1e-9) << t;
    EXPECT_LT(c.max_normal, 1e-7) << t;
  }
}

// Many instances, overlapping: their BVH (an 8-wide tree over their boxes, with nodes) finds
// what the same objects placed one by one find.
TEST(Instance, ManyInstancesFindWhatTheirObjectsFind) {
  std::string objects, instances;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const std::string t = "translate: [" + std::to_string(0.7 * (i - 2.5)) + ", " + std::to_string(0.25 * j) + ", " +
                            std::to_string(-0.8 * (j - 2.5)) + "]";
      objects += group_objects("  ", t);
      instances += "  - {type: instance, of: g, " + t + "}\n";
    }
  const RenderScene direct_scene = compile(parse_scene(kHead + "objects:\n" + kFloor + objects, "direct.yaml", "."));
  const RenderScene instanced_scene = compile(parse_scene(
      kHead + "groups:\n  g:\n" + group_objects("    ", "") + "objects:\n" + kFloor + instances, "instanced.yaml", "."));
  ASSERT_EQ(instanced_scene.instances.size(), 36u);
  ASSERT_FALSE(instanced_scene.instance_bvh.nodes.empty());
  const Compared c = compare(direct_scene, instanced_scene, 13);
  EXPECT_GT(c.both, 2000);
  EXPECT_LE(c.disagree, 4);
  EXPECT_LT(c.max_t, 1e-9);
  EXPECT_LT(c.max_normal, 1e-7);
}

TEST(Instance, EveryAcceleratorAgrees) {
  const std::string t = "transform: [{rotate: {axis: [0, 1, 0], angle: 25}}, {scale: 1.3}, {translate: [0.2, 0, 0]}]";
  const RenderScene reference = instanced(t, AccelKind::Bvh);
  for (AccelKind k : {AccelKind::Naive, AccelKind::KdTree, AccelKind::Octree}) {
    const Compared c = compare(reference, instanced(t, k), 11);
    EXPECT_EQ(c.disagree, 0) << accel_name(k);
    EXPECT_LT(c.max_t, 1e-12) << accel_name(k);
  }
}

TEST(Instance, ShadowRaysSeeInstancesAsTheObjects) {
  const std::string t = "transform: [{rotate: [0, 40, 0]}, {translate: [0.1, 0, 0.2]}]";
  const RenderScene x = direct(t), y = instanced(t);
  const SceneView vx = x.view(), vy = y.view();
  ASSERT_FALSE(vx.opaque);  // glass: crossings are counted, not just any hit
  test::Random rng(3);
  int blocked = 0, tinted = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 from = rng.point(-2, 2) + Vec3(0, 0.8, 0), to = rng.point(-2, 2) * 3 + Vec3(0, 4, 0);
    const Real d = length(to - from);
    const Ray ray{from, (to - from) / d};
    const Vec3 a = transmittance(vx, ray, d), b = transmittance(vy, ray, d);
    EXPECT_NEAR(a.x, b.x, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);
    EXPECT_NEAR(a.z, b.z, 1e-12);
    blocked += a == Vec3(0);
    tinted += a.x > 0 && a.x < 1;
  }
  EXPECT_GT(blocked, 100);
  EXPECT_GT(tinted, 50);
  // All opaque: the any-hit path.
  const std::string opaque_group =
      "groups:\n  g:\n    - {type: box, corners: [[-1, 0, -1], [1, 1, 1]]}\nobjects:\n"
      "  - {type: instance, of: g, translate: [0, 2, 0]}\n";
  const RenderScene o = compile(parse_scene(kHead + opaque_group, "o.yaml", "."));
  ASSERT_TRUE(o.view().opaque);
  EXPECT_EQ(transmittance(o.view(), Ray{{0, 0, 0}, {0, 1, 0}}, 10), Vec3(0));
  EXPECT_EQ(transmittance(o.view(), Ray{{0, 0, 0}, {0, 1, 0}}, 1.5), Vec3(1));
  EXPECT_EQ(transmittance(o.view(), Ray{{3, 0, 0}, {0, 1, 0}}, 10), Vec3(1));
}

TEST(Instance, TheGroupIsHeldOnce) {
  std::string objects;
  for (int i = 0; i < 500; ++i)
    objects += "  - {type: instance, of: g, transform: [{rotate: {axis: [0, 1, 0], angle: " + std::to_string(i) +
               "}}, {translate: [" + std::to_string(10 * (i % 25)) + ", 0, " + std::to_string(10 * (i / 25)) + "]}]}\n";
  const RenderScene rs = compile(parse_scene(kHead + "groups:\n  g:\n" + group_objects("    ", "") + "objects:\n" + objects,
                                             "many.yaml", "."));
  EXPECT_EQ(rs.instances.size(), 500u);
  ASSERT_EQ(rs.groups.size(), 1u);
  EXPECT_EQ(rs.groups[0].triangles.size(), 1u);
  EXPECT_TRUE(rs.triangles.empty());
  EXPECT_TRUE(rs.solids.empty());
  EXPECT_LE(sizeof(kernel::Instance), 128u);
  // Instance 137 is found where it was placed: straight down onto the top of its sphere.
  const Mat3 r = Mat3::rotation(Vec3(0, 1, 0), 137);
  const Vec3 centre = r * Vec3(-1, 0.5, 0) + Vec3(10 * (137 % 25), 0, 10 * (137 / 25));
  const Hit h = closest_hit(rs.view(), Ray{centre + Vec3(0, 10, 0), {0, -1, 0}}, 0, kInfinity);
  ASSERT_EQ(h.kind, ShapeKind::Instance);
  EXPECT_NEAR(h.t, 9.5, 1e-12);
}

// A copied scene's view points into the copy's groups, not the original's (which is gone), and
// view() changes nothing in the scene (it is called from every render thread).
TEST(Instance, ACopiedSceneViewsItsOwnGroups) {
  auto original = std::make_unique<RenderScene>(
      compile(parse_scene(kHead + "groups:\n  g:\n" + group_objects("    ", "") + "objects:\n" +
                              "  - {type: instance, of: g, translate: [0, 0, 5]}\n",
                          "copy.yaml", ".")));
  const Ray down{{-1, 10, 5}, {0, -1, 0}};
  const Hit expected = closest_hit(original->view(), down, 0, kInfinity);
  ASSERT_EQ(expected.kind, ShapeKind::Instance);
  const RenderScene copy = *original;
  RenderScene assigned;
  assigned = *original;
  original.reset();
  for (const RenderScene* rs : {&copy, static_cast<const RenderScene*>(&assigned)}) {
    const SceneView v = rs->view();
    ASSERT_EQ(v.groups[0].accel.prims.spheres, rs->groups[0].spheres.data());
    ASSERT_EQ(v.groups[0].vertex_normals, rs->groups[0].vertex_normals.data());
    const Hit h = closest_hit(v, down, 0, kInfinity);
    EXPECT_EQ(h.kind, ShapeKind::Instance);
    EXPECT_EQ(h.t, expected.t);
    EXPECT_EQ(rs->view().groups, v.groups);  // a second view() rebuilds nothing
  }
}

std::string error_of(const std::string& text) {
  try {
    compile(parse_scene(kHead + text, "bad.yaml", "."));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Instance, BadGroupsAreErrorsAtTheirPlace) {
  EXPECT_EQ(error_of("objects:\n  - {type: instance, of: nothing}\n"),
            "bad.yaml:10:26: unknown group 'nothing' (the scene defines no groups)");
  EXPECT_EQ(error_of("groups:\n  g: [{type: instance, of: g}]\nobjects:\n  - {type: instance, of: g}\n"),
            "bad.yaml:10:28: group 'g' places an instance of itself (a cycle)");
  EXPECT_EQ(error_of("groups:\n  g: [{type: plane, normal: [0, 1, 0]}]\nobjects:\n  - {type: instance, of: g}\n"),
            "bad.yaml:10:7: a plane cannot be part of group 'g': it is unbounded (place it in objects)");
  EXPECT_EQ(error_of("groups:\n  g: []\nobjects:\n  - {type: instance, of: g}\n"), "bad.yaml:10:6: group 'g' has no objects");
  EXPECT_EQ(error_of("groups:\n  g: [{type: sphere, center: [0, 0, 0], radius: 1}]\nobjects:\n"
                     "  - {type: instance, of: g, matrix: [[1, 0, 0], [0, 1, 0], [1, 0, 0]]}\n"),
            "bad.yaml:12:37: matrix is singular (its determinant is 0): it flattens the object");
}

// kHead with a shutter from 0 to 1 (for motions).
std::string with_shutter() {
  std::string head = kHead;
  head.replace(head.find("fov: 45}"), 8, "fov: 45, shutter: [0, 1]}");
  return head;
}

// Two scenes agree on the surfaces their rays met (but for a few grazing ones), to rounding.
void expect_same_surfaces(const Compared& c, int min_both, const std::string& what = "") {
  EXPECT_GT(c.both, min_both) << what;
  EXPECT_LE(c.disagree, 4) << what;
  EXPECT_LT(c.max_t, 1e-9) << what;
  EXPECT_LT(c.max_normal, 1e-7) << what;
  EXPECT_LE(c.shadow_disagree, 4) << what;
}

// Nested instances (scene/instances.h): `outer` places the group `g` by T1 beside a sphere of
// its own, and the scene places `outer` by T2.
RenderScene nested(const std::string& t1, const std::string& t2, AccelKind accel = AccelKind::Bvh) {
  Scene s = parse_scene(kHead + "groups:\n  g:\n" + group_objects("    ", "") +
                            "  outer:\n    - {type: instance, of: g" + (t1.empty() ? "" : ", " + t1) + "}\n" +
                            "    - {type: sphere, center: [0, 2.5, 0], radius: 0.2, material: red}\n" +
                            "objects:\n" + kFloor + "  - {type: instance, of: outer" + (t2.empty() ? "" : ", " + t2) + "}\n",
                        "nested.yaml", ".");
  s.settings.accel = accel;
  return compile(s);
}

TEST(Instance, NestedIdentityInstancesRenderTheSameBitsAsTheObjects) {
  const RenderScene n = nested("", "");
  ASSERT_EQ(n.instances.size(), 2u);  // outer's own sphere, and g by way of outer
  ASSERT_EQ(n.group_nesting.size(), 2u);
  EXPECT_EQ(n.group_nesting[1].unfolded, 2u);
  const RenderScene d = compile(parse_scene(kHead + "objects:\n" + kFloor + group_objects("  ", "") +
                                                "  - {type: sphere, center: [0, 2.5, 0], radius: 0.2, material: red}\n",
                                            "direct.yaml", "."));
  const Image in = render_of(n), id = render_of(d);
  EXPECT_TRUE(in == id) << "max difference " << test::max_abs_diff(in, id);
  const Compared c = compare(d, n, 17);
  EXPECT_GT(c.both, 1000);
  EXPECT_EQ(c.disagree, 0);
  EXPECT_EQ(c.max_t, 0);
  EXPECT_EQ(c.max_normal, 0);
}

// The group's objects are where T1 and then T2 put them (the objects written in place with both
// transforms in turn), for a mirror and a shear too; and every accelerator (inside the groups,
// one of which has no shapes of its own) agrees.
TEST(Instance, NestedInstanceIsTheObjectsUnderBothTransforms) {
  const char* inner[] = {"{rotate: {axis: [1, 2, 0.5], angle: 37}}, {translate: [0.3, -0.2, 0.7]}",
                         "{scale: [-1, 1, 1]}", "{matrix: [[1, 0.3, 0, 0.2], [0, 1, 0, 0], [0.1, 0, 0.8, -0.1]]}"};
  const char* outer[] = {"{scale: [1.5, 0.7, 1.2]}, {rotate: [10, 20, 30]}, {translate: [0.1, 0.2, -0.3]}",
                         "{rotate: {axis: [0, 1, 0], angle: 200}}", "{translate: [0.5, 0, 0]}"};
  for (int k = 0; k < 3; ++k) {
    const std::string t1 = inner[k], t2 = outer[k];
    const RenderScene n = nested("transform: [" + t1 + "]", "transform: [" + t2 + "]");
    const RenderScene d = compile(parse_scene(
        kHead + "objects:\n" + kFloor + group_objects("  ", "transform: [" + t1 + ", " + t2 + "]") +
            "  - {type: sphere, center: [0, 2.5, 0], radius: 0.2, material: red, transform: [" + t2 + "]}\n",
        "direct.yaml", "."));
    const Compared c = compare(d, n, 19 + k);
    expect_same_surfaces(c, 500, t1 + " then " + t2);
  }
  // The group `holder` has no shapes of its own: it is placed by its records only.
  const std::string t = "transform: [{rotate: {axis: [0, 1, 0], angle: 25}}, {scale: 1.3}]";
  const auto holder = [&](AccelKind accel) {
    Scene s = parse_scene(kHead + "groups:\n  g:\n" + group_objects("    ", "") + "  holder:\n" +
                              "    - {type: instance, of: g, " + t + "}\nobjects:\n" + kFloor +
                              "  - {type: instance, of: holder, translate: [0.2, 0, 0]}\n",
                          "holder.yaml", ".");
    s.settings.accel = accel;
    return compile(s);
  };
  const RenderScene reference = holder(AccelKind::Bvh);
  ASSERT_EQ(reference.instances.size(), 1u);
  EXPECT_FALSE(reference.group_nesting[1].own);
  for (AccelKind k : {AccelKind::Naive, AccelKind::KdTree, AccelKind::Octree}) {
    const Compared c = compare(reference, holder(k), 11);
    EXPECT_EQ(c.disagree, 0) << accel_name(k);
    EXPECT_LT(c.max_t, 1e-12) << accel_name(k);
  }
}

// Three levels, each placement a translation by eighths (exact sums): the unfolded records are
// those of the same placements written at one level, so the images are the same bits, still and
// moving (every record carried by the outer instance's motion).
TEST(Instance, DeepNestingUnfoldsEveryPlacement) {
  const std::string g = "groups:\n  g:\n" + group_objects("    ", "");
  const std::string ball = "  ball:\n    - {type: sphere, center: [0, 2.5, 0], radius: 0.2, material: red}\n";
  const std::string deep = g + ball +
                           "  pair:\n    - {type: instance, of: g, translate: [-0.5, 0, 0]}\n"
                           "    - {type: instance, of: g, translate: [0.625, 0, -0.25]}\n"
                           "    - {type: instance, of: ball}\n"
                           "  row:\n    - {type: instance, of: pair, translate: [0, 0, -1.5]}\n"
                           "    - {type: instance, of: pair, translate: [0.25, 0.125, 1]}\n";
  const std::string flat = g + ball;
  const std::string shutter_head = with_shutter();
  const char* records[] = {"g, translate: [-0.5, 0, -1.5]", "g, translate: [0.625, 0, -1.75]", "ball, translate: [0, 0, -1.5]",
                           "g, translate: [-0.25, 0.125, 1]", "g, translate: [0.875, 0.125, 0.75]",
                           "ball, translate: [0.25, 0.125, 1]"};
  for (const std::string motion : {"", ", motion: {velocity: [0.25, 0, 0.5]}"}) {
    std::string flat_objects;
    for (const char* r : records) flat_objects += std::string("  - {type: instance, of: ") + r + motion + "}\n";
    const RenderScene d = compile(parse_scene(shutter_head + flat + "objects:\n" + kFloor +
                                                  flat_objects,
                                              "flat.yaml", "."));
    const RenderScene n = compile(parse_scene(shutter_head + deep + "objects:\n" + kFloor +
                                                  "  - {type: instance, of: row" + motion + "}\n",
                                              "deep.yaml", "."));
    ASSERT_EQ(n.instances.size() + n.moving_instances.size(), 6u) << motion;
    ASSERT_EQ(n.moving_instances.size(), motion.empty() ? 0u : 6u);
    const Image in = render_of(n), id = render_of(d);
    EXPECT_TRUE(in == id) << motion << ": max difference " << test::max_abs_diff(in, id);
    if (motion.empty()) {
      const Compared c = compare(d, n, 23);
      EXPECT_GT(c.both, 1000);
      EXPECT_EQ(c.disagree, 0);
      EXPECT_EQ(c.max_t, 0);
    }
  }
}

// An instance inside a group may move (when nothing placing it does): its records are carried by
// its motion and then by the placements above it (the motion map's post map). Under the identity
// that is the moving instance written at the top, bit for bit; under x ↦ M·x + t it is the moving
// instance placed by M·P, M·t_P + t and moving by M·v, at every time of the shutter.
TEST(Instance, MovingInstancesInsideGroupsMoveUnderTheOuterPlacement) {
  const std::string head = with_shutter();
  const std::string g = "groups:\n  g:\n" + group_objects("    ", "");
  const std::string inner = "transform: [{rotate: {axis: [1, 2, 0.5], angle: 37}}, {translate: [0.25, -0.5, 0.75]}]";
  const auto scene_of = [&](const std::string& text) { return compile(parse_scene(head + text, "moving.yaml", ".")); };
  const RenderScene top = scene_of(g + "objects:\n" + kFloor + "  - {type: instance, of: g, " + inner +
                                   ", motion: {velocity: [0.5, 0.25, -1]}}\n");
  const RenderScene nested_identity =
      scene_of(g + "  outer: [{type: instance, of: g, " + inner + ", motion: {velocity: [0.5, 0.25, -1]}}]\nobjects:\n" +
               kFloor + "  - {type: instance, of: outer}\n");
  ASSERT_EQ(nested_identity.moving_instances.size(), 1u);
  EXPECT_EQ(nested_identity.moving_instances[0].map.post, 0u);
  const Image it = render_of(top), in = render_of(nested_identity);
  EXPECT_TRUE(it == in) << "max difference " << test::max_abs_diff(it, in);
  // M: a quarter turn about z (exact entries) and a stretch in z; t = (1, 0, -1).
  const RenderScene nested_placed = scene_of(g + "  outer: [{type: instance, of: g, " + inner +
                                             ", motion: {velocity: [0.5, 0.25, -1]}}]\nobjects:\n" + kFloor +
                                             "  - {type: instance, of: outer, matrix: [[0, -1, 0, 1], [1, 0, 0, 0], [0, 0, 2, -1]]}\n");
  ASSERT_EQ(nested_placed.moving_instances.size(), 1u);
  EXPECT_EQ(nested_placed.moving_instances[0].map.post, 1u);
  // The same, flat: the group placed by M·P (its transform list then M) and moving by M·v.
  const RenderScene flat = scene_of(g + "objects:\n" + kFloor + "  - {type: instance, of: g, transform: [" +
                                    inner.substr(12, inner.size() - 13) +
                                    ", {matrix: [[0, -1, 0, 1], [1, 0, 0, 0], [0, 0, 2, -1]]}], motion: {velocity: [-0.25, 0.5, -2]}}\n");
  const SceneView vn = nested_placed.view(), vf = flat.view();
  test::Random rng(29);
  int both = 0, disagree = 0;
  Real max_t = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 o = Vec3(1, 0.5, -1) + rng.direction() * 9;
    const Ray ray{o, normalize(Vec3(1, 0.5, -1) + rng.point(-3, 3) - o), rng.uniform()};
    const Hit a = closest_hit(vn, ray, 0, kInfinity), b = closest_hit(vf, ray, 0, kInfinity);
    if (a.found() != b.found() || (a.found() && std::fabs(a.t - b.t) > 1e-6 * a.t)) {
      ++disagree;
      continue;
    }
    if (!a.found()) continue;
    both += a.kind != ShapeKind::Plane;
    max_t = std::fmax(max_t, std::fabs(a.t - b.t) / a.t);
  }
  EXPECT_GT(both, 300);
  EXPECT_LE(disagree, 4);
  EXPECT_LT(max_t, 1e-9);
}

// Hits of two scenes along rays at random times of the shutter (or all at time `at`, where given):
// how many met a shape (not the floor), how many disagreed (a grazing ray), the largest relative
// difference in t and normal.
Compared compare_in_time(const RenderScene& x, const RenderScene& y, std::uint64_t seed, Real at = -1) {
  const SceneView vx = x.view(), vy = y.view();
  test::Random rng(seed);
  Compared c;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 o = Vec3(0, 0.8, 0) + rng.direction() * 8;
    const Vec3 d = normalize(Vec3(0, 0.8, 0) + rng.point(-2.5, 2.5) - o);
    const Ray ray{o, d, at < 0 ? rng.uniform() : at};
    const Hit hx = closest_hit(vx, ray, 0, kInfinity), hy = closest_hit(vy, ray, 0, kInfinity);
    ++c.rays;
    // As a shadow ray across the scene (through the glass: crossings counted, render/moving_shapes.h).
    const Vec3 ax = transmittance(vx, ray, 16), ay = transmittance(vy, ray, 16);
    c.shadowed += !(ax == Vec3(1));
    c.shadow_disagree += max_abs_component(ax - ay) > 1e-9;
    if (hx.found() != hy.found() || (hx.found() && std::fabs(hx.t - hy.t) > 1e-6 * hx.t)) {
      ++c.disagree;
      continue;
    }
    if (!hx.found() || hx.kind == ShapeKind::Plane) continue;
    ++c.both;
    c.max_t = std::fmax(c.max_t, std::fabs(hx.t - hy.t) / hx.t);
    c.max_normal = std::fmax(c.max_normal, length(surface_at(vx, ray, hx).normal - surface_at(vy, ray, hy).normal));
  }
  return c;
}

// A group's shapes may move (a spinning rotor on each of many windmills): each is held still in
// a group of its own and placed in its group by a moving instance, so it moves as it does in the
// scene's objects — a sphere by a velocity and by keys that scale it unevenly, a triangle and a
// box turning, a mesh whose keys act before its own transform, a CSG tree — and, under an
// instance's transform M, as the same shape with M added to its placement (a mesh's transform
// list; a box's velocity carried by M).
TEST(Instance, MovingShapesOfAGroupMoveAsInTheScene) {
  const std::string head = with_shutter();
  const std::string shapes[] = {
      "{type: sphere, center: [-1, 0.5, 0], radius: 0.5, material: red, motion: {velocity: [0.5, 0, -0.25]}",
      "{type: sphere, center: [1, 1.5, -1], radius: 0.4, motion: {to: {scale: [1, 1.5, 0.75]}}",
      "{type: triangle, vertices: [[-2, 0, -1], [2, 0, -1], [0, 2, -1.5]], motion: {to: {rotate: {axis: [0, 0, 1], angle: 40}}}",
      "{type: box, corners: [[0.2, 0, -0.4], [1, 0.8, 0.4]], material: glass, motion: {spin: {axis: [0, 1, 0], angle: 200, "
      "center: [0.6, 0, 0]}}",
      "{type: mesh, file: meshes/icosahedron.obj, scale: 0.4, translate: [0, 1.2, 0.8], motion: {to: {rotate: [0, 90, 0], "
      "translate: [0.5, 0, 0]}}",
      "{type: difference, material: red, objects: [{type: sphere, center: [0, 1.6, 0.5], radius: 0.4}, "
      "{type: cylinder, base: [0, 1.6, 0], cap: [0, 1.6, 1], radius: 0.2}], motion: {velocity: [0, 0.5, 0]}",
  };
  const std::string base = std::string(STRAHL_SOURCE_DIR) + "/scenes";
  std::string top, grouped;
  for (const std::string& shape : shapes) {
    top += "  - " + shape + "}\n";
    grouped += "    - " + shape + "}\n";
  }
  const std::string still = "{type: sphere, center: [2, 0.3, 1], radius: 0.3}\n";
  const RenderScene direct_scene =
      compile(parse_scene(head + "objects:\n" + kFloor + top + "  - " + still, "direct.yaml", base));
  const RenderScene grouped_scene = compile(parse_scene(
      head + "groups:\n  g:\n" + grouped + "    - " + still + "objects:\n" + kFloor + "  - {type: instance, of: g}\n",
      "grouped.yaml", base));
  EXPECT_EQ(grouped_scene.instances.size(), 1u);          // the group's still sphere
  EXPECT_EQ(grouped_scene.moving_instances.size(), 6u);   // each moving shape, in a group of its own
  EXPECT_EQ(grouped_scene.groups.size(), 7u);
  const Compared c = compare_in_time(direct_scene, grouped_scene, 31);
  expect_same_surfaces(c, 400);
  // Under M: the mesh with M after its own transform, the box placed by M moving by M·v.
  const std::string m = "matrix: [[0, -1, 0, 1], [1, 0, 0, 0], [0, 0, 2, -1]]";
  const RenderScene placed = compile(parse_scene(
      head + "groups:\n  g:\n    - " + shapes[4] + "}\n    - {type: box, corners: [[0.2, 0, -0.4], [1, 0.8, 0.4]], "
             "motion: {velocity: [0.5, 0.25, -0.5]}}\nobjects:\n" + kFloor + "  - {type: instance, of: g, " + m + "}\n",
      "placed.yaml", base));
  const RenderScene composed = compile(parse_scene(
      head + "objects:\n" + kFloor + "  - {type: mesh, file: meshes/icosahedron.obj, transform: [{scale: 0.4}, "
             "{translate: [0, 1.2, 0.8]}, {" + m + "}], motion: {to: {rotate: [0, 90, 0], translate: [0.5, 0, 0]}}}\n"
             "  - {type: box, corners: [[0.2, 0, -0.4], [1, 0.8, 0.4]], " + m + ", motion: {velocity: [-0.25, 0.5, -1]}}\n",
      "composed.yaml", base));
  const Compared d = compare_in_time(placed, composed, 37);
  expect_same_surfaces(d, 150);
}

// A moving instance whose motion scales brings rays to its still group with directions of another
// length: its spheres (met by a test that takes unit directions) are still where the moving
// sphere written in the objects is (until 2026-12-06 they were not: the record passed the ray on
// unnormalised).
TEST(Instance, AMovingInstanceThatScalesMeetsItsSpheres) {
  const std::string head = with_shutter();
  for (const std::string motion : {"{to: {scale: 1.5}}", "{from: {scale: 0.5}, to: {scale: [1, 2, 1], translate: [0, 1, 0]}}"}) {
    const RenderScene direct_scene = compile(parse_scene(
        head + "objects:\n" + kFloor + "  - {type: sphere, center: [1, 1, -1], radius: 0.6, motion: " + motion + "}\n",
        "direct.yaml", "."));
    const RenderScene instanced_scene = compile(parse_scene(
        head + "groups:\n  g: [{type: sphere, center: [1, 1, -1], radius: 0.6}]\nobjects:\n" + kFloor +
            "  - {type: instance, of: g, motion: " + motion + "}\n",
        "instanced.yaml", "."));
    const Compared c = compare_in_time(direct_scene, instanced_scene, 41);
    EXPECT_GT(c.both, 100) << motion;
    EXPECT_EQ(c.disagree, 0) << motion;
    EXPECT_LT(c.max_t, 1e-9) << motion;
    EXPECT_LT(c.max_normal, 1e-7) << motion;
  }
}

// An instance that only translates (a velocity) may place things that move: a car driving, its
// wheels spinning about their hubs. Its translation is added to theirs, so each wheel is where a
// wheel written in the objects with the velocity and the spin carried over — axis M·z, centre
// M·hub + t — is, at every time; likewise the body.
TEST(Instance, ATranslatingInstanceCarriesWhatMovesInside) {
  const std::string head = with_shutter();
  const std::string groups =
      "groups:\n  wheel:\n    - {type: cylinder, base: [0, 0, -0.1], cap: [0, 0, 0.1], radius: 0.3}\n"
      "    - {type: box, corners: [[0.15, -0.05, -0.12], [0.3, 0.05, 0.12]], material: red}\n"
      "  body: [{type: box, corners: [[-1, 0.3, -0.4], [1, 0.8, 0.4]], material: glass}]\n";
  const char* hubs[] = {"[0.7, 0.3, 0.5]", "[-0.7, 0.3, 0.5]"};
  std::string car = "  car:\n    - {type: instance, of: body}\n";
  for (const char* hub : hubs)
    car += std::string("    - {type: instance, of: wheel, translate: ") + hub +
           ", motion: {spin: {axis: [0, 0, 1], angle: -120, center: " + hub + "}}}\n";
  // M: the identity, and a quarter turn about y (exact entries) with a shift.
  struct Case {
    const char* m;
    const char* axis;
    const char* centers[2];
  };
  const Case cases[] = {{"", "[0, 0, 1]", {"[0.7, 0.3, 0.5]", "[-0.7, 0.3, 0.5]"}},
                        {"matrix: [[0, 0, 1, 0.25], [0, 1, 0, 0], [-1, 0, 0, -0.5]]", "[1, 0, 0]",
                         {"[0.75, 0.3, -1.2]", "[0.75, 0.3, 0.2]"}}};
  for (const Case& k : cases) {
    const std::string m = k.m;
    const std::string velocity = "velocity: [0.5, 0, 0.25]";
    const RenderScene nested_scene = compile(parse_scene(
        head + groups + car + "objects:\n" + kFloor + "  - {type: instance, of: car, " + (m.empty() ? "" : m + ", ") +
            "motion: {" + velocity + "}}\n",
        "car.yaml", "."));
    ASSERT_EQ(nested_scene.moving_instances.size(), 3u);
    std::string flat = head + groups + "objects:\n" + kFloor + "  - {type: instance, of: body, " +
                       (m.empty() ? "" : m + ", ") + "motion: {" + velocity + "}}\n";
    for (int w = 0; w < 2; ++w)
      flat += std::string("  - {type: instance, of: wheel, transform: [{translate: ") + hubs[w] + "}" +
              (m.empty() ? "" : ", {" + m + "}") + "], motion: {" + velocity + ", spin: {axis: " + k.axis +
              ", angle: -120, center: " + k.centers[w] + "}}}\n";
    const Compared c = compare_in_time(nested_scene, compile(parse_scene(flat, "flat.yaml", ".")), 43);
    expect_same_surfaces(c, 150, m);
  }
}

// Motions that turn or scale compose (geometry/moving_instance.h: a record carried by A(u), then
// B(u)): a car whose wheels spin about their hubs, placed by keys that turn it and scale it
// (under a matrix; inside a group moved by a velocity; moved inside a group by a velocity after a
// fixed turn, the turn and scale above; that velocity under a fixed placement alone, folded into
// the spins), against still scenes at fixed times of the shutter, the
// car and its wheels placed by the transforms that the motions reach then, written out: the
// spin's angle −120°·u about the hub, the keys' turn 40°·u about y with the scale 1 + 0.5·u, the
// velocity's shift.
TEST(Instance, TurnsAndScalesComposeAcrossNestedMotions) {
  const std::string head = with_shutter();
  const std::string groups =
      "groups:\n  wheel:\n    - {type: cylinder, base: [0, 0, -0.1], cap: [0, 0, 0.1], radius: 0.3}\n"
      "    - {type: box, corners: [[0.15, -0.05, -0.12], [0.3, 0.05, 0.12]], material: red}\n"
      "  body: [{type: box, corners: [[-1, 0.3, -0.4], [1, 0.8, 0.4]], material: glass}]\n"
      "  car:\n    - {type: instance, of: body}\n"
      "    - {type: instance, of: wheel, translate: [0.7, 0.3, 0.5], motion: {spin: {axis: [0, 0, 1], angle: -120, "
      "center: [0.7, 0.3, 0.5]}}}\n"
      "    - {type: instance, of: wheel, translate: [-0.7, 0.3, 0.5], motion: {spin: {axis: [0, 0, 1], angle: -120, "
      "center: [-0.7, 0.3, 0.5]}}}\n";
  const std::string keys = "motion: {to: {rotate: [0, 40, 0], scale: 1.5}}";
  const std::string m = "[[0, 0, 1, 0.25], [0, 1, 0, 0], [-1, 0, 0, -0.5]]";
  const auto num = [](Real x) { return fmt::format("{}", x); };
  const auto turned = [&](Real u) {
    return "{scale: " + num(1 + 0.5 * u) + "}, {rotate: [0, " + num(40 * u) + ", 0]}";
  };
  struct Case {
    std::string moving;                      // groups after the car's, and the objects
    std::function<std::string(Real)> outer;  // the car's transform list at u
  };
  const Case cases[] = {
      {"objects:\n" + kFloor + "  - {type: instance, of: car, matrix: " + m + ", " + keys + "}\n",
       [&](Real u) { return "{matrix: " + m + "}, " + turned(u); }},
      {"  convoy: [{type: instance, of: car, translate: [0, 0, -0.5], " + keys + "}]\nobjects:\n" + kFloor +
           "  - {type: instance, of: convoy, motion: {velocity: [0.5, 0, 0.25]}}\n",
       [&](Real u) {
         return "{translate: [0, 0, -0.5]}, " + turned(u) + ", {translate: [" + num(0.5 * u) + ", 0, " + num(0.25 * u) + "]}";
       }},
      {"  convoy: [{type: instance, of: car, rotate: [0, 90, 0], motion: {velocity: [0.5, 0, 0]}}]\nobjects:\n" +
           kFloor + "  - {type: instance, of: convoy, translate: [0.3, 0, -0.2], " + keys + "}\n",
       [&](Real u) {
         return "{rotate: [0, 90, 0]}, {translate: [" + num(0.5 * u) + ", 0, 0]}, {translate: [0.3, 0, -0.2]}, " + turned(u);
       }},
      // The velocity's map then has the fixed placement above it as its post map, and is folded
      // into the wheels' spins, fixed map and all.
      {"  convoy: [{type: instance, of: car, rotate: [0, 90, 0], motion: {velocity: [0.5, 0, 0]}}]\nobjects:\n" +
           kFloor + "  - {type: instance, of: convoy, translate: [0.3, 0, -0.2], scale: 1.25}\n",
       [&](Real u) {
         return "{rotate: [0, 90, 0]}, {translate: [" + num(0.5 * u) + ", 0, 0]}, {scale: 1.25}, {translate: [0.3, 0, -0.2]}";
       }},
  };
  int seed = 47;
  for (const Case& k : cases) {
    const RenderScene moving = compile(parse_scene(head + groups + k.moving, "car.yaml", "."));
    ASSERT_EQ(moving.moving_instances.size(), 3u) << k.moving;
    const bool twice = k.moving.find(keys) != std::string::npos;  // (else the spins alone turn)
    EXPECT_EQ(moving.moving_instances[1].two_maps + moving.moving_instances[2].two_maps, twice ? 2u : 0u) << k.moving;
    for (const Real u : {0.0, 0.3, 0.71, 1.0}) {
      std::string still = head + groups + "objects:\n" + kFloor + "  - {type: instance, of: body, transform: [" +
                          k.outer(u) + "]}\n";
      for (const char* hub : {"[0.7, 0.3, 0.5]", "[-0.7, 0.3, 0.5]"})
        still += "  - {type: instance, of: wheel, transform: [{rotate: {axis: [0, 0, 1], angle: " + num(-120 * u) +
                 "}}, {translate: " + hub + "}, " + k.outer(u) + "]}\n";
      const Compared c = compare_in_time(moving, compile(parse_scene(still, "still.yaml", ".")), seed++, u);
      expect_same_surfaces(c, 150, k.moving + " at " + num(u));
      EXPECT_GT(c.shadowed, 150) << k.moving << " at " << u;
    }
  }
}

TEST(Instance, NestedGroupsAreWrittenAndReadBack) {
  const Scene a = parse_scene(kHead + "groups:\n  g:\n" + group_objects("    ", "") +
                                  "  outer:\n    - {type: instance, of: g, rotate: [0, 30, 0]}\n"
                                  "    - {type: instance, of: g, translate: [2, 0, 0], motion: {velocity: [0, 1, 0]}}\n"
                                  "    - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 1, 0], "
                                  "angle: 90}}}\n"
                                  "objects:\n  - {type: instance, of: outer, scale: 0.5}\n",
                              "a.yaml", ".");
  const std::string text = scene_to_yaml(a);
  const Scene b = parse_scene(text, "b.yaml", ".");
  const RenderScene ca = compile(a);
  EXPECT_EQ(ca.instances.size() + ca.moving_instances.size(), 3u);
  EXPECT_EQ(scene_hash(ca), scene_hash(compile(b))) << text;
}

// A spinning triangle moves as an instance of a group of its own, which the compiled scene holds
// after the scene's groups: an instance (built in code) cannot name it.
TEST(Instance, AnInstanceNamesOnlyTheScenesGroups) {
  Scene s;
  Triangle spinning({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, Vec3(1));
  spinning.motion = Motion::spinning(Spin{{0, 0, 1}, 90, {}});
  s.add(spinning);
  s.add(Instance(0));
  try {
    compile(s);
    ADD_FAILURE() << "compiled";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "instance of group number 0, which the scene does not have");
  }
}

TEST(Instance, BadNestingIsAnErrorAtItsPlace) {
  const std::string sphere = "[{type: sphere, center: [0, 0, 0], radius: 1}]";
  EXPECT_EQ(error_of("groups:\n  a: [{type: instance, of: b}]\n  b: " + sphere + "\nobjects:\n  - {type: instance, of: a}\n"),
            "bad.yaml:10:28: unknown group 'b': group 'a' can place the groups defined above it (none is)");
  EXPECT_EQ(error_of("groups:\n  b: " + sphere + "\n  a: [{type: instance, of: c}]\n  c: " + sphere +
                     "\nobjects:\n  - {type: instance, of: a}\n"),
            "bad.yaml:11:28: unknown group 'c': group 'a' can place the groups defined above it (b)");
  // Three motions that turn or scale (a spin in a group scaled in a group turned): two compose.
  EXPECT_EQ(error_of("groups:\n  b: " + sphere + "\n  a: [{type: instance, of: b, motion: {spin: {axis: [0, 1, 0], angle: 90}}}]\n" +
                     "  c: [{type: instance, of: a, motion: {to: {scale: 2}}}]\nobjects:\n  - {type: instance, of: c}\n"
                     "  - {type: instance, of: c, motion: {to: {rotate: [0, 30, 0]}}}\n"),
            "bad.yaml:15:5: this instance moves, and so does the object at bad.yaml:11:7 in group 'a', inside a "
            "placement that moves too: a placed object has at most two motions that turn or scale (let one of the "
            "three only translate)");
  EXPECT_EQ(error_of("groups:\n  b: " + sphere + "\n  a: [{type: instance, of: b, scale: [1, 0, 1]}]\nobjects:\n"
                     "  - {type: instance, of: a}\n"),
            "bad.yaml:11:38: scale must not be zero");
  // 2^25 records from 25 groups each placing the one before twice: refused before a record is made.
  std::string doubling = "groups:\n  g0: " + sphere + "\n";
  for (int i = 1; i <= 25; ++i)
    doubling += "  g" + std::to_string(i) + ": [{type: instance, of: g" + std::to_string(i - 1) + "}, {type: instance, of: g" +
                std::to_string(i - 1) + ", translate: [" + std::to_string(1 << i) + ", 0, 0]}]\n";
  EXPECT_EQ(error_of(doubling + "objects:\n  - {type: instance, of: g25}\n"),
            "bad.yaml:37:5: too many instances: this one unfolds into more than 16777216 records through nested groups, "
            "and a scene holds at most 16777216");
  // One record, then 2^24: the second passes the limit (before any of its records is made).
  EXPECT_EQ(error_of(doubling + "objects:\n  - {type: instance, of: g0}\n  - {type: instance, of: g24}\n"),
            "bad.yaml:38:5: too many instances: this one unfolds into 16777216 records through nested groups, and a "
            "scene holds at most 16777216");
}

}  // namespace
}  // namespace strahl::instance_test
