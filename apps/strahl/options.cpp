#include "options.h"

#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "strahl/accel/accel.h"
#include "strahl/render/integrator_kind.h"
#include "strahl/sampling/pixel_sampler.h"
#include "strahl/util/number_syntax.h"
#include "strahl/version.h"

namespace strahl::cli {

namespace {
// Number flags read as scene files read numbers (util/number_syntax.h, YAML 1.2's core schema):
// 010 is 10, 0x10 is 16, 1e3 is 1000 for a whole number; a value out of range is refused with
// the text the user wrote, never wrapped (--seed -1) or rounded in the message. The transform
// hands CLI11 the plain decimal it then converts.
CLI::Validator whole(std::int64_t lo, std::uint64_t hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        const number::Integer r = number::parse_integer(s, lo, hi);
        switch (r.status) {
          case number::Integer::Status::Ok:
            s = r.value < 0 ? std::to_string(r.value) : std::to_string(r.unsigned_value);
            return {};
          case number::Integer::Status::OutOfRange: return number::range_message("value", lo, hi, s);
          default: return "value must be a whole number (got '" + s + "')";
        }
      },
      "INT in " + range);
}
// A finite real in [lo, hi] (lo excluded when `open_lo`: "positive").
CLI::Validator real(double lo, double hi, bool open_lo) {
  const std::string range = (open_lo ? "(" : "[") + number::shortest(lo) + ", " + number::shortest(hi) + "]";
  return CLI::Validator(
      [lo, hi, open_lo, range](std::string& s) -> std::string {
        const number::Real r = number::parse_real(s);
        if (r.status != number::Real::Status::Ok) return "value must be a number (got '" + s + "')";
        if (!std::isfinite(r.value) || r.value < lo || (open_lo && r.value == lo) || r.value > hi)
          return "value must lie in " + range + " (got " + s + ")";
        s = number::shortest(r.value);
        return {};
      },
      "NUMBER in " + range);
}
constexpr double kForever = 1e9;  // seconds: the largest time limit or checkpoint interval (31 years)

std::vector<std::string> accel_list() {
  std::vector<std::string> names;
  for (AccelKind k : accel_kinds()) names.emplace_back(accel_name(k));  // with "embree" where built
  return names;
}
// Pixel sampling, filters, AOVs and progressive rendering (docs/cli.md, "Sampling").
void add_sampling_options(CLI::App& app, Options& o) {
  app.add_option("--spp", o.spp,
                 "Samples per pixel (adaptive: the maximum); grid and stratified round it to a square n×n")
      ->transform(whole(1, kMaxSpp));
  app.add_option("--sampler", o.sampler, std::string("Pixel sampler: ") + kSamplerNames + " (default grid)")
      ->check(CLI::IsMember({"grid", "stratified", "random", "sobol", "adaptive"}));
  app.add_option("--seed", o.seed, "Seed of the random numbers, 0 to 18446744073709551615 (default 0)")
      ->transform(whole(0, std::numeric_limits<std::uint64_t>::max()));
  app.add_option("--filter", o.filter, std::string("Reconstruction filter: ") + kFilterNames + " (default box)")
      ->check(CLI::IsMember({"box", "tent", "gaussian", "mitchell"}));
  app.add_option("--filter-radius", o.filter_radius, "Filter radius in pixels, 0.5 to 4 (default 0.5)")
      ->transform(real(0.5, 4.0, false));
  app.add_option("--adaptive-min", o.adaptive_min, "Adaptive: samples every pixel gets first (default 16)")
      ->transform(whole(1, kMaxSpp));
  app.add_option("--adaptive-threshold", o.adaptive_threshold,
                 "Adaptive: relative standard error at which a pixel stops (default 0.02)")
      ->transform(real(0, 1e6, true));
  app.add_option("--aov", o.aov, "Also write these per-pixel outputs as <output>.<name>.exr: depth, normal, albedo, id")
      ->delimiter(',')
      ->check(CLI::IsMember({"depth", "normal", "albedo", "id"}));
  app.add_option("--time-limit", o.time_limit,
                 "Render progressively and stop after this many seconds with the image so far")
      ->transform(real(0, kForever, true));
  app.add_option("--checkpoint", o.checkpoint, "Rewrite the output image every this many seconds while rendering")
      ->transform(real(0, kForever, true));
}
}  // namespace

