// Scene files: what a good YAML/JSON file loads into, and that every error names the file,
// line and column of the offending value ("test.yaml:LINE:COL: message").

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <string>

#include "strahl/render/render_scene.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::scene_file_test {
namespace {

// The error message of parsing `text` as "test.yaml" (empty if it parses).
std::string error_of(const std::string& text, const fs::path& dir = ".") {
  try {
    parse_scene(text, "test.yaml", dir);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

// Line and column (1-based) where `needle` first occurs in `text`.
std::pair<int, int> position_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "'" << needle << "' is not in the test text";
  if (at == std::string::npos) return {0, 0};
  const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
  const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
  const int column = int(at - (line_start == std::string::npos || at == 0 ? 0 : line_start + 1)) + 1;
  return {line, column};
}

// The error names test.yaml, the line and column where `needle` begins, and mentions `mentions`.
::testing::AssertionResult error_at(const std::string& text, const std::string& needle, const std::string& mentions = {},
                                    const fs::path& dir = ".") {
  const std::string message = error_of(text, dir);
  if (message.empty()) return ::testing::AssertionFailure() << "no error for:\n" << text;
  const auto [line, column] = position_of(text, needle);
  const std::string prefix = "test.yaml:" + std::to_string(line) + ":" + std::to_string(column) + ":";
  if (message.rfind(prefix, 0) != 0)
    return ::testing::AssertionFailure() << "expected the message to begin with '" << prefix << "' (at '" << needle
                                         << "'), got: " << message;
  if (!mentions.empty() && message.find(mentions) == std::string::npos)
    return ::testing::AssertionFailure() << "expected the message to mention '" << mentions << "', got: " << message;
  return ::testing::AssertionSuccess() << message;
}

// A sphere that every scene below needs (a scene without objects is an error of its own).
const std::string kSphere = "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n";

TEST(SceneFile, FullSceneLoadsEveryField) {
  const std::string text = R"(camera:
  position: [1, 2, 3]
  look_at: [0, 0.5, 0]
  up: [0, 1, 0]
  fov: 40
  fov_axis: vertical
render:
  width: 64
  height: 32
  max_depth: 5
  min_weight: 0.01
  supersample: 3
  background: [0.1, 0.2, 0.3]
  ambient_light: 0.5
  medium_ior: water
materials:
  shiny: {color: [0.9, 0.1, 0.2], ambient: 0.2, diffuse: 0.6, specular: [0.5, 0.4, 0.3], shininess: 42,
          reflectivity: 0.25, transparency: 0.5, ior: diamond, fresnel: true, filter: true}
  tiles: {color: 1, checker: {size: 0.5, color: [0, 0, 0.1]}}
lights:
  - {type: point, position: [1, 5, 2], color: [1, 0.5, 0.25], intensity: 2}
  - {type: directional, direction: [0, -2, 0]}
objects:
  - {type: sphere, center: [0, 1, 0], radius: 0.5, material: shiny}
  - {type: plane, normal: [0, 1, 0], distance: -1, material: tiles}
  - type: triangle
    vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    material: {color: [0, 1, 0], ior: 1.7}
)";
  const Scene s = parse_scene(text, "test.yaml", ".");
  EXPECT_EQ(s.camera.position, Vec3(1, 2, 3));
  EXPECT_EQ(s.camera.look_at, Vec3(0, 0.5, 0));
  EXPECT_EQ(s.camera.fov_degrees, 40);
  EXPECT_EQ(s.camera.fov_axis, CameraDescription::FovAxis::Vertical);
  EXPECT_FALSE(s.camera.explicit_image_plane);
  EXPECT_EQ(s.settings.width, 64);
  EXPECT_EQ(s.settings.height, 32);
  EXPECT_EQ(s.settings.max_depth, 5);
  EXPECT_EQ(s.settings.min_weight, 0.01);
  EXPECT_EQ(s.settings.supersample, 3);
  EXPECT_EQ(s.settings.background, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(s.settings.ambient_light, Vec3(0.5));
  EXPECT_EQ(s.settings.medium_ior, 1.333);
  ASSERT_EQ(s.objects().size(), 3u);
  const auto* sphere = dynamic_cast<const Sphere*>(s.objects()[0].get());
  ASSERT_NE(sphere, nullptr);
  EXPECT_EQ(sphere->center, Vec3(0, 1, 0));
  EXPECT_EQ(sphere->radius, 0.5);
  const Material& m = sphere->material;
  EXPECT_EQ(m.color, Vec3(0.9, 0.1, 0.2));
  EXPECT_EQ(m.ambient, 0.2);
  EXPECT_EQ(m.diffuse, 0.6);
  EXPECT_EQ(m.specular, Vec3(0.5, 0.4, 0.3));
  EXPECT_EQ(m.shininess, 42);
  EXPECT_EQ(m.reflectivity, 0.25);
  EXPECT_EQ(m.transparency, 0.5);
  EXPECT_EQ(m.ior, 2.419);
  EXPECT_TRUE(m.fresnel);
  EXPECT_TRUE(m.filter);
  const auto* plane = dynamic_cast<const Plane*>(s.objects()[1].get());
  ASSERT_NE(plane, nullptr);
  EXPECT_EQ(plane->normal, Vec3(0, 1, 0));
  EXPECT_EQ(plane->distance, -1);
  EXPECT_EQ(plane->material.checker_size, 0.5);
  EXPECT_EQ(plane->material.checker_color, Vec3(0, 0, 0.1));
  EXPECT_EQ(plane->material.color, Vec3(1));
  const auto* tri = dynamic_cast<const Triangle*>(s.objects()[2].get());
  ASSERT_NE(tri, nullptr);
  EXPECT_EQ(tri->v1, Vec3(1, 0, 0));
  EXPECT_EQ(tri->material.color, Vec3(0, 1, 0));
  EXPECT_EQ(tri->material.ior, 1.7);
  EXPECT_EQ(tri->material.ambient, Material{}.ambient);  // unspecified fields keep the defaults
  ASSERT_EQ(s.lights().size(), 2u);
  EXPECT_EQ(s.lights()[0].kind, LightKind::Point);
  EXPECT_EQ(s.lights()[0].position, Vec3(1, 5, 2));
  EXPECT_EQ(s.lights()[0].radiance, Vec3(2, 1, 0.5));
  EXPECT_EQ(s.lights()[1].kind, LightKind::Directional);
  // Compiles, with the directional light normalised.
  const RenderScene rs = compile(s);
  EXPECT_VEC_NEAR(rs.lights[1].direction, Vec3(0, -1, 0), 1e-15);
  EXPECT_EQ(rs.supersample, 3);
}

TEST(SceneFile, ExplicitImagePlane) {
  const Scene s = parse_scene("camera:\n  position: [0, 0, 5]\n  look_at: [0, 0, 0]\n"
                              "  image_plane: {l: -2, r: 1, b: -0.5, t: 0.75, d: 3}\n" + kSphere,
                              "test.yaml", ".");
  EXPECT_TRUE(s.camera.explicit_image_plane);
  EXPECT_EQ(s.camera.l, -2);
  EXPECT_EQ(s.camera.r, 1);
  EXPECT_EQ(s.camera.b, -0.5);
  EXPECT_EQ(s.camera.t, 0.75);
  EXPECT_EQ(s.camera.d, 3);
}

TEST(SceneFile, JsonIsAccepted) {
  const std::string json = R"({
  "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0], "fov": 45},
  "render": {"width": 8, "height": 6},
  "materials": {"red": {"color": [1, 0, 0], "ior": "acrylic"}},
  "lights": [{"type": "point", "position": [2, 3, 4]}],
  "objects": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 1.5, "material": "red"},
    {"type": "plane", "normal": [0, 1, 0], "distance": -1.5}
  ]
})";
  const Scene s = parse_scene(json, "test.json", ".");
  EXPECT_EQ(s.settings.width, 8);
  ASSERT_EQ(s.objects().size(), 2u);
  EXPECT_EQ(s.objects()[0]->material.color, Vec3(1, 0, 0));
  EXPECT_EQ(s.objects()[0]->material.ior, 1.491);
  ASSERT_EQ(s.lights().size(), 1u);
  EXPECT_EQ(s.lights()[0].position, Vec3(2, 3, 4));
  EXPECT_NO_THROW(compile(s));
}

