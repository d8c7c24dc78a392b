// The `strahl` command line: exit codes 0 (rendered), 1 (usage error), 2 (scene or I/O error),
// and an existing output image left untouched when a run fails.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <limits>
#include <string>

#include "strahl/image/image_io.h"
#include "strahl/scene/scene_file.h"
#include "strahl/version.h"
#include "test_helpers.h"

namespace strahl::cli_test {
namespace {

const char* kGoodScene = R"(camera: {position: [0, 1, 3], look_at: [0, 0, 0], fov: 40}
render: {width: 320, height: 240}
lights:
  - {type: point, position: [2, 3, 2]}
objects:
  - {type: plane, normal: [0, 1, 0], distance: -1}
  - {type: sphere, center: [0, 0, 0], radius: 1, material: {color: [0.9, 0.2, 0.1]}}
)";

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_text(dir_ / "scene.yaml", kGoodScene);
    test::write_text(dir_ / "bad.yaml", "objects:\n  - {type: sphere, center: [0, 0, 0], radius: -1}\n");
  }

  // Runs the CLI in the temporary directory with `args`; returns its exit status.
  int run(const std::string& args) {
    const std::string command = "cd '" + dir_.path().string() + "' && '" STRAHL_CLI "' " + args + " > '" +
                                (dir_ / "log.txt").string() + "' 2>&1";
    const int status = std::system(command.c_str());
    if (status == -1 || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
  }
  std::string log() const { return test::read_text(dir_ / "log.txt"); }

  test::TempDir dir_;
};

TEST_F(Cli, RendersASmallSceneAndExitsZero) {
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 -q -o out.png"), 0) << log();
  ASSERT_TRUE(fs::exists(dir_ / "out.png"));
  const Image img = read_image(dir_ / "out.png");
  EXPECT_EQ(img.width(), 16);
  EXPECT_EQ(img.height(), 12);
  // The red sphere is in the middle of the picture.
  const Rgb centre = img.at(8, 6);
  EXPECT_GT(centre.r, centre.g);
  EXPECT_GT(centre.r, 0.1f);
}

TEST_F(Cli, FloatOutputMatchesTheLibraryRender) {
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --supersample 2 -q -o out.pfm"), 0) << log();
  Scene s = load_scene(dir_ / "scene.yaml");
  s.settings.width = 16;
  s.settings.height = 12;
  s.settings.supersample = 2;
  EXPECT_TRUE(read_image(dir_ / "out.pfm") == test::render_image(s));
}

TEST_F(Cli, RendersTheBuiltInLectureSceneWithoutAFile) {
  ASSERT_EQ(run("--width 16 --height 9 --threads 2 -o lecture.ppm"), 0) << log();
  EXPECT_TRUE(fs::exists(dir_ / "lecture.ppm"));
  EXPECT_NE(log().find("rays"), std::string::npos) << "the summary is printed unless --quiet";
}

// The summary names the time segments of the moving shapes' BVH beside the moving shapes, or,
// where only instances move, beside those. A spinning triangle or mesh is held as an instance of
// itself, but counts as a moving shape of the scene's: no instances line for it.
TEST_F(Cli, SummaryNamesTheTimeSegmentsWhereTheMovingThingsAre) {
  test::write_text(dir_ / "spin.yaml", std::string(kGoodScene) +
                                           "  - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], motion: "
                                           "{spin: {axis: [0, 0, 1], angle: 120}}}\n");
  ASSERT_EQ(run("spin.yaml --width 8 --height 8 -o spin.png"), 0) << log();
  EXPECT_NE(log().find("scene       1 spheres, 1 planes, 1 triangles, 0 solids, 1 lights (1 of the shapes moving, "
                       "their BVH cut into "),
            std::string::npos)
      << log();
  EXPECT_EQ(log().find("instances"), std::string::npos) << log();
  test::write_text(dir_ / "spin.yaml", std::string(kGoodScene) +
                                           "  - {type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: "
                                           "[0, 0, 1], angle: 120}}}\n");
  ASSERT_EQ(run("spin.yaml --width 8 --height 8 -o spin.png"), 0) << log();
  EXPECT_NE(log().find("1 solids, 1 lights (1 of the shapes moving, their BVH cut into "), std::string::npos) << log();
  // Only instances move: a group's spinning triangle rides with each of its two instances.
  test::write_text(dir_ / "spin.yaml", std::string(kGoodScene) +
                                           "  - {type: instance, of: flag}\n"
                                           "  - {type: instance, of: flag, translate: [2, 0, 0]}\n"
                                           "groups:\n  flag:\n    - {type: sphere, center: [0, 0, 0], radius: 0.1}\n"
                                           "    - {type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
                                           "motion: {spin: {axis: [0, 0, 1], angle: 120}}}\n");
  ASSERT_EQ(run("spin.yaml --width 8 --height 8 -o spin.png"), 0) << log();
  EXPECT_NE(log().find("scene       1 spheres, 1 planes, 0 triangles, 0 solids, 1 lights\ninstances   4 instances (2 "
                       "moving, their BVH cut into "),
            std::string::npos)
      << log();
  EXPECT_NE(log().find("time segments) of 1 groups (1 spheres, 1 triangles, 0 solids, once;"), std::string::npos)
      << log();
}

