// strahl-bench: throughput of the acceleration structures (and Embree, where built) on the
// lecture scene, a procedural mesh and any meshes given; the strahl-BVH / Embree ratios; and the
// BVH's scaling from 1 thousand to 4 million triangles. See docs/benchmark.md.
// Exit codes: 0 ok, 1 usage, 2 a mesh could not be read.

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "console.h"
#include "measure.h"
#include "report.h"
#include "scenes.h"
#include "strahl/util/error.h"

namespace {

using namespace strahl;
using namespace strahl::bench;

struct Options {
  int threads = 0;  // 0: all cores
  int width = 1920, height = 1080;
  bool quick = false;
  bool no_scaling = false;
  int runs = 0;                          // 0: up to 5, stopping once 0.3 s are spent
  std::size_t procedural_triangles = 0;  // 0: 270,000 (--quick: 12,000)
  std::vector<std::string> accels;       // empty: all built in
  std::vector<std::string> meshes;
};

std::optional<Options> parse(int argc, char** argv, int& exit_code) {
  Options o;
  std::vector<std::string> names;
  for (AccelKind k : accel_kinds()) names.emplace_back(accel_name(k));
  CLI::App app{"strahl-bench — ray throughput of strahl's acceleration structures (and Embree where built): build "
               "time, memory, Mrays/s for primary, incoherent and shadow rays at 1 and all threads, and a BVH scaling "
               "table. Meshes (.obj, .ply, .gltf, .glb) given as arguments are normalised to unit size resting on y = 0.",
               "strahl-bench"};
  app.add_option("meshes", o.meshes, "Mesh files (.obj, .ply, .gltf, .glb) to measure besides the built-in scenes");
  app.add_option("--threads", o.threads, "Threads for the \"all threads\" figures (default: all cores)")
      ->check(CLI::Range(1, 4096));
  app.add_option("--width", o.width, "Primary rays per row (default 1920; --quick: 160)")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Rows of primary rays (default 1080; --quick: 90)")->check(CLI::Range(1, 16384));
  app.add_option("--triangles", o.procedural_triangles,
                 "Triangles of the procedural mesh in the per-scene tables (default 270000; --quick: 12000)")
      ->check(CLI::Range(std::size_t(12), std::size_t(50'000'000)));
  app.add_option("--accel", o.accels, "Only these structures (default: all of " + accel_names() + ")")
      ->check(CLI::IsMember(names))
      ->delimiter(',')
      ->allow_extra_args(false);  // one comma-separated list: mesh paths may follow it
  app.add_flag("--quick", o.quick, "Small sizes, one run per figure: finishes in seconds (CI smoke test)");
  app.add_flag("--no-scaling", o.no_scaling, "Skip the scaling table");
  app.add_option("--runs", o.runs,
                 "Trace every figure exactly N times and keep the fastest (default: up to 5 runs, stopping once "
                 "0.3 s are spent; on a noisy machine more runs give steadier ratios)")
      ->check(CLI::Range(1, 1000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    exit_code = app.exit(e) == 0 ? 0 : 1;
    return std::nullopt;
  }
  if (o.quick) {
    if (app.count("--width") == 0) o.width = 160;
    if (app.count("--height") == 0) o.height = 90;
  }
  if (o.procedural_triangles == 0) o.procedural_triangles = o.quick ? 12'000 : 270'000;
  return o;
}

int run(const Options& o) {
  const int all = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  // More threads than cores need the global limit raised.
  std::unique_ptr<tbb::global_control> limit;
  if (all > tbb::info::default_concurrency())
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(all));

  Plan plan;
  plan.threads = all == 1 ? std::vector<int>{1} : std::vector<int>{1, all};
  if (o.accels.empty()) {
    plan.kinds = accel_kinds();
  } else {
    for (const std::string& name : o.accels) plan.kinds.push_back(*accel_from_name(name));
  }
  plan.repeat = o.runs > 0 ? Repeat{kInfinity, o.runs} : o.quick ? Repeat{0, 1} : Repeat{0.3, 5};
  plan.naive_budget = o.quick ? 2e6 : 5e7;

  // Meshes first, so that a bad file is reported at once.
  std::vector<BenchScene> meshes;
  for (const std::string& mesh : o.meshes) meshes.push_back(mesh_bench_scene(mesh, o.width, o.height));

  print_header(plan, o.width, o.height);
  warm_up(plan);

  std::vector<SceneResult> results;
  results.push_back(measure_scene(lecture_bench_scene(o.width, o.height), plan));
  results.push_back(measure_scene(procedural_bench_scene(o.procedural_triangles, o.width, o.height), plan));
  for (const BenchScene& mesh : meshes) results.push_back(measure_scene(mesh, plan));
  print_ratios(results, plan);

  if (!o.no_scaling) {
    const std::vector<std::size_t> sizes =
        o.quick ? std::vector<std::size_t>{1'000, 4'000, 16'000}
                : std::vector<std::size_t>{1'000, 4'000, 16'000, 64'000, 256'000, 1'000'000, 4'000'000};
    run_scaling(sizes, o.width, o.height, plan);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  strahl::console::protect_streams();
  int exit_code = 0;
  const std::optional<Options> options = parse(argc, argv, exit_code);
  if (!options) return exit_code;
  try {
    const int code = run(*options);
    // The tables on stdout are the benchmark's product: losing them (a full disk, a broken pipe) fails.
    if (code == 0 && strahl::console::lost(strahl::console::Stream::out)) {
      strahl::console::err("strahl-bench: error: the report could not be written to stdout\n");
      return 2;
    }
    return code;
  } catch (const strahl::Error& e) {
    strahl::console::err("strahl-bench: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    strahl::console::err("strahl-bench: error: {}\n", e.what());
    return 2;
  }
}