TEST(SceneFile, JsonErrorsNameLineAndColumnToo) {
  const std::string json = "{\n  \"objects\": [\n    {\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": \"big\"}\n  ]\n}\n";
  EXPECT_TRUE(error_at(json, "\"big\"", "radius"));
}

TEST(SceneFile, UnknownKey) {
  EXPECT_TRUE(error_at("camera:\n  position: [0, 0, 5]\n  look_at: [0, 0, 0]\n  colour: 3\n" + kSphere, "colour", "colour"));
  EXPECT_TRUE(error_at(kSphere + "lights:\n  - {type: point, position: [0, 1, 0], size: 2}\n", "size", "size"));
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, 0, 0]\n    radius: 1\n    radus: 2\n", "radus", "radus"));
  EXPECT_TRUE(error_at("materials:\n  m: {colour: [1, 0, 0]}\n" + kSphere, "colour", "colour"));
  EXPECT_TRUE(error_at("render:\n  widht: 10\n" + kSphere, "widht", "widht"));
  EXPECT_TRUE(error_at("scene: 1\n" + kSphere, "scene", "scene"));
}

TEST(SceneFile, WrongType) {
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, 0, 0]\n    radius: big\n", "big", "radius"));
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, zero, 0]\n    radius: 1\n", "zero", "center"));
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: 5\n    radius: 1\n", "5", "center"));
  EXPECT_TRUE(error_at("render:\n  width: wide\n" + kSphere, "wide", "width"));
  EXPECT_TRUE(error_at("render:\n  width: 12.5\n" + kSphere, "12.5", "width"));
  EXPECT_TRUE(error_at("materials:\n  m: {fresnel: maybe}\n" + kSphere, "maybe", "fresnel"));
  EXPECT_TRUE(error_at("materials:\n  m: {diffuse: [1, 2, 3]}\n" + kSphere, "[1, 2, 3]", "diffuse"));
}

