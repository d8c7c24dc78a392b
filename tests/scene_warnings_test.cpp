// Warnings that reach the user (docs/cli.md, "Warnings"): a one-sided light facing away from
// every object, a light too faint or too small to show, an ignored second YAML document — each
// one line, the render still done; and moving shapes counted in the summary.

#include <gtest/gtest.h>

#include "child_process.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::scene_warnings_test {
namespace {

const std::string kHead = "camera: {position: [0, 1, 3], look_at: [0, 0, 0], fov: 40}\nrender: {width: 16, height: 12}\n";
const std::string kObjects =
    "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n  - {type: triangle, vertices: [[-2, -1, -2], [2, -1, -2], [0, -1, 2]]}\n";

std::vector<std::string> warnings_of(const std::string& text) {
  return compile(parse_scene(text, "w.yaml", ".")).warnings;
}

std::string joined(const std::vector<std::string>& w) {
  std::string s;
  for (const std::string& line : w) s += line + "\n";
  return s;
}

TEST(SceneWarnings, AOneSidedLightFacingAwayFromEveryObject) {
  // Above the objects: edge_u × edge_v = x × z = −y points down (towards them), z × x points up.
  const auto rect = [](const char* u, const char* v) {
    return kHead + "lights:\n  - {type: rect, corner: [-0.5, 3, -0.5], edge_u: " + u + ", edge_v: " + v + "}\n" + kObjects;
  };
  EXPECT_TRUE(warnings_of(rect("[1, 0, 0]", "[0, 0, 1]")).empty()) << joined(warnings_of(rect("[1, 0, 0]", "[0, 0, 1]")));
  const std::vector<std::string> away = warnings_of(rect("[0, 0, 1]", "[1, 0, 0]"));
  ASSERT_EQ(away.size(), 1u);
  EXPECT_EQ(away[0].rfind("w.yaml:4:5: the rect light emits towards (0, 1, 0), away from every object", 0), 0u) << away[0];
  EXPECT_EQ(away[0].find('\n'), std::string::npos);
  const auto disk = [](const char* n) {
    return kHead + "lights:\n  - {type: disk, center: [0, 3, 0], normal: " + n + ", radius: 0.5}\n" + kObjects;
  };
  EXPECT_TRUE(warnings_of(disk("[0, -1, 0]")).empty());
  ASSERT_EQ(warnings_of(disk("[0, 1, 0]")).size(), 1u);
  EXPECT_NE(warnings_of(disk("[0, 1, 0]"))[0].find("disk light emits towards (0, 1, 0), away from every object"),
            std::string::npos);
  // A plane that is not parallel to the light reaches its front side: no warning.
  const std::string with_wall = kHead + "lights:\n  - {type: disk, center: [0, 3, 0], normal: [0, 1, 0], radius: 0.5}\n" +
                                kObjects + "  - {type: plane, normal: [1, 0, 0], distance: -5}\n";
  EXPECT_TRUE(warnings_of(with_wall).empty()) << joined(warnings_of(with_wall));
  // Solids count as objects: a light facing only a box, or only an unclipped quadric, is no warning.
  const std::string light = "lights:\n  - {type: disk, center: [0, 3, 0], normal: [0, -1, 0], radius: 0.5}\n";
  const std::string box = kHead + light + "objects:\n  - {type: box, corners: [[-1, -1, -1], [1, 1, 1]]}\n";
  EXPECT_TRUE(warnings_of(box).empty()) << joined(warnings_of(box));
  const std::string quadric =
      kHead + light + "objects:\n  - {type: quadric, coefficients: [1, 0, 1, 0, 0, 0, 0, 0, 0, -1]}\n";
  EXPECT_TRUE(warnings_of(quadric).empty()) << joined(warnings_of(quadric));
  const std::string box_behind = kHead + light + "objects:\n  - {type: box, corners: [[-1, 4, -1], [1, 5, 1]]}\n";
  EXPECT_EQ(warnings_of(box_behind).size(), 1u) << joined(warnings_of(box_behind));
}

TEST(SceneWarnings, ALightTooFaintOrTooSmallToShow) {
  const auto light = [](const std::string& l) { return kHead + "lights:\n  - " + l + "\n" + kObjects; };
  EXPECT_TRUE(warnings_of(light("{type: point, position: [2, 3, 2], intensity: 0.01}")).empty());
  const std::vector<std::string> faint = warnings_of(light("{type: point, position: [2, 3, 2], intensity: 1e-9}"));
  ASSERT_EQ(faint.size(), 1u);
  EXPECT_EQ(faint[0], "w.yaml:4:5: the light adds at most 1e-09 to any pixel (white is 1): too faint or too small to show");
  // A sphere light of radius 1e-6 at distance ~2 from the objects adds ~(1e-6/2)² of its radiance.
  EXPECT_EQ(warnings_of(light("{type: sphere, center: [0, 3, 0], radius: 1e-6}")).size(), 1u);
  EXPECT_TRUE(warnings_of(light("{type: sphere, center: [0, 3, 0], radius: 0.01}")).empty());
  // Bright enough to make up for its size: L·r²/d² = 1e10·1e-12/4 ≫ 1e-6.
  EXPECT_TRUE(warnings_of(light("{type: sphere, center: [0, 3, 0], radius: 1e-6, intensity: 1e10}")).empty());
  EXPECT_EQ(warnings_of(light("{type: directional, direction: [0, -1, 0], intensity: 1e-7}")).size(), 1u);
}

TEST(SceneWarnings, ASecondYamlDocumentIsNamed) {
  const std::string text = kHead + "lights:\n  - {type: point, position: [2, 3, 2]}\n" + kObjects +
                           "---\nobjects:\n  - {type: sphere, center: [5, 0, 0], radius: 1}\n";
  const Scene scene = parse_scene(text, "w.yaml", ".");
  EXPECT_EQ(scene.objects().size(), 2u);
  const std::vector<std::string> w = compile(scene).warnings;
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "w.yaml:8:1: a second YAML document starts here (after ---); only the first is read, the rest is ignored");
  EXPECT_TRUE(warnings_of(kHead + "lights:\n  - {type: point, position: [2, 3, 2]}\n" + kObjects).empty());
  // A --- opening the first document, comments and an end marker with nothing after: one document.
  EXPECT_TRUE(warnings_of("# a scene\n---\n" + kHead + "lights:\n  - {type: point, position: [2, 3, 2]}\n" + kObjects +
                          "...\n# the end\n")
                  .empty());
  // A `---` inside a quoted or block value is not at column 1 (YAML forbids it there anyway).
  EXPECT_EQ(warnings_of(kHead + "lights:\n  - {type: point, position: [2, 3, 2]}\n" + kObjects + "--- \n").size(), 1u);
}

