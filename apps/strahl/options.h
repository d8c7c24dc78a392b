#pragma once
// Command-line options of the `strahl` renderer.

#include <functional>
#include <optional>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace strahl::cli {

struct Options {
  std::string scene;   // empty: the built-in lecture scene
  std::string output;  // empty: <scene name>.png in the current directory
  std::vector<std::pair<std::string, double>> declares;  // --declare NAME=VALUE (.pov scenes)
  std::optional<int> width, height, max_depth, supersample;
  std::optional<std::string> accel, integrator;
  // Sampling and output (issue 4).
  std::optional<int> spp, adaptive_min;
  std::optional<std::string> sampler, filter;
  std::optional<double> filter_radius, adaptive_threshold;
  std::optional<std::uint64_t> seed;
  std::vector<std::string> aov;  // depth, normal, albedo, id
  double time_limit = 0;         // seconds, 0: none
  double checkpoint = 0;         // seconds, 0: none
  int threads = 0;
  int tile_size = 32;
  bool linear = false;
  bool quiet = false;
};

// Parses argv. Returns the options, or an exit code (0 after --help, 1 for a usage error)
// after printing the message.
struct ParseResult {
  std::optional<Options> options;
  int exit_code = 0;
};
// `program` names the program in --help and --version; `more` adds its own options (strahl-mpi).
ParseResult parse_options(int argc, char** argv, const char* program = "strahl",
                          const std::function<void(CLI::App&)>& more = {});

}  // namespace strahl::cli