TEST(SceneFile, ImpossibleValues) {
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, 0, 0]\n    radius: -1\n", "-1", "radius"));
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, 0, 0]\n    radius: 0\n", "0\n", "radius"));
  EXPECT_TRUE(error_at("objects:\n  - type: plane\n    normal: [0, 0, 0]\n", "[0, 0, 0]", "normal"));
  EXPECT_TRUE(error_at("materials:\n  m: {transparency: 1.5}\n" + kSphere, "1.5", "transparency"));
  EXPECT_TRUE(error_at("materials:\n  m: {color: [1, -0.5, 0]}\n" + kSphere, "[1, -0.5", "color"));
  EXPECT_TRUE(error_at("render:\n  width: 0\n" + kSphere, "0\n", "width"));
  EXPECT_TRUE(error_at("render:\n  max_depth: 65\n" + kSphere, "65", "max_depth"));
  EXPECT_TRUE(error_at(kSphere + "lights:\n  - {type: directional, direction: [0, 0, 0]}\n", "[0, 0, 0]}", "direction"));
  EXPECT_TRUE(error_at("objects:\n  - type: triangle\n    vertices: [[0, 0, 0], [1, 1, 1], [2, 2, 2]]\n", "[[",
                       "degenerate"));
}

TEST(SceneFile, NanAndInfinityAreRejected) {
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, 0, 0]\n    radius: .nan\n", ".nan", "radius"));
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, .nan, 0]\n    radius: 1\n", ".nan", "center"));
  EXPECT_TRUE(error_at("objects:\n  - type: plane\n    normal: [0, 1, 0]\n    distance: .inf\n", ".inf", "distance"));
  EXPECT_TRUE(error_at("camera:\n  position: [0, 0, .NaN]\n" + kSphere, ".NaN", "position"));
  EXPECT_TRUE(error_at("materials:\n  m: {shininess: .nan}\n" + kSphere, ".nan", "shininess"));
}