ParseResult parse_options(int argc, char** argv, const char* program, const std::function<void(CLI::App&)>& more) {
  Options o;
  CLI::App app{"strahl — a Whitted-style ray tracer. Renders a scene file (.yaml/.json/.pov), or the lecture's scene "
               "when none is given.",
               program};
  app.add_option("scene", o.scene,
                 "Scene file (.yaml, .yml, .json, or a POV-Ray scene .pov: docs/pov-import.md); omitted: the built-in "
                 "lecture scene");
  app.add_option_function<std::vector<std::string>>(
         "--declare",
         [&o](const std::vector<std::string>& all) {
           for (const std::string& d : all)
             o.declares.emplace_back(d.substr(0, d.find('=')), std::strtod(d.c_str() + d.find('=') + 1, nullptr));
         },
         "NAME=VALUE: declare a float in a .pov scene before it is read (POV-Ray's Declare=NAME=VALUE); repeatable")
      ->allow_extra_args(false)
      ->check([](const std::string& d) -> std::string {
        const std::size_t eq = d.find('=');
        if (eq == std::string::npos || eq == 0) return "expected NAME=VALUE, got '" + d + "'";
        for (std::size_t i = 0; i < eq; ++i)
          if (!(std::isalnum(static_cast<unsigned char>(d[i])) || d[i] == '_') || (i == 0 && std::isdigit(static_cast<unsigned char>(d[0]))))
            return "'" + d.substr(0, eq) + "' is not a POV-Ray name (letters, digits, _)";
        const std::string v = d.substr(eq + 1);
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(x)) return "'" + v + "' is not a number";
        return {};
      });
  app.add_option("-o,--output", o.output,
                 "Output image; the format follows the extension: .png .jpg/.jpeg .ppm (8-bit sRGB), .pfm .exr (linear "
                 "float). Default: <scene>.png");
  app.add_option("--width", o.width, "Image width in pixels (overrides the scene)")->transform(whole(1, 65536));
  app.add_option("--height", o.height, "Image height in pixels (overrides the scene)")->transform(whole(1, 65536));
  app.add_option("--max-depth", o.max_depth, "Maximum recursion depth; camera rays are depth 1 (default 8)")
      ->transform(whole(1, 64));
  app.add_option("--integrator", o.integrator,
                 std::string("Integrator: ") + kIntegratorNames +
                     " (whitted: the lecture's recursive ray tracing; path: path tracing, global illumination; "
                     "default: the scene's, else whitted)")
      ->check(CLI::IsMember({"whitted", "path"}));
  app.add_option("--supersample", o.supersample, "N×N regular samples per pixel, box filter (default 1)")
      ->transform(whole(1, 64));
  add_sampling_options(app, o);
  app.add_option("--accel", o.accel, "Acceleration structure: " + accel_names() + " (default bvh)")
      ->check(CLI::IsMember(accel_list()));
  app.add_option("--threads", o.threads, "Worker threads (default: all cores)")->transform(whole(1, 4096));
  app.add_option("--tile-size", o.tile_size, "Tile side in pixels (default 32)")->transform(whole(1, 4096));
  app.add_flag("--linear", o.linear, "Store linear values in 8-bit images instead of sRGB (as POV-Ray's File_Gamma=1.0)");
  app.add_flag("-q,--quiet", o.quiet, "No progress and no summary");
  if (more) more(app);
  app.set_version_flag("--version", std::string(program) + " " + version(), "Print the version and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return {std::nullopt, code == 0 ? 0 : 1};
  }
  return {o, 0};
}

}  // namespace strahl::cli
