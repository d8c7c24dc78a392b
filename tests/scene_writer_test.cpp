// scene_to_yaml / save_scene (scene/scene_writer.h): what it writes reads back to the same
// compiled scene (scene_hash, which covers every shape, material, light, the camera and the
// settings), for every example scene and for scenes built in code with every kind of object,
// light and camera; and writing the read-back scene gives the same text.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "strahl/render/render_scene.h"
#include "strahl/render/scene_hash.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/scene_writer.h"
#include "test_helpers.h"

namespace strahl::scene_writer_test {
namespace {

namespace fs = std::filesystem;

Scene read_back(const Scene& scene) { return parse_scene(scene_to_yaml(scene), "written.yaml", "."); }

// Saved into a fresh directory (the scene file and its meshes' OBJ files) and loaded again.
void expect_round_trip(const Scene& scene) {
  const test::TempDir dir;
  save_scene(scene, dir / "saved.yaml");
  const Scene back = load_scene(dir / "saved.yaml");
  EXPECT_EQ(scene_hash(compile(scene)), scene_hash(compile(back))) << scene_to_yaml(scene);
  EXPECT_EQ(scene_to_yaml(back), scene_to_yaml(scene));
  EXPECT_EQ(back.settings.accel, scene.settings.accel);
}

TEST(SceneWriter, EveryExampleSceneReadsBackToTheSameCompiledScene) {
  int scenes = 0, with_groups = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(STRAHL_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const Scene scene = load_scene(entry.path());
    with_groups += !scene.groups.empty();
    expect_round_trip(scene);
    ++scenes;
  }
  EXPECT_GE(scenes, 10);
  EXPECT_EQ(with_groups, 4);  // scenes/instances.yaml (meshes and CSG, 1,024 instances), instances-nested.yaml,
                              // instances-windmills.yaml, motion-tumble.yaml
}

TEST(SceneWriter, EveryKindOfObjectLightAndCamera) {
  Scene s;
  s.camera.position = Vec3(0.1, 0.7, 3.3);
  s.camera.look_at = Vec3(0.01, 0.2, -0.3);
  s.camera.up = Vec3(0.1, 1, 0);
  s.camera.fov_degrees = 37.5;
  s.camera.fov_axis = CameraDescription::FovAxis::Vertical;
  s.camera.aperture = 0.05;
  s.camera.has_focus_point = true;
  s.camera.focus_point = Vec3(0, 0.3, 0);
  s.camera.shutter_open = 0.25;
  s.camera.shutter_close = 0.75;
  s.settings.width = 33;
  s.settings.height = 17;
  s.settings.max_depth = 5;
  s.settings.min_weight = 1.0 / 3;
  s.settings.background = Vec3(0.1, 0.2, 0.30000000000000004);
  s.settings.ambient_light = Vec3(0.9);
  s.settings.medium_ior = 1.333;
  s.settings.ray_budget = 77;
  s.settings.integrator = IntegratorKind::Path;
  s.settings.accel = AccelKind::KdTree;
  s.settings.sampling.sampler = SamplerKind::Sobol;
  s.settings.sampling.spp = 7;
  s.settings.sampling.seed = 18446744073709551615ull;  // the largest seed: scene files take 64 bits
  s.settings.sampling.filter.kind = FilterKind::Mitchell;
  s.settings.sampling.filter.radius = 1.75;
  Material glass;
  glass.color = Vec3(0.9, 1, 0.95);
  glass.transparency = 0.9;
  glass.ior = 1.5;
  glass.fresnel = true;
  glass.filter = true;
  glass.roughness = 0.1;
  Material checker;
  checker.checker_size = 0.3;
  checker.checker_color = Vec3(1, 0.85, 0.1);
  checker.specular = Vec3(0.1, 0.2, 0.3);
  checker.shininess = 7;
  checker.emission = Vec3(0.25, 0, 3);
  s.add(Plane(Vec3(0, 2, 0.1), 0.5, checker));
  s.add(Sphere(Vec3(0.1, 0.2, 0.3), 0.7, glass)).motion = Motion::linear(Vec3(0.1, 0, 0));
  s.add(Triangle(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0.1), Vec3(0.2, 0.3, 0.4)));
  MeshData data;
  data.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  data.normals = {Vec3(0, 0, -1), Vec3(1, 1, 1)};
  data.faces.push_back({{0, 1, 2}, {0, 0, 0}});
  data.faces.push_back({{0, 1, 3}, {-1, -1, -1}});
  data.faces.push_back({{1, 2, 3}, {1, 1, 1}});
  Transform t;
  t.scale = Vec3(1, -2, 1);  // mirrored
  t.rotate_degrees = Vec3(10, 20, 30);
  t.translate = Vec3(0.1, 0.2, 0.3);
  Mesh& mesh = s.add(Mesh(data, glass, t));
  Transform from, to;
  to.rotate_degrees = Vec3(0, 45, 0);
  mesh.motion = Motion::keyframes(from, to);
  s.add(point_light(Vec3(1, 2, 3), Vec3(0.5, 0.25, 1), 3));
  s.add(directional_light(Vec3(1, -1, 0.3), Vec3(1), 0.7));
  s.add(spot_light(Vec3(0, 3, 1), Vec3(0.1, -1, 0.2), 12.5, 1.0 / 3, 7, Vec3(0.2, 0.4, 0.8), 5));
  Light faded = point_light(Vec3(-1, 2, 0), Vec3(0.3), 2);
  faded.fade_distance = 0.7;
  faded.fade_power = 2.5;
  s.add(faded);
  s.add(rect_light(Vec3(0, 2, 0), Vec3(0.5, 0, 0), Vec3(0, 0, 0.25), Vec3(4), 3));
  s.add(disk_light(Vec3(0, 2, 1), Vec3(0.3, -1, 0.2), 0.2, Vec3(2, 3, 4), 2));
  s.add(sphere_light(Vec3(-1, 2, 1), 0.1, Vec3(10)));
  expect_round_trip(s);