TEST(SceneFile, MissingRequiredKey) {
  // Reported at the object (the mapping that lacks the key).
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    center: [0, 0, 0]\n", "type: sphere", "radius"));
  EXPECT_TRUE(error_at("objects:\n  - {type: sphere, radius: 1}\n", "{type", "center"));
  EXPECT_TRUE(error_at("objects:\n  - {center: [0, 0, 0], radius: 1}\n", "{center", "type"));
  EXPECT_TRUE(error_at(kSphere + "lights:\n  - {type: point}\n", "{type: point", "position"));
  EXPECT_TRUE(error_at("camera:\n  image_plane: {l: -1, r: 1, b: -1, t: 1}\n" + kSphere, "{l:", "'d'"));
}

TEST(SceneFile, UnknownNames) {
  EXPECT_TRUE(error_at("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: shiny}\n", "shiny",
                       "unknown material 'shiny'"));
  EXPECT_TRUE(error_at("materials:\n  glass: {ior: unobtainium}\n" + kSphere, "unobtainium", "unknown ior"));
  EXPECT_TRUE(error_at("render:\n  medium_ior: jelly\n" + kSphere, "jelly", "unknown medium_ior 'jelly'"));
  // A value out of range names the key it was given under.
  EXPECT_TRUE(error_at("render:\n  medium_ior: -1\n" + kSphere, "-1", "medium_ior"));
  EXPECT_TRUE(error_at("materials:\n  glass: {ior: 0}\n" + kSphere, "0}", "ior"));
  EXPECT_TRUE(error_at("objects:\n  - {type: cube, center: [0, 0, 0]}\n", "cube", "cube"));
  EXPECT_TRUE(error_at(kSphere + "lights:\n  - {type: laser, position: [0, 1, 0]}\n", "laser", "laser"));
  EXPECT_TRUE(error_at("camera:\n  fov_axis: diagonal\n" + kSphere, "diagonal", "fov_axis"));
}

