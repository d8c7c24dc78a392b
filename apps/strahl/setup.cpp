#include "setup.h"

#include "outputs.h"

#include <filesystem>

#include "strahl/image/image_io.h"
#include "strahl/render/aov.h"
#include "strahl/scene/scene_file.h"

namespace strahl::cli {

namespace {

// Command-line sampling settings over the scene's. A time limit without a sample count renders
// until the limit (up to 65536 samples per pixel).
void apply_sampling_options(const Options& o, SamplingSettings& s) {
  if (o.sampler) s.sampler = *sampler_from_name(*o.sampler);
  if (o.spp) s.spp = *o.spp;
  if (o.seed) s.seed = *o.seed;
  if (o.filter) s.filter.kind = *filter_from_name(*o.filter);
  if (o.filter_radius) s.filter.radius = *o.filter_radius;
  if (o.adaptive_min) s.adaptive_min = *o.adaptive_min;
  if (o.adaptive_threshold) s.adaptive_threshold = *o.adaptive_threshold;
  if (o.time_limit > 0 && !o.spp && s.spp == 0) s.spp = 65536;
}

}  // namespace

std::string output_path(const Options& o) {
  namespace fs = std::filesystem;
  return !o.output.empty() ? o.output : (o.scene.empty() ? "lecture" : fs::path(o.scene).stem().string()) + ".png";
}

Scene configured_scene(const Options& o) {
  PovOptions pov;
  if (o.width) pov.width = *o.width;
  if (o.height) pov.height = *o.height;
  pov.declares = o.declares;
  Scene scene = o.scene.empty() ? lecture_scene() : load_scene(o.scene, pov);
  if (o.width) scene.settings.width = *o.width;
  if (o.height) scene.settings.height = *o.height;
  if (o.max_depth) scene.settings.max_depth = *o.max_depth;
  if (o.supersample) scene.settings.supersample = *o.supersample;
  if (o.integrator) scene.settings.integrator = *integrator_from_name(*o.integrator);
  if (o.accel) scene.settings.accel = *accel_from_name(*o.accel);
  apply_sampling_options(o, scene.settings.sampling);
  return scene;
}

void write_aovs(const RenderScene& scene, const Options& o, const std::string& output) {
  const AovImages aovs = render_aovs(scene, o.threads);
  for (const std::string& name : o.aov) {
    const Image& img = name == "depth" ? aovs.depth : name == "normal" ? aovs.normal : name == "albedo" ? aovs.albedo : aovs.id;
    write_image(img, aov_path(output, name));
  }
}

}  // namespace strahl::cli
