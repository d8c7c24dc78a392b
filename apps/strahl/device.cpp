#include "device.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>

namespace strahl::cli {

void add_device_option(CLI::App& app, std::string& device) {
  app.add_option("--device", device,
                 "Where to render: cpu, cuda (an NVIDIA GPU; exit 2 when none is usable) or auto (the GPU when "
                 "one is usable, else the CPU; default cpu)")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}));
}

std::string device_accel_conflict(const std::string& device, const Options& o) {
  if (device == "cuda" && o.accel && *o.accel == "embree")
    return "--device cuda renders with --accel bvh, kdtree, octree or naive, not embree";
  return {};
}

OpenedDevice open_device(const std::string& device, const RenderScene& scene) {
  OpenedDevice d;
  if (device == "cpu") return d;
  std::string why;
  d.gpu = CudaBackend::create(scene, why);
  if (d.gpu) return d;
  if (device == "cuda")
    d.error = "--device cuda: " + why;
  else
    d.note = "--device auto: " + why + "; rendering on the CPU";
  return d;
}

std::string device_line(const CudaBackend* gpu, const RenderStats& stats, int threads) {
  if (!gpu) return fmt::format("device      cpu ({} threads)\n", threads);
  const CudaStats g = gpu->stats();
  return fmt::format(
      "device      cuda: {}, {:.1f} MiB used ({:.1f} MiB in use on the device), upload {:.3f} s, kernel {:.3f} s "
      "in {} launches, {:.2f} Mrays/s (kernel time)\n",
      g.device, double(g.memory_used) / (1 << 20), double(g.memory_in_use) / (1 << 20), g.upload_seconds,
      g.kernel_seconds, g.launches, g.kernel_seconds > 0 ? double(stats.rays.total()) / g.kernel_seconds * 1e-6 : 0.0);
}

}  // namespace strahl::cli