// A spot light: its axis from point_at or direction, its angles in degrees (defaults 30 and 45,
// tightness 0), colour × intensity; what is wrong is named where it stands.
TEST(SceneFile, SpotLights) {
  const Scene s = parse_scene(kSphere + "lights:\n"
                                        "  - {type: spot, position: [0, 4, 0], point_at: [1, 0, 0]}\n"
                                        "  - {type: spot, position: [1, 2, 3], direction: [0, -2, 0], angle: 10, falloff: 12.5, "
                                        "tightness: 4, color: [1, 0.5, 0.25], intensity: 2}\n",
                              "test.yaml", ".");
  ASSERT_EQ(s.lights().size(), 2u);
  const Light& a = s.lights()[0];
  EXPECT_EQ(a.kind, LightKind::Spot);
  EXPECT_EQ(a.position, Vec3(0, 4, 0));
  EXPECT_EQ(a.direction, Vec3(1, -4, 0));  // point_at − position (compile() normalises it)
  EXPECT_EQ(a.angle, 30);
  EXPECT_EQ(a.falloff, 45);
  EXPECT_EQ(a.tightness, 0);
  EXPECT_EQ(a.radiance, Vec3(1));
  const Light& b = s.lights()[1];
  EXPECT_EQ(b.direction, Vec3(0, -2, 0));
  EXPECT_EQ(b.angle, 10);
  EXPECT_EQ(b.falloff, 12.5);
  EXPECT_EQ(b.tightness, 4);
  EXPECT_EQ(b.radiance, Vec3(2, 1, 0.5));
  const std::string spot = kSphere + "lights:\n  - {type: spot, position: [0, 4, 0], ";
  EXPECT_TRUE(error_at(spot + "point_at: [0, 0, 0], direction: [0, -1, 0]}\n", "[0, -1, 0]", "not both"));
  EXPECT_TRUE(error_at(spot + "angle: 10}\n", "{type: spot", "point_at or direction"));
  EXPECT_TRUE(error_at(spot + "point_at: [0, 4, 0]}\n", "[0, 4, 0]}", "spotlight direction"));
  EXPECT_TRUE(error_at(spot + "direction: [0, 0.0, 0]}\n", "[0, 0.0, 0]", "spotlight direction"));
  EXPECT_TRUE(error_at(spot + "direction: [0, -1, 0], angle: 91}\n", "91", "spotlight angle must lie in [0, 90]"));
  EXPECT_TRUE(error_at(spot + "direction: [0, -1, 0], falloff: -1}\n", "-1}", "spotlight falloff"));
  EXPECT_TRUE(error_at(spot + "direction: [0, -1, 0], tightness: -2}\n", "-2", "spotlight tightness"));
  EXPECT_TRUE(error_at(spot + "direction: [0, -1, 0], radius: 2}\n", "radius: 2", "unknown key 'radius'"));
  // Point and spot lights fade with distance where fade_power > 0 (POV-Ray's fade).
  const Scene f = parse_scene(kSphere + "lights:\n"
                                        "  - {type: point, position: [0, 4, 0], fade_distance: 2, fade_power: 1.5}\n"
                                        "  - {type: spot, position: [0, 4, 0], direction: [0, -1, 0], fade_power: 2, "
                                        "fade_distance: 0.5}\n",
                              "test.yaml", ".");
  EXPECT_EQ(f.lights()[0].fade_distance, 2);
  EXPECT_EQ(f.lights()[0].fade_power, 1.5);
  EXPECT_EQ(f.lights()[1].fade_distance, 0.5);
  EXPECT_EQ(f.lights()[1].fade_power, 2);
  EXPECT_TRUE(error_at(spot + "direction: [0, -1, 0], fade_power: -2}\n", "-2}", "light fade_power must not be negative"));
  EXPECT_TRUE(error_at(spot + "direction: [0, -1, 0], fade_power: 2}\n", "2}",
                       "a light's fade_power needs a positive fade_distance"));
  EXPECT_TRUE(error_at(kSphere + "lights:\n  - {type: directional, direction: [0, -1, 0], fade_power: 2}\n", "fade_power",
                       "unknown key 'fade_power' in directional light"));
}

TEST(SceneFile, RepeatedKeysAndMaterialNames) {
  EXPECT_TRUE(error_at("render:\n  width: 10\n  width: 20\n" + kSphere, "width: 20", "width"));
  EXPECT_TRUE(error_at("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, radius: 2}\n", "radius: 2", "radius"));
  EXPECT_TRUE(error_at("materials:\n  m: {color: 1}\n  m: {color: 0.5}\n" + kSphere, "m: {color: 0.5}", "'m'"));
}

TEST(SceneFile, AccelerationStructure) {
  EXPECT_EQ(parse_scene("render: {accel: naive}\n" + kSphere, "test.yaml", ".").settings.accel, AccelKind::Naive);
  EXPECT_EQ(parse_scene("render: {accel: bvh}\n" + kSphere, "test.yaml", ".").settings.accel, AccelKind::Bvh);
  EXPECT_EQ(parse_scene(kSphere, "test.yaml", ".").settings.accel, AccelKind::Bvh);
  EXPECT_TRUE(error_at("render:\n  accel: octopus\n" + kSphere, "octopus", "octopus"));
}