// Nested instances are counted as the records they unfold into, and the line says so.
TEST_F(Cli, SummarySaysTheInstancesWereUnfolded) {
  test::write_text(dir_ / "nested.yaml", std::string(kGoodScene) +
                                             "  - {type: instance, of: pair, translate: [0, 0, -2]}\n"
                                             "groups:\n  ball: [{type: sphere, center: [0, 0, 0], radius: 0.2}]\n"
                                             "  pair: [{type: instance, of: ball}, {type: instance, of: ball, "
                                             "translate: [1, 0, 0]}]\n");
  ASSERT_EQ(run("nested.yaml --width 8 --height 8 -o nested.png"), 0) << log();
  EXPECT_NE(log().find("lights\ninstances   2 instances (unfolded from nested groups) of 2 groups (1 spheres"),
            std::string::npos)
      << log();
}

// --explain prints one sample's ray tree instead of rendering: no image; a pixel or sample
// outside the image is a usage error.
TEST_F(Cli, ExplainPrintsTheRayTreeAndWritesNothing) {
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --explain 8,6 -o out.png"), 0) << log();
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
  EXPECT_NE(log().find("pixel (8, 6) of 16×12"), std::string::npos) << log();
  EXPECT_NE(log().find("ray 1: camera ray, depth 1, weight 1\n  from (0, 1, 3)"), std::string::npos) << log();
  EXPECT_NE(log().find("hits a sphere (object id 1)"), std::string::npos) << log();
  EXPECT_NE(log().find("\nradiance ("), std::string::npos) << log();
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --spp 4 --explain 15,11,3"), 0) << log();
  EXPECT_NE(log().find("sample 3 of its grid sequence"), std::string::npos) << log();
  EXPECT_EQ(run("scene.yaml --width 16 --height 12 --explain 16,0"), 1) << log();
  EXPECT_NE(log().find("--explain 16,0: the image has 16×12 pixels (x 0 to 15, y 0 to 11 from the top) and 1 samples per "
                       "pixel (0 to 0)"),
            std::string::npos)
      << log();
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --explain 8,6 --device auto"), 0) << log();
  EXPECT_NE(log().find("strahl: note: --explain traces on the CPU (--device auto is not used)\n"), std::string::npos) << log();
  EXPECT_NE(log().find("pixel (8, 6) of 16×12"), std::string::npos) << log();
  EXPECT_EQ(run("scene.yaml --explain 1,1,1"), 1) << log();
  EXPECT_EQ(run("scene.yaml --explain 1"), 1) << log();
  EXPECT_EQ(run("scene.yaml --explain 1,-1"), 1) << log();
  EXPECT_EQ(run("bad.yaml --explain 1,1"), 2) << log();
  EXPECT_NE(log().find("bad.yaml:2:"), std::string::npos) << log();
}