TEST(SceneWarnings, ReachTheUserAsOneLineEachAndTheRenderGoesOn) {
  test::TempDir dir;
  test::write_text(dir / "w.yaml", kHead + "lights:\n  - {type: point, position: [2, 3, 2]}\n" +
                                       "  - {type: rect, corner: [-0.5, 3, -0.5], edge_u: [0, 0, 1], edge_v: [1, 0, 0]}\n" +
                                       kObjects + "  - {type: sphere, center: [0, 2, 0], radius: 0.3, motion: {velocity: [1, 0, 0]}}\n" +
                                       "---\n");
  const test::ChildResult r = test::run_child({STRAHL_CLI, "w.yaml", "-o", "w.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "w.png"));
  std::vector<std::string> warnings;
  std::istringstream err(r.err);
  for (std::string line; std::getline(err, line);)
    if (line.rfind("strahl: warning: ", 0) == 0) warnings.push_back(line);
  ASSERT_EQ(warnings.size(), 2u) << r.err;
  EXPECT_NE(warnings[0].find("w.yaml:10:1: a second YAML document starts here"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("w.yaml:5:5: the rect light emits towards (0, 1, 0)"), std::string::npos) << warnings[1];
  // The summary counts the moving sphere with the others; alone, its BVH is one leaf without a
  // box, and so not cut into time segments.
  EXPECT_NE(r.out.find("scene       2 spheres, 0 planes, 1 triangles, 0 solids, 2 lights (1 of the shapes moving)\n"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace strahl::scene_warnings_test