TEST(SceneFile, ValueSyntax) {
  // Booleans: YAML 1.2's true/false, not 1.1's yes/no, nor 1/0.
  EXPECT_TRUE(parse_scene("materials:\n  m: {fresnel: True}\n" + kSphere, "test.yaml", ".").objects().size() == 1);
  EXPECT_TRUE(error_at("materials:\n  m: {fresnel: yes}\n" + kSphere, "yes", "true or false"));
  EXPECT_TRUE(error_at("materials:\n  m: {fresnel: 1}\n" + kSphere, "1}", "fresnel"));
  // Whole numbers take any number of whole value (640.0, 1e3), not 640.5; numbers take
  // scientific notation (tests/number_syntax_test.cpp has the rest of YAML 1.2's core schema).
  EXPECT_EQ(parse_scene("render:\n  width: 640.0\n  height: 1e3\n" + kSphere, "test.yaml", ".").settings.height, 1000);
  EXPECT_TRUE(error_at("render:\n  width: 640.5\n" + kSphere, "640.5", "width"));
  const Scene s = parse_scene("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1.5e-3}\n", "test.yaml", ".");
  EXPECT_EQ(dynamic_cast<const Sphere&>(*s.objects()[0]).radius, 1.5e-3);
  // A grey colour as one number.
  const Scene g = parse_scene("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: {color: 0.25}}\n",
                              "test.yaml", ".");
  EXPECT_EQ(g.objects()[0]->material.color, Vec3(0.25));
  // Anchors and aliases reuse a whole value.
  const Scene a = parse_scene("materials:\n  m: &red {color: [1, 0, 0]}\n"
                              "objects:\n  - {type: sphere, center: &c [1, 2, 3], radius: 1, material: *red}\n"
                              "  - {type: sphere, center: *c, radius: 2}\n",
                              "test.yaml", ".");
  ASSERT_EQ(a.objects().size(), 2u);
  EXPECT_EQ(a.objects()[0]->material.color, Vec3(1, 0, 0));
  EXPECT_EQ(dynamic_cast<const Sphere&>(*a.objects()[1]).center, Vec3(1, 2, 3));
  // Materials may be defined below the objects that use them.
  EXPECT_EQ(parse_scene("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: m}\n"
                        "materials:\n  m: {color: 0.5}\n",
                        "test.yaml", ".")
                .objects()[0]
                ->material.color,
            Vec3(0.5));
}

TEST(SceneFile, CompileTimeChecksPointAtTheDefiningMap) {
  // A resolution over 2^28 pixels (e.g. after a command-line override) is found by compile();
  // the error names the render section.
  Scene s = parse_scene(kSphere + "render:\n  width: 100\n  height: 100\n", "test.yaml", ".");
  s.settings.width = 65536;
  s.settings.height = 65536;
  try {
    compile(s);
    FAIL() << "no error for 2^32 pixels";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("test.yaml:4:3:", 0), 0u) << e.what();
  }
}

TEST(SceneFile, NamedIndicesOfRefraction) {
  const std::string text = "materials:\n"
                           "  a: {ior: air}\n  b: {ior: ice}\n  c: {ior: acrylic}\n  d: {ior: diamond}\n  e: {ior: vacuum}\n"
                           "objects:\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 1, material: a}\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 1, material: b}\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 1, material: c}\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 1, material: d}\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 1, material: e}\n";
  const Scene s = parse_scene(text, "test.yaml", ".");
  ASSERT_EQ(s.objects().size(), 5u);
  EXPECT_EQ(s.objects()[0]->material.ior, 1.0003);
  EXPECT_EQ(s.objects()[1]->material.ior, 1.31);
  EXPECT_EQ(s.objects()[2]->material.ior, 1.491);
  EXPECT_EQ(s.objects()[3]->material.ior, 2.419);
  EXPECT_EQ(s.objects()[4]->material.ior, 1.0);
}