// A POV-Ray scene: --width/--height are its image_width/image_height, --declare its
// Declare=NAME=VALUE; the picture is its YAML twin's.
TEST_F(Cli, ReadsPovRayScenesWithDeclaredNames) {
  const fs::path scenes = fs::path(STRAHL_SOURCE_DIR) / "scenes";
  ASSERT_EQ(run("--declare WHITTED=1 '" + (scenes / "lecture.pov").string() + "' --width 32 --height 18 -q -o out.pfm"), 0)
      << log();
  Scene twin = load_scene(scenes / "lecture-whitted.yaml");
  twin.settings.width = 32;
  twin.settings.height = 18;
  EXPECT_TRUE(read_image(dir_ / "out.pfm") == test::render_image(twin));
  ASSERT_EQ(run("'" + (scenes / "lecture.pov").string() + "' --width 32 --height 18 -q -o plain.pfm"), 0) << log();
  EXPECT_FALSE(read_image(dir_ / "plain.pfm") == test::render_image(twin));
  ASSERT_EQ(run("'" + (scenes / "lecture.pov").string() + "' --declare TINY=1e-320 --width 8 --height 8 -q -o tiny.png"), 0)
      << log();  // (a subnormal number is a number)
  for (const char* bad : {"--declare WHITTED", "--declare =1", "--declare 1X=2", "--declare W=one", "--declare W=inf"}) {
    EXPECT_EQ(run(std::string("scene.yaml -q ") + bad), 1) << bad << ": " << log();
    EXPECT_NE(log().find("--declare"), std::string::npos) << log();
  }
  test::write_text(dir_ / "bad.pov", "sphere { 0, 1 }\nsphere { <0, 0, 0> 2 }\n");
  EXPECT_EQ(run("bad.pov -q"), 2) << log();
  EXPECT_NE(log().find("bad.pov:2:20: expected ','"), std::string::npos) << log();
}

TEST_F(Cli, DefaultOutputNameFollowsTheScene) {
  ASSERT_EQ(run("scene.yaml --width 8 --height 8 -q"), 0) << log();
  EXPECT_TRUE(fs::exists(dir_ / "scene.png"));
}

TEST_F(Cli, HelpExitsZero) { EXPECT_EQ(run("--help"), 0) << log(); }

// One version, from project(VERSION): the macros, the library's strahl::version() and --version.
TEST_F(Cli, VersionIsTheProjectsEverywhere) {
  const std::string from_macros = std::to_string(STRAHL_VERSION_MAJOR) + "." + std::to_string(STRAHL_VERSION_MINOR) +
                                  "." + std::to_string(STRAHL_VERSION_PATCH);
  EXPECT_EQ(from_macros, STRAHL_VERSION_STRING);
  EXPECT_EQ(STRAHL_VERSION, STRAHL_VERSION_MAJOR * 10000 + STRAHL_VERSION_MINOR * 100 + STRAHL_VERSION_PATCH);
  EXPECT_STREQ(version(), STRAHL_VERSION_STRING);
  ASSERT_EQ(run("--version"), 0) << log();
  EXPECT_EQ(log(), "strahl " STRAHL_VERSION_STRING "\n");
}

