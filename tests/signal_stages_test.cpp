// Every signal at every stage of a run (issue 12, "Signals and streams"; docs/cli.md,
// "Interrupting a run"): SIGINT, SIGTERM and SIGHUP while loading (the YAML scene, its OBJ, PLY
// and glTF meshes) or building end the run with 130 and
// nothing written; while rendering, the image so far is written; while writing, the image is
// finished; SIGPIPE is ignored throughout. Never a half-written file or a stray temporary one.
// The CLI's test hook (STRAHL_TEST_HOLD=STAGE:SECONDS) holds the stage open until the signal
// arrives, so each signal lands inside its stage deterministically.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <set>

#include "child_process.h"
#include "strahl/image/image_io.h"
#include "test_helpers.h"

namespace strahl::signal_stages_test {
namespace {

const char* kScene =
    "camera: {position: [0, 1, 3], look_at: [0, 0.3, 0]}\n"
    "render: {width: 64, height: 48}\n"
    "lights: [{type: point, position: [1, 3, 2]}]\n"
    "objects:\n"
    "  - {type: plane, normal: [0, 1, 0], distance: 0}\n"
    "  - {type: sphere, center: [0, 0.5, 0], radius: 0.5}\n"
    "  - {type: mesh, file: quad.obj, translate: [0, 0, -1]}\n"
    "  - {type: mesh, file: quad.ply, translate: [0, 0, -2]}\n"
    "  - {type: mesh, file: quad.gltf, translate: [0, 0, -3]}\n";

const char* kQuad = "v -1 0 0\nv 1 0 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
// The quad as a glTF triangle fan, its buffer a data: URI.
const char* kQuadGltf =
    "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 0}],\n"
    " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"mode\": 6}]}],\n"
    " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"type\": \"VEC3\", \"count\": 4}],\n"
    " \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 48}],\n"
    " \"buffers\": [{\"byteLength\": 48, \"uri\": \"data:application/octet-stream;base64,"
    "AACAvwAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAA\"}]}\n";
const char* kQuadPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "-1 0 0\n1 0 0\n1 1 0\n-1 1 0\n4 0 1 2 3\n";

void write_inputs(const fs::path& dir) {
  test::write_text(dir / "scene.yaml", kScene);
  test::write_text(dir / "quad.obj", kQuad);
  test::write_text(dir / "quad.ply", kQuadPly);
  test::write_text(dir / "quad.gltf", kQuadGltf);
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

long lit(const Image& img) {
  long n = 0;
  for (const Rgb& p : img.pixels()) n += (p.r > 0 || p.g > 0 || p.b > 0);
  return n;
}

struct SignalRun {
  test::ChildResult result;
  bool held = false;
  double seconds = 0;
};

// Runs the CLI holding at `stage` and sends `sig` once it says so.
SignalRun run_with_signal(const fs::path& dir, const std::string& stage, int sig, double hold_seconds) {
  const std::string hold = stage + ":" + std::to_string(hold_seconds);
  ::setenv("STRAHL_TEST_HOLD", hold.c_str(), 1);
  const auto start = std::chrono::steady_clock::now();
  test::ChildProcess child({STRAHL_CLI, "scene.yaml", "--threads", "1", "--tile-size", "16", "-o", "out.png"}, dir);
  ::unsetenv("STRAHL_TEST_HOLD");
  SignalRun run;
  run.held = child.wait_for_stderr("strahl: holding at " + stage + "\n", 60);
  if (run.held) child.send(sig);
  run.result = child.wait(60);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

TEST(SignalStages, EachSignalAtEachStageDoesWhatTheDocsSay) {
  test::TempDir ref_dir;
  write_inputs(ref_dir.path());
  const test::ChildResult ref =
      test::run_child({STRAHL_CLI, "scene.yaml", "--threads", "1", "-q", "-o", "out.png"}, ref_dir.path(), 60);
  ASSERT_EQ(ref.exit_code, 0) << ref.err;
  const Image reference = read_image(ref_dir / "out.png");

  const std::pair<int, const char*> signals[] = {{SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGHUP, "SIGHUP"},
                                                 {SIGPIPE, "SIGPIPE"}};
  // Loading the scene file, its OBJ, PLY and glTF meshes; compiling; rendering; writing.
  for (const char* stage : {"yaml", "obj", "ply", "gltf", "build", "render", "write"}) {
    for (const auto& [sig, name] : signals) {
      SCOPED_TRACE(std::string(name) + " while at stage " + stage);
      test::TempDir dir;
      write_inputs(dir.path());
      const bool ignored = sig == SIGPIPE;
      // An ignored signal leaves the hold to time out; a handled one ends it at once.
      const SignalRun run = run_with_signal(dir.path(), stage, sig, ignored ? 0.3 : 30);
      const test::ChildResult& r = run.result;
      ASSERT_TRUE(run.held) << "the CLI never reached the stage: " << r.err;
      ASSERT_FALSE(r.timed_out);
      EXPECT_EQ(r.term_signal, 0) << "ended by the signal instead of handling it";
      EXPECT_LT(run.seconds, 20) << "the signal did not end the hold";
      const std::string stage_s = stage;
      if (ignored) {
        EXPECT_EQ(r.exit_code, 0) << r.err;
        const Image img = read_image(dir / "out.png");
        EXPECT_EQ(test::max_abs_diff(img, reference), 0.0f);
      } else if (stage_s != "render" && stage_s != "write") {
        EXPECT_EQ(r.exit_code, 130) << r.err;
        EXPECT_NE(r.err.find(std::string("strahl: interrupted (") + name + ") before rendering; nothing written"),
                  std::string::npos)
            << r.err;
      } else {
        EXPECT_EQ(r.exit_code, 130) << r.err;
        EXPECT_NE(r.err.find(std::string("strahl: interrupted (") + name + "); wrote the image rendered so far"),
                  std::string::npos)
            << r.err;
        const Image img = read_image(dir / "out.png");
        ASSERT_EQ(img.width(), 64);
        ASSERT_EQ(img.height(), 48);
        if (stage_s == "write") {
          EXPECT_EQ(test::max_abs_diff(img, reference), 0.0f) << "the rendered image, written whole";
        } else {
          // One 16×16 tile was done when the hold began, and the render stopped there.
          EXPECT_GT(lit(reference), 1000);
          EXPECT_LE(lit(img), 256) << "the render went on after the signal";
        }
      }
      // Nothing but the inputs and (where one was written) the whole image: no temporary files.
      std::set<std::string> expected = {"scene.yaml", "quad.obj", "quad.ply", "quad.gltf"};
      if (ignored || stage_s == "render" || stage_s == "write") expected.insert("out.png");
      EXPECT_EQ(listing(dir.path()), expected);
    }
  }
}

}  // namespace
}  // namespace strahl::signal_stages_test