TEST(SceneFile, YamlSyntaxError) {
  // A tab where indentation is expected, at the start of line 3.
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n\tcenter: [0, 0, 0]\n", "\tcenter", "syntax error"));
  // A flow mapping closed by the wrong bracket: at that bracket.
  EXPECT_TRUE(error_at("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1]\n", "]\n", "syntax error"));
  // A key with two values, "radius: 1: 2": at the second colon.
  EXPECT_TRUE(error_at("objects:\n  - type: sphere\n    radius: 1: 2\n", ": 2", "syntax error"));
  // An unclosed flow mapping: noticed at the end of the text (line 2).
  const std::string unclosed = error_of("objects: [ {type: sphere\n");
  EXPECT_EQ(unclosed.rfind("test.yaml:2:", 0), 0u) << unclosed;
}

// The objects list's elements are parsed a batch (512) at a time on all cores and read in the
// file's order: the objects keep their order, and of two errors in different batches the first in
// the file is reported, whichever thread met the other.
TEST(SceneFile, ObjectsParsedInBatchesKeepTheFilesOrder) {
  const auto scene_text = [](int bad_radius, int bad_merge) {
    std::string text = "objects:\n";
    for (int i = 0; i < 1200; ++i) {
      if (i == bad_radius) text += "  - {type: sphere, center: [0, 0, 0], radius: -1}\n";
      else if (i == bad_merge) text += "  - {<<: 1, type: sphere, center: [0, 0, 0], radius: 1}\n";
      else text += "  - {type: sphere, center: [" + std::to_string(i) + ", 0, 0], radius: 1}\n";
    }
    return text;
  };
  const Scene scene = parse_scene(scene_text(-1, -1), "test.yaml", ".");
  ASSERT_EQ(scene.objects().size(), 1200u);
  for (int i = 0; i < 1200; ++i) {
    const auto* sphere = dynamic_cast<const Sphere*>(scene.objects()[std::size_t(i)].get());
    ASSERT_NE(sphere, nullptr);
    EXPECT_EQ(sphere->center.x, Real(i));
    EXPECT_EQ(sphere->loc.line, i + 2);
  }
  EXPECT_TRUE(error_at(scene_text(700, 900), "-1}", "radius"));
  EXPECT_TRUE(error_at(scene_text(900, 700), "1, type", "merge key"));
  EXPECT_TRUE(error_at(scene_text(100, 1100), "-1}", "radius"));
}

TEST(SceneFile, CameraUpParallelToView) {
  // Either the camera section or the up vector may carry the blame; both name the right place.
  const std::string text = "camera:\n  position: [0, 0, 5]\n  look_at: [0, 0, 0]\n  up: [0, 0, 1]\n" + kSphere;
  const std::string message = error_of(text);
  EXPECT_TRUE(message.rfind("test.yaml:2:3:", 0) == 0 || message.rfind("test.yaml:4:7:", 0) == 0) << message;
  EXPECT_NE(message.find("parallel"), std::string::npos) << message;
  // The default up (0, 1, 0) with a camera looking straight down: the camera section.
  EXPECT_TRUE(error_at("camera:\n  position: [0, 5, 0]\n  look_at: [0, 0, 0]\n" + kSphere, "position", "parallel"));
  EXPECT_TRUE(error_at("camera:\n  up: [0, 0, 0]\n" + kSphere, "[0, 0, 0]", "up"));
}

TEST(SceneFile, FovOutOfRange) {
  for (const char* fov : {"180", "0", "-30", "200", "1e9"})
    EXPECT_TRUE(error_at(std::string("camera:\n  fov: ") + fov + "\n" + kSphere, fov, "fov")) << fov;
  EXPECT_EQ(error_of("camera:\n  fov: 179.5\n" + kSphere), "");
  EXPECT_EQ(error_of("camera:\n  fov: 0.5\n" + kSphere), "");
}

