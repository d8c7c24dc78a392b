#include "summary.h"

#include <fmt/format.h>
#include <sys/resource.h>

namespace strahl::cli {

std::string summary(const std::string& output, int width, int height, int threads,
                    const Timings& t, const RenderStats& s, const RenderScene& scene) {
  const RayCounters& r = s.rays;
  const double mrays = t.render > 0 ? double(r.total()) / t.render * 1e-6 : 0;
  std::string out;
  const SamplingSettings& sm = scene.sampling;
  out += fmt::format("image       {} ({}x{}, {} {} spp, {} filter r={}, {} threads)\n", output, width, height,
                     sampler_name(sm.sampler), sm.spp, filter_name(sm.filter.kind), sm.filter.radius, threads);
  const AccelBuildStats& a = scene.accel.stats;
  // A group past the scene's (group_nesting: the scene's groups and their moving shapes') holds a
  // turning shape of the scene's own, a mesh or triangle moved as an instance of itself
  // (scene/instances.h): its shapes count with the scene's, as moving ones, and not as instances.
  struct Tally {
    std::size_t spheres = 0, triangles = 0, solids = 0, bytes = 0;
  };
  Tally grouped, turning;
  for (std::size_t g = 0; g < scene.groups.size(); ++g) {
    Tally& sum = g < scene.group_nesting.size() ? grouped : turning;
    sum.spheres += scene.groups[g].spheres.size();
    sum.triangles += scene.groups[g].triangles.size();
    sum.solids += scene.groups[g].solids.size();
    sum.bytes += scene.groups[g].accel.stats.bytes;
  }
  std::size_t moving_instances = 0;  // the user's (records of the scene's groups)
  for (const kernel::MovingInstance& m : scene.moving_instances)
    if (m.instance.group < scene.group_nesting.size()) ++moving_instances;
  // Moving shapes count with the others (and are named, as the accelerator line leaves them out),
  // moving instances with the instances; the time segments their BVH was cut into
  // (accel/motion_bvh.h), where more than one, are named beside the first of the two.
  const std::size_t moving = scene.moving_spheres.size() + scene.moving_triangles.size() + scene.moving_solids.size() +
                             turning.spheres + turning.triangles + turning.solids;
  const std::uint32_t segments = scene.moving_bvh.segments;
  const std::string cut = segments > 1 ? fmt::format(", their BVH cut into {} time segments", segments) : std::string();
  out += fmt::format("scene       {} spheres, {} planes, {} triangles, {} solids, {} lights{}\n",
                     scene.spheres.size() + scene.moving_spheres.size() + turning.spheres, scene.planes.size(),
                     scene.triangles.size() + scene.moving_triangles.size() + turning.triangles,
                     scene.solids.size() + scene.moving_solids.size() + turning.solids, scene.lights.size(),
                     moving == 0 ? std::string() : fmt::format(" ({} of the shapes moving{})", moving, cut));
  if (!scene.instances.empty() || moving_instances > 0) {
    std::size_t groups = 0;  // the scene's, which instances name
    std::string notes;       // nested groups unfolded (scene/instances.h); how many move
    for (const RenderScene::GroupNesting& n : scene.group_nesting) {
      if (n.placeable) ++groups;
      for (const RenderScene::GroupPlacement& p : n.places)  // (not a group's moving shape, placed as its own group)
        if (scene.group_nesting[p.group].placeable) notes = "unfolded from nested groups";
    }
    if (moving_instances > 0)
      notes += fmt::format("{}{} moving{}", notes.empty() ? "" : "; ", moving_instances, moving == 0 ? cut : std::string());
    out += fmt::format("instances   {} instances{} of {} groups ({} spheres, {} triangles, {} solids, once; their {}: {:.1f} MiB)\n",
                       scene.instances.size() + moving_instances, notes.empty() ? std::string() : " (" + notes + ")",
                       groups, grouped.spheres, grouped.triangles, grouped.solids,
                       accel_name(scene.groups.front().accel.kind), double(grouped.bytes) / (1 << 20));
  }
  // Embree reports no node count or depth.
  const std::string nodes =
      a.nodes > 0 ? fmt::format("{} nodes, {} leaves, depth {}, ", a.nodes, a.leaves, a.max_depth) : std::string();
  out += fmt::format("accel       {}: {}{:.1f} MiB ({:.1f} bytes per primitive), built in {:.3f} s\n",
                     accel_name(scene.accel.kind), nodes, double(a.bytes) / (1 << 20),
                     a.primitives > 0 ? double(a.bytes) / double(a.primitives) : 0.0, a.seconds);
  out += fmt::format("time        load {:.3f} s, build {:.3f} s, render {:.3f} s, write {:.3f} s\n", t.load, t.build,
                     t.render, t.write);
  out += fmt::format("rays        {} total: {} camera, {} shadow, {} reflection, {} refraction\n", r.total(), r.camera,
                     r.shadow, r.reflection, r.refraction);
  out += fmt::format("throughput  {:.2f} Mrays/s\n", mrays);
  const double pixels = double(width) * double(height);
  out += fmt::format("samples     {} ({:.2f} per pixel, {} passes{}), {:.2f} Msamples/s\n", s.samples,
                     pixels > 0 ? double(s.samples) / pixels : 0.0, s.passes,
                     s.time_limited ? ", stopped by the time limit" : "",
                     t.render > 0 ? double(s.samples) / t.render * 1e-6 : 0.0);
  // Peak resident set size of the whole process so far (Linux reports ru_maxrss in KiB).
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0)
    out += fmt::format("memory      peak {:.1f} MiB resident\n", double(usage.ru_maxrss) / 1024);
  if (r.invalid_samples > 0)
    out += fmt::format("warning     {} samples were NaN or infinite and were set to black\n", r.invalid_samples);
  if (r.cut > 0)
    out += fmt::format("warning     {} reflected or refracted rays were cut: the ray budget of {} per camera sample "
                       "(render.ray_budget) was spent\n",
                       r.cut, scene.settings.ray_budget);
  return out;
}

}  // namespace strahl::cli
