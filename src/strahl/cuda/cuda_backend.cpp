// The CUDA back end's host side: takes every tile of a pass from the job, flattens them into the
// per-pixel arrays the kernel reads (device.h), runs the pass on the GPU, and delivers each tile
// with its sums back to the job.

#include "strahl/cuda/cuda_backend.h"

#include <dlfcn.h>

#include <cstdio>
#include <optional>
#include <vector>

#include "strahl/cuda/device.h"
#include "strahl/render/render_scene.h"

namespace strahl {

using cuda_detail::Device;
using cuda_detail::PassData;
using cuda_detail::PassPixel;
using cuda_detail::PassTile;

struct CudaBackend::Impl {
  std::unique_ptr<Device> device;
  std::string error;
};

bool cuda_built() { return true; }

CudaBackend::CudaBackend() : impl_(std::make_unique<Impl>()) {}
CudaBackend::~CudaBackend() = default;

std::unique_ptr<CudaBackend> CudaBackend::create(const RenderScene& scene, std::string& error) {
  const AccelKind kind = scene.accel.kind;
  if (!scene.instances.empty()) {
    error = "the CUDA back end cannot render instances yet (the scene places " + std::to_string(scene.instances.size()) +
            "): use --device cpu, or write the objects in place";
    return nullptr;
  }
  if (kind != AccelKind::Bvh && kind != AccelKind::Naive) {
    error = "the CUDA back end traverses the BVH (or the naive loop), not the " + std::string(accel_name(kind)) +
            ": use --accel bvh with --device cuda";
    return nullptr;
  }
  // Without the driver's library the CUDA runtime reports only an "insufficient" driver: say what
  // is missing.
  if (void* driver = dlopen("libcuda.so.1", RTLD_NOW | RTLD_LOCAL)) {
    dlclose(driver);
  } else {
    error = "no CUDA driver (libcuda.so.1 cannot be loaded)";
    return nullptr;
  }
  std::unique_ptr<Device> device = Device::open(error);
  if (!device) return nullptr;
  if (!device->upload(scene, error)) return nullptr;
  std::unique_ptr<CudaBackend> b(new CudaBackend());
  b->impl_->device = std::move(device);
  return b;
}

void CudaBackend::render_pass(RenderJob& job) {
  std::vector<TileWork> works;
  while (std::optional<TileWork> w = job.next_tile()) works.push_back(std::move(*w));
  if (works.empty()) return;
  const FilmParams film = job.film_layout().params();

  PassData pass;
  std::size_t pixels = 0, fixed = 0;
  for (const TileWork& w : works) {
    pixels += w.rect.pixels();
    fixed += w.fixed.size();
  }
  pass.pixels.reserve(pixels);
  if (film.local) pass.local.reserve(pixels * 4);
  if (film.stats) pass.stats.reserve(pixels);
  pass.fixed.assign(fixed, 0);
  pass.tiles.reserve(works.size());
  std::uint64_t offset = 0;
  for (std::size_t t = 0; t < works.size(); ++t) {
    const TileWork& w = works[t];
    const TileRect& r = w.rect;
    for (int row = r.row0; row < r.row1; ++row)
      for (int x = r.x0; x < r.x1; ++x) {
        const std::size_t i = r.index(x, row);
        pass.pixels.push_back({x, row, w.first[i], w.count[i], std::uint32_t(t)});
      }
    if (film.local) pass.local.insert(pass.local.end(), w.local.begin(), w.local.end());
    if (film.stats) pass.stats.insert(pass.stats.end(), w.stats.begin(), w.stats.end());
    pass.tiles.push_back({w.bx0, w.brow0, w.bw, w.bh, offset});
    offset += w.fixed.size();
  }

  RayCounters counters;
  const StopToken& stop = job.stop();
  const bool ok = impl_->error.empty() &&
                  impl_->device->run(job.view(), job.sampler(), film, pass, [&] { return stop.requested(); }, counters,
                                     impl_->error);
  if (!ok) {  // every tile back unchanged (no samples taken), and the job stops
    job.cancel();
    for (TileWork& w : works) job.deliver(std::move(w));
    return;
  }

  std::size_t p = 0;
  for (std::size_t t = 0; t < works.size(); ++t) {
    TileWork& w = works[t];
    const std::size_t n = w.rect.pixels();
    for (std::size_t i = 0; i < n; ++i) w.taken[i] = pass.taken[p + i];
    if (film.local)
      std::copy(pass.local.begin() + std::ptrdiff_t(p * 4), pass.local.begin() + std::ptrdiff_t((p + n) * 4),
                w.local.begin());
    if (film.stats)
      std::copy(pass.stats.begin() + std::ptrdiff_t(p), pass.stats.begin() + std::ptrdiff_t(p + n), w.stats.begin());
    const std::size_t off = pass.tiles[t].fixed_offset;
    std::copy(pass.fixed.begin() + std::ptrdiff_t(off), pass.fixed.begin() + std::ptrdiff_t(off + w.fixed.size()),
              w.fixed.begin());
    p += n;
  }
  works[0].counters = counters;  // the job sums the tiles' counters
  for (TileWork& w : works) job.deliver(std::move(w));
}

CudaStats CudaBackend::stats() const {
  const Device& d = *impl_->device;
  CudaStats s;
  char line[256];
  std::snprintf(line, sizeof line, "%s (compute capability %d.%d, %d SMs, %.0f GiB)", d.info().name.c_str(),
                d.info().major, d.info().minor, d.info().multiprocessors,
                double(d.info().memory_total) / double(1ull << 30));
  s.device = line;
  s.memory_used = d.memory_used();
  s.memory_in_use = d.memory_in_use();
  s.memory_total = d.info().memory_total;
  s.upload_seconds = d.upload_seconds();
  s.kernel_seconds = d.kernel_seconds();
  s.launches = d.launches();
  return s;
}

const std::string& CudaBackend::error() const { return impl_->error; }

double CudaBackend::last_kernel_seconds() const { return impl_->device->last_kernel_seconds(); }

double CudaBackend::primary_seconds(const SceneView& view, int frames, std::string& error) {
  return impl_->device->primary_benchmark(view, frames, error);
}

}  // namespace strahl