TEST(SceneFile, ImagePlaneBoundsMustBeOrdered) {
  EXPECT_TRUE(error_at("camera:\n  image_plane: {l: 1, r: 1, b: -1, t: 1, d: 1}\n" + kSphere, "{l:", "l < r"));
  EXPECT_TRUE(error_at("camera:\n  image_plane: {l: 2, r: 1, b: -1, t: 1, d: 1}\n" + kSphere, "{l:", "l < r"));
  EXPECT_TRUE(error_at("camera:\n  image_plane: {l: -1, r: 1, b: 1, t: -1, d: 1}\n" + kSphere, "{l:", "b < t"));
  EXPECT_TRUE(error_at("camera:\n  image_plane: {l: -1, r: 1, b: -1, t: 1, d: 0}\n" + kSphere, "0}", "d"));
  EXPECT_TRUE(error_at("camera:\n  fov: 40\n  image_plane: {l: -1, r: 1, b: -1, t: 1, d: 1}\n" + kSphere, "{l:"));
}

TEST(SceneFile, EmptyOrObjectlessSceneIsAnError) {
  EXPECT_FALSE(error_of("").empty());
  EXPECT_FALSE(error_of("camera:\n  fov: 40\n").empty());
  EXPECT_TRUE(error_at("- 1\n- 2\n", "- 1"));
}

class SceneFileMesh : public ::testing::Test {
 protected:
  test::TempDir dir_;
};

TEST_F(SceneFileMesh, MeshPathIsRelativeToTheSceneDirectory) {
  fs::create_directories(dir_ / "models");
  test::write_text(dir_ / "models" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  test::write_text(dir_ / "scene.yaml",
                   "objects:\n  - {type: mesh, file: models/tri.obj, scale: 2, translate: [0, 0, -1]}\n");
  const Scene s = load_scene(dir_ / "scene.yaml");
  ASSERT_EQ(s.objects().size(), 1u);
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.triangles.size(), 1u);
  EXPECT_VEC_NEAR(rs.triangles[0].v1, Vec3(2, 0, -1), 1e-15);
}

TEST_F(SceneFileMesh, MissingMeshFileNamesTheSceneLocation) {
  const std::string text = "objects:\n  - type: mesh\n    file: nothere.obj\n";
  EXPECT_TRUE(error_at(text, "nothere.obj", "nothere.obj", dir_.path()));
}

TEST_F(SceneFileMesh, BrokenMeshFileNamesTheSceneLocation) {
  test::write_text(dir_ / "empty.obj", "# no faces\nv 0 0 0\n");
  EXPECT_TRUE(error_at("objects:\n  - {type: mesh, file: empty.obj}\n", "empty.obj", "empty.obj", dir_.path()));
}

TEST_F(SceneFileMesh, ZeroMeshScaleIsRejected) {
  test::write_text(dir_ / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(error_at("objects:\n  - {type: mesh, file: tri.obj, scale: [1, 0, 1]}\n", "[1, 0, 1]", "scale", dir_.path()));
}

TEST_F(SceneFileMesh, LoadSceneErrorsNameTheFile) {
  try {
    load_scene(dir_ / "absent.yaml");
    FAIL() << "no error for a missing scene file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.yaml"), std::string::npos) << e.what();
  }
  test::write_text(dir_ / "scene.txt", kSphere);
  EXPECT_THROW(load_scene(dir_ / "scene.txt"), Error);
  test::write_text(dir_ / "bad.yaml", "objects:\n  - {type: sphere, center: [0, 0, 0], radius: -2}\n");
  try {
    load_scene(dir_ / "bad.yaml");
    FAIL() << "no error for a negative radius";
  } catch (const Error& e) {
    const std::string expected = (dir_ / "bad.yaml").string() + ":2:";
    EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what();
  }
}

TEST(SceneFile, ShippedScenesLoad) {
  for (const char* name : {"lecture.yaml", "lecture-whitted.yaml"}) {
    const Scene s = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / name);
    EXPECT_EQ(s.objects().size(), 6u) << name;
    EXPECT_EQ(s.lights().size(), 1u) << name;
    EXPECT_NO_THROW(compile(s)) << name;
  }
}

}  // namespace
}  // namespace strahl::scene_file_test
