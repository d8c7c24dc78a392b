// YAML merge keys in scene files (scene/yaml_merge.h): `<<: *name` and `<<: [*a, *b]` add the
// keys a map does not set itself, in materials, objects and nested merges, in both of the
// loader's ways of reading objects; bad merges are errors at file:line:column, and aliases that
// reach one map many times expand it once.

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/util/error.h"

namespace strahl::yaml_merge_test {
namespace {

Scene parse(const std::string& text) { return parse_scene(text, "m.yaml", "."); }

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const Sphere& sphere(const Scene& s, std::size_t i) { return dynamic_cast<const Sphere&>(*s.objects().at(i)); }

TEST(YamlMerge, MaterialsTakeTheKeysTheyDoNotSet) {
  const Scene s = parse(R"(materials:
  glass: &glass {color: 0.9, transparency: 0.9, ior: glass, specular: 0.8, shininess: 200}
  flint: {<<: *glass, ior: 1.62}
  tinted: {<<: [{color: [1, 0, 0], shininess: 7}, *glass], diffuse: 0.3}
objects:
  - {type: sphere, center: [0, 0, 0], radius: 1, material: glass}
  - {type: sphere, center: [3, 0, 0], radius: 1, material: flint}
  - {type: sphere, center: [6, 0, 0], radius: 1, material: tinted}
)");
  const Material& glass = s.objects()[0]->material;
  const Material& flint = s.objects()[1]->material;
  const Material& tinted = s.objects()[2]->material;
  EXPECT_EQ(glass.ior, 1.5);
  EXPECT_EQ(flint.ior, 1.62);
  EXPECT_EQ(flint.transparency, glass.transparency);
  EXPECT_EQ(flint.specular, glass.specular);
  EXPECT_EQ(flint.shininess, glass.shininess);
  EXPECT_EQ(flint.color, glass.color);
  // Of a list, the earlier map wins; the map's own key wins over both.
  EXPECT_EQ(tinted.color, Vec3(1, 0, 0));
  EXPECT_EQ(tinted.shininess, 7);
  EXPECT_EQ(tinted.ior, 1.5);
  EXPECT_EQ(tinted.diffuse, 0.3);
}

TEST(YamlMerge, ObjectsAndNestedMerges) {
  const Scene s = parse(R"(objects:
  - &ball {type: sphere, center: [0, 0, 0], radius: 0.5}
  - &moved {<<: *ball, center: [2, 0, 0]}
  - {<<: *moved, radius: 0.25}
)");
  ASSERT_EQ(s.objects().size(), 3u);
  EXPECT_EQ(sphere(s, 0).center, Vec3(0, 0, 0));
  EXPECT_EQ(sphere(s, 1).center, Vec3(2, 0, 0));
  EXPECT_EQ(sphere(s, 1).radius, 0.5);
  EXPECT_EQ(sphere(s, 2).center, Vec3(2, 0, 0));
  EXPECT_EQ(sphere(s, 2).radius, 0.25);
}

// Without anchors the top-level objects are read one element at a time: a merge of a map
// written in place works there too, and its errors keep their lines.
TEST(YamlMerge, ElementByElementReading) {
  const Scene s = parse(R"(objects:
  - type: sphere
    <<: {center: [1, 2, 3], radius: 2}
  - type: sphere
    center: [0, 0, 0]
    radius: 1
)");
  ASSERT_EQ(s.objects().size(), 2u);
  EXPECT_EQ(sphere(s, 0).center, Vec3(1, 2, 3));
  EXPECT_EQ(sphere(s, 0).radius, 2);
  EXPECT_EQ(error_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n  - type: sphere\n"
                     "    <<: {center: [1, 2, 3], radius: -2}\n"),
            "m.yaml:4:37: sphere radius must be positive (got -2)");
}

TEST(YamlMerge, BadMergesNameTheirPlace) {
  const std::string sphere_line = "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n";
  EXPECT_EQ(error_of("materials:\n  a: {<<: 3}\n" + sphere_line),
            "m.yaml:2:11: a merge key '<<' must name a map (<<: *name) or a list of maps (<<: [*a, *b])");
  EXPECT_EQ(error_of("materials:\n  a: &a {color: 1}\n  b: {<<: [*a, [1, 2]]}\n" + sphere_line),
            "m.yaml:3:16: a merge key's list must hold maps only (<<: [*a, *b])");
  EXPECT_EQ(error_of("materials:\n  a: &a {color: 1}\n  b: {<<: *a, <<: *a}\n" + sphere_line),
            "m.yaml:3:6: repeated merge key '<<' (merge several maps with a list: <<: [*a, *b])");
  // A merged key the map does not take is the unknown key it is, where it is written.
  EXPECT_EQ(error_of("materials:\n  a: &a {color: 1, radius: 2}\n  b: {<<: *a}\n" + sphere_line).substr(0, 42),
            "m.yaml:2:20: unknown key 'radius' in mater");
  EXPECT_EQ(error_of("camera: &c {position: [0, 0, 5], fov: 50}\nrender: {<<: *c}\n" + sphere_line).substr(0, 44),
            "m.yaml:1:13: unknown key 'position' in rende");
}

// Lists of lists that share their halves by aliases reach the innermost map 2^40 times: it is
// expanded once, and the file is refused (unknown keys) at once instead of after hours.
TEST(YamlMerge, SharedNodesAreExpandedOnce) {
  std::string text = "l0: &l0 [{<<: {color: 1}}]\n";
  for (int i = 1; i <= 40; ++i)
    text += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [*l" + std::to_string(i - 1) + ", *l" +
            std::to_string(i - 1) + "]\n";
  text += "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n";
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(error_of(text).substr(0, 29), "m.yaml:1:1: unknown key 'l0' ");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

}  // namespace
}  // namespace strahl::yaml_merge_test