TEST_F(Cli, UsageErrorsExitOne) {
  EXPECT_EQ(run("scene.yaml --bogus -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --width 0 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --width -5 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --width abc -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --height 0 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --max-depth 0 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --supersample 0 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --threads 0 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml --tile-size 0 -o out.png"), 1) << log();
  EXPECT_EQ(run("scene.yaml other.yaml -o out.png"), 1) << log();
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

TEST_F(Cli, AccelerationStructureOption) {
  ASSERT_EQ(run("scene.yaml --width 12 --height 8 --accel naive -q -o naive.pfm"), 0) << log();
  ASSERT_EQ(run("scene.yaml --width 12 --height 8 --accel bvh -q -o bvh.pfm"), 0) << log();
  EXPECT_TRUE(read_image(dir_ / "naive.pfm") == read_image(dir_ / "bvh.pfm"));
  EXPECT_EQ(run("scene.yaml --width 12 --height 8 --accel octopus -q -o x.pfm"), 1) << log();
  EXPECT_FALSE(fs::exists(dir_ / "x.pfm"));
}

TEST_F(Cli, EqualsFormOfOptions) {
  ASSERT_EQ(run("scene.yaml --width=10 --height=6 -q --output=eq.ppm"), 0) << log();
  EXPECT_EQ(read_image(dir_ / "eq.ppm").width(), 10);
}

TEST_F(Cli, OverriddenResolutionIsCheckedLikeTheFilesOwn) {
  // 65536 × 65536 passes the option parser but exceeds 2^28 pixels: a scene error naming the
  // render section (line 2 of scene.yaml).
  EXPECT_EQ(run("scene.yaml --width 65536 --height 65536 -q -o big.png"), 2) << log();
  EXPECT_NE(log().find("scene.yaml:2:"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(dir_ / "big.png"));
}

TEST_F(Cli, MissingSceneFileExitsTwo) {
  EXPECT_EQ(run("absent.yaml --width 8 --height 8 -o out.png"), 2) << log();
  EXPECT_NE(log().find("absent.yaml"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

TEST_F(Cli, BadSceneExitsTwoAndNamesTheLocation) {
  EXPECT_EQ(run("bad.yaml --width 8 --height 8 -o out.png"), 2) << log();
  EXPECT_NE(log().find("bad.yaml:2:"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

TEST_F(Cli, YamlSyntaxErrorExitsTwo) {
  test::write_text(dir_ / "broken.yaml", "objects: [ {type: sphere\n");
  EXPECT_EQ(run("broken.yaml --width 8 --height 8 -o out.png"), 2) << log();
}

TEST_F(Cli, UnknownOutputExtensionExitsTwo) {
  EXPECT_EQ(run("scene.yaml --width 8 --height 8 -o out.xyz"), 2) << log();
  EXPECT_EQ(run("scene.yaml --width 8 --height 8 -o out"), 2) << log();
  EXPECT_FALSE(fs::exists(dir_ / "out.xyz"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, UnwritableOutputDirectoryExitsTwo) {
  EXPECT_EQ(run("scene.yaml --width 8 --height 8 -o no/such/dir/out.png"), 2) << log();
  test::write_text(dir_ / "plainfile", "x");
  EXPECT_EQ(run("scene.yaml --width 8 --height 8 -o plainfile/out.png"), 2) << log();
}

TEST_F(Cli, OutputPathThatIsADirectoryExitsTwoAndLeavesNoTemporaries) {
  fs::create_directory(dir_ / "taken.png");
  EXPECT_EQ(run("scene.yaml --width 8 --height 8 -q -o taken.png"), 2) << log();
  EXPECT_TRUE(fs::is_directory(dir_ / "taken.png"));
  for (const auto& e : fs::directory_iterator(dir_.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(Cli, FailedRunLeavesAnExistingImageUntouched) {
  ASSERT_EQ(run("scene.yaml --width 8 --height 8 -q -o out.png"), 0) << log();
  const std::string before = test::read_text(dir_ / "out.png");
  ASSERT_FALSE(before.empty());
  EXPECT_EQ(run("bad.yaml --width 8 --height 8 -o out.png"), 2) << log();
  EXPECT_EQ(run("absent.yaml --width 8 --height 8 -o out.png"), 2) << log();
  EXPECT_EQ(run("scene.yaml --width 0 -o out.png"), 1) << log();
  EXPECT_EQ(test::read_text(dir_ / "out.png"), before);
  // Nothing else was left behind (no temporary files).
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_.path())) ++files;
  EXPECT_EQ(files, 4) << "scene.yaml, bad.yaml, log.txt, out.png";
}

TEST_F(Cli, ExistingOutputIsReplacedBySuccessfulRun) {
  test::write_text(dir_ / "out.ppm", "not an image");
  ASSERT_EQ(run("scene.yaml --width 8 --height 4 -q -o out.ppm"), 0) << log();
  const Image img = read_image(dir_ / "out.ppm");
  EXPECT_EQ(img.width(), 8);
  EXPECT_EQ(img.height(), 4);
}

// ---- strahl-diff ----

class Diff : public Cli {
 protected:
  int diff(const std::string& args) {
    const std::string command = "cd '" + dir_.path().string() + "' && '" STRAHL_DIFF "' " + args + " > '" +
                                (dir_ / "log.txt").string() + "' 2>&1";
    const int status = std::system(command.c_str());
    if (status == -1 || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
  }
};

TEST_F(Diff, ComparesImagesAndReportsExitCodes) {
  Image a(4, 2), b(4, 2), c(3, 2);
  b.at(1, 1) = Rgb{0.5f, 0, 0};
  write_image(a, dir_ / "a.pfm");
  write_image(b, dir_ / "b.pfm");
  write_image(c, dir_ / "c.pfm");
  EXPECT_EQ(diff("a.pfm a.pfm"), 0) << log();
  EXPECT_NE(log().find("psnr inf"), std::string::npos) << log();
  EXPECT_EQ(diff("a.pfm b.pfm d.pfm"), 0) << log();
  EXPECT_NE(log().find("pixels differing by more than 1/255: 1 of 8"), std::string::npos) << log();
  const Image d = read_image(dir_ / "d.pfm");
  EXPECT_FLOAT_EQ(d.at(1, 1).r, 5.0f);  // |A − B| × 10
  EXPECT_FLOAT_EQ(d.at(0, 0).r, 0.0f);
  EXPECT_EQ(diff("a.pfm"), 1) << log();
  EXPECT_EQ(diff("a.pfm c.pfm"), 2) << log();
  EXPECT_EQ(diff("a.pfm absent.pfm"), 2) << log();
}

// The difference image never replaces an input, under any of its names; the input is untouched.
TEST_F(Diff, RefusesToWriteOverAnInput) {
  Image a(4, 2), b(4, 2);
  b.at(1, 1) = Rgb{0.5f, 0, 0};
  write_image(a, dir_ / "a.png");
  write_image(b, dir_ / "b.png");
  fs::create_hard_link(dir_ / "a.png", dir_ / "hard.png");
  fs::create_symlink("b.png", dir_ / "link.png");
  const std::string a_bytes = test::read_text(dir_ / "a.png"), b_bytes = test::read_text(dir_ / "b.png");
  fs::last_write_time(dir_ / "a.png", fs::file_time_type(std::chrono::hours(24 * 365 * 20)));
  const auto mtime = fs::last_write_time(dir_ / "a.png");
  for (const char* args : {"a.png b.png a.png", "a.png b.png b.png", "a.png b.png ./a.png", "a.png b.png hard.png",
                           "a.png b.png link.png", "hard.png b.png a.png"}) {
    SCOPED_TRACE(args);
    EXPECT_EQ(diff(args), 2) << log();
    EXPECT_NE(log().find("the difference image would overwrite the input image"), std::string::npos) << log();
    EXPECT_EQ(log().find("rmse"), std::string::npos) << "compared before refusing: " << log();
  }
  EXPECT_EQ(test::read_text(dir_ / "a.png"), a_bytes);
  EXPECT_EQ(test::read_text(dir_ / "b.png"), b_bytes);
  EXPECT_TRUE(fs::last_write_time(dir_ / "a.png") == mtime);
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.png"));
  // Another name is fine, and a path that cannot be written is refused before the comparison.
  EXPECT_EQ(diff("a.png b.png d.png"), 0) << log();
  EXPECT_EQ(diff("a.png b.png no-such-dir/d.png"), 2) << log();
  EXPECT_EQ(log().find("rmse"), std::string::npos) << log();
}

// NaN and infinite values count as different: rmse, psnr and max are nan, never a passing
// number, and the exit code is 3. Clamping would have made +inf equal to 1.
TEST_F(Diff, NonFiniteValuesNeverPass) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  Image grey(4, 2), all_nan(4, 2), white(4, 2), all_inf(4, 2), one_nan(4, 2);
  for (std::size_t i = 0; i < 8; ++i) {
    grey.at(int(i % 4), int(i / 4)) = Rgb{0.5f, 0.5f, 0.5f};
    all_nan.at(int(i % 4), int(i / 4)) = Rgb{nan, nan, nan};
    white.at(int(i % 4), int(i / 4)) = Rgb{1, 1, 1};
    all_inf.at(int(i % 4), int(i / 4)) = Rgb{inf, inf, inf};
  }
  one_nan.at(2, 1).g = nan;
  write_image(grey, dir_ / "grey.pfm");
  write_image(all_nan, dir_ / "nan.pfm");
  write_image(white, dir_ / "white.pfm");
  write_image(all_inf, dir_ / "inf.pfm");
  write_image(one_nan, dir_ / "one-nan.pfm");
  const auto expect_nan = [&](const std::string& args, const std::string& pixels, const std::string& warning) {
    SCOPED_TRACE(args);
    EXPECT_EQ(diff(args + " d.pfm"), 3) << log();
    EXPECT_NE(log().find("rmse nan  psnr nan dB  max nan  pixels differing by more than 1/255: " + pixels), std::string::npos)
        << log();
    EXPECT_NE(log().find(warning), std::string::npos) << log();
  };
  expect_nan("nan.pfm grey.pfm", "8 of 8", "nan.pfm: 24 values are NaN or infinite");
  expect_nan("grey.pfm nan.pfm", "8 of 8", "nan.pfm: 24 values are NaN or infinite");
  expect_nan("inf.pfm white.pfm", "8 of 8", "inf.pfm: 24 values are NaN or infinite");
  expect_nan("inf.pfm inf.pfm", "8 of 8", "inf.pfm: 24 values are NaN or infinite");
  expect_nan("one-nan.pfm one-nan.pfm", "1 of 8", "one-nan.pfm: 1 values are NaN or infinite");
  // The difference image shows a non-finite channel at the full amplified difference, 10.
  const Image d = read_image(dir_ / "d.pfm");
  EXPECT_EQ(d.at(2, 1), (Rgb{0, 10, 0}));
  EXPECT_EQ(diff("white.pfm white.pfm"), 0) << log();
  EXPECT_NE(log().find("psnr inf dB"), std::string::npos) << log();
}

// Sampling flags (docs/cli.md, "Sampling and output").
TEST_F(Cli, SamplingFiltersAovsAndTimeLimit) {
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --sampler sobol --spp 8 --filter mitchell --filter-radius 2 "
                "--seed 5 --aov depth,normal,albedo,id -o out.png"),
            0)
      << log();
  EXPECT_NE(log().find("sobol 8 spp, mitchell filter r=2"), std::string::npos) << log();
  EXPECT_NE(log().find("samples     1536 (8.00 per pixel"), std::string::npos) << log();
  for (const char* aov : {"depth", "normal", "albedo", "id"}) {
    const fs::path p = dir_ / (std::string("out.") + aov + ".exr");
    ASSERT_TRUE(fs::exists(p)) << p;
    EXPECT_EQ(read_image(p).width(), 16);
  }
  // Stratified rounds 10 to 3×3; adaptive reports its passes.
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --sampler stratified --spp 10 -o s.png"), 0) << log();
  EXPECT_NE(log().find("stratified 9 spp"), std::string::npos) << log();
  ASSERT_EQ(run("scene.yaml --width 16 --height 12 --sampler adaptive --spp 64 --adaptive-min 4 "
                "--adaptive-threshold 0.05 -o a.png"),
            0)
      << log();
  // A time limit without a sample count renders until the limit (at most 65536 spp: 64×48 of them
  // take seconds, where 16×12 could finish in 0.27 s on a fast machine); a checkpoint rewrites the output.
  ASSERT_EQ(run("scene.yaml --width 64 --height 48 --time-limit 0.3 --checkpoint 0.05 -o t.png"), 0) << log();
  EXPECT_NE(log().find("stopped by the time limit"), std::string::npos) << log();
  EXPECT_TRUE(fs::exists(dir_ / "t.png"));
  // Bad values are usage errors.
  EXPECT_EQ(run("scene.yaml --sampler halton -o x.png"), 1);
  EXPECT_EQ(run("scene.yaml --filter-radius 9 -o x.png"), 1);
  EXPECT_EQ(run("scene.yaml --spp 0 -o x.png"), 1);
  EXPECT_EQ(run("scene.yaml --aov colour -o x.png"), 1);
  EXPECT_EQ(run("scene.yaml --time-limit -1 -o x.png"), 1);
}

// The same settings as scene keys; a bad value names its line.
TEST_F(Cli, SamplingSceneKeys) {
  std::string scene = kGoodScene;
  scene.replace(scene.find("render: {width: 320, height: 240}"), std::string("render: {width: 320, height: 240}").size(),
                "render: {width: 8, height: 6, sampler: random, spp: 3, seed: 2, filter: gaussian, filter_radius: 1.5, "
                "adaptive_min: 2, adaptive_threshold: 0.1}");
  test::write_text(dir_ / "keys.yaml", scene);
  ASSERT_EQ(run("keys.yaml -o k.png"), 0) << log();
  EXPECT_NE(log().find("random 3 spp, gaussian filter r=1.5"), std::string::npos) << log();
  scene.replace(scene.find("sampler: random"), std::string("sampler: random").size(), "sampler: halton");
  test::write_text(dir_ / "bad-keys.yaml", scene);
  EXPECT_EQ(run("bad-keys.yaml -o k.png"), 2);
  EXPECT_NE(log().find("bad-keys.yaml:2:"), std::string::npos) << log();
  EXPECT_NE(log().find("unknown sampler 'halton'"), std::string::npos) << log();
}

}  // namespace
}  // namespace strahl::cli_test