  // The explicit image plane instead of a field of view, and a focus distance.
  s.camera.explicit_image_plane = true;
  s.camera.l = -0.6;
  s.camera.r = 0.4;
  s.camera.b = -0.3;
  s.camera.t = 0.2;
  s.camera.d = 0.9;
  s.camera.has_focus_point = false;
  s.camera.focus_distance = 2.5;
  s.settings.sampling.spp = 0;  // supersample² on the grid
  s.settings.supersample = 3;
  expect_round_trip(s);
}

TEST(SceneWriter, ShortestNumbersReadBackExactly) {
  Scene s;
  s.add(Sphere(Vec3(0.1 + 0.2, 1e-300, -5e-324), 1.0 / 3, Vec3(0.8, 0.2, 0.2)));
  const Scene back = read_back(s);
  const auto& sphere = dynamic_cast<const Sphere&>(*back.objects()[0]);
  EXPECT_EQ(sphere.center.x, 0.1 + 0.2);
  EXPECT_EQ(sphere.center.y, 1e-300);
  EXPECT_EQ(sphere.center.z, -5e-324);
  EXPECT_EQ(sphere.radius, 1.0 / 3);
}

TEST(SceneWriter, RefusesWhatAFileCannotHold) {
  Scene s;
  s.add(Sphere(Vec3(0, std::nan(""), 0), 1, Vec3(1)));
  EXPECT_THROW(
      {
        try {
          (void)scene_to_yaml(s);
        } catch (const Error& e) {
          EXPECT_STREQ(e.what(), "cannot write sphere center: it is not a finite number");
          throw;
        }
      },
      Error);
  Scene ok;
  ok.add(Sphere(Vec3(0), 1, Vec3(1)));
  const test::TempDir dir;
  EXPECT_THROW(save_scene(ok, dir / "scene.png"), Error);
  EXPECT_THROW(save_scene(ok, dir.path() / "missing" / "scene.yaml"), Error);
  save_scene(ok, dir / "scene.yaml");
  EXPECT_EQ(scene_hash(compile(load_scene(dir / "scene.yaml"))), scene_hash(compile(ok)));
}

// Groups and instances: names of any characters, meshes in groups and beside them (their OBJ
// files numbered in the order written), instances by the fixed keys and by a general matrix.
TEST(SceneWriter, GroupsAndInstancesReadBack) {
  const test::TempDir dir;
  test::write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Scene scene = parse_scene(R"(groups:
  "a \"quoted\": name\\ with\tcontrol # and more":
    - {type: mesh, file: tri.obj, scale: 2, material: {color: [1, 0, 0]}}
    - {type: sphere, center: [0, 1, 0], radius: 0.5}
  plain:
    - {type: difference, objects: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}, {type: sphere, center: [1, 1, 1], radius: 0.5}]}
objects:
  - {type: mesh, file: tri.obj, translate: [0, 0, -3]}
  - {type: instance, of: "a \"quoted\": name\\ with\tcontrol # and more", translate: [1, 0, 0]}
  - {type: instance, of: plain, transform: [{rotate: {axis: [1, 2, 3], angle: 33}}, {scale: [1, 2, 3]}]}
  - {type: instance, of: plain, scale: 0.5, rotate: [0, 90, 0]}
)",
                                  "groups.yaml", dir.path());
  ASSERT_EQ(scene.groups.size(), 2u);
  EXPECT_EQ(scene.groups[0].name, "a \"quoted\": name\\ with\tcontrol # and more");
  expect_round_trip(scene);
  const std::string yaml = scene_to_yaml(scene, "s");
  EXPECT_LT(yaml.find("s.mesh0.obj"), yaml.find("s.mesh1.obj"));  // the group's mesh first
  EXPECT_LT(yaml.find("groups:"), yaml.find("objects:"));
}

TEST(SceneWriter, MeshesReadBackFromTheirObjFiles) {
  MeshData data;
  data.positions = {Vec3(0.1, 0.2, 0.3), Vec3(1e-300, 0, -0.0), Vec3(0, 1.0 / 3, 0), Vec3(7, 8, 9)};
  data.normals = {Vec3(0, 0, 1), Vec3(0.6, 0.8, 0)};
  data.faces.push_back({{0, 1, 2}, {1, 0, 1}});
  data.faces.push_back({{3, 1, 2}, {-1, -1, -1}});
  const MeshData back = parse_obj(mesh_to_obj(data), "m.obj");
  ASSERT_EQ(back.positions.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_TRUE(back.positions[i] == data.positions[i]) << i;
  ASSERT_EQ(back.normals.size(), 2u);
  EXPECT_TRUE(back.normals[1] == data.normals[1]);
  ASSERT_EQ(back.faces.size(), 2u);
  for (std::size_t f = 0; f < 2; ++f) {
    EXPECT_EQ(back.faces[f].v, data.faces[f].v) << f;
    EXPECT_EQ(back.faces[f].n, data.faces[f].n) << f;
  }
  // A seed of 64 bits reads back from a scene file.
  EXPECT_EQ(parse_scene("render: {seed: 18446744073709551615}\nobjects: [{type: sphere, center: [0, 0, 0], radius: 1}]\n",
                        "s.yaml", ".")
                .settings.sampling.seed,
            18446744073709551615ull);
}

}  // namespace
}  // namespace strahl::scene_writer_test
