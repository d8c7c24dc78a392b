#pragma once
// --device (docs/cli.md, docs/gpu.md): which back end renders — the CPU's threads or the GPU —
// as strahl and strahl-view offer it: the option, the check against --accel, opening the GPU
// with its fallback, and the summary's line.

#include <memory>
#include <string>

#include "options.h"
#include "strahl/cuda/cuda_backend.h"
#include "strahl/render/render_job.h"

namespace strahl::cli {

// Adds --device cpu|cuda|auto (default cpu) to `app`, into `device`.
void add_device_option(CLI::App& app, std::string& device);

// --device cuda with an --accel the GPU does not traverse (embree): the usage error's text
// (exit 1), or empty.
std::string device_accel_conflict(const std::string& device, const Options& o);

// The GPU back end for `scene` as `device` asks for it. cpu: none. cuda: the back end, or none and
// `error` (exit 2). auto: the back end, or none and `note`, the reason it renders on the CPU.
struct OpenedDevice {
  std::unique_ptr<CudaBackend> gpu;
  std::string error, note;
};
OpenedDevice open_device(const std::string& device, const RenderScene& scene);

// The summary's line: "device      cuda: …" (memory, upload and kernel times, Mrays/s) or
// "device      cpu (N threads)".
std::string device_line(const CudaBackend* gpu, const RenderStats& stats, int threads);

}  // namespace strahl::cli
