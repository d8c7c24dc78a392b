// The CUDA back end's host side: opens the device, uploads the scene, and renders each pass of the
// job as one flat launch (cuda/flat_pass_job.h) on the GPU.

#include "strahl/cuda/cuda_backend.h"

#include <dlfcn.h>

#include <cstdio>

#include "strahl/cuda/device.h"
#include "strahl/cuda/flat_pass_job.h"
#include "strahl/render/render_scene.h"

namespace strahl {

using cuda_detail::Device;

struct CudaBackend::Impl {
  std::unique_ptr<Device> device;
  std::string error;
};

bool cuda_built() { return true; }

CudaBackend::CudaBackend() : impl_(std::make_unique<Impl>()) {}
CudaBackend::~CudaBackend() = default;

std::unique_ptr<CudaBackend> CudaBackend::create(const RenderScene& scene, std::string& error) {
  const AccelKind kind = scene.accel.kind;
  if (!gpu_traverses(kind)) {
    error = "the CUDA back end does not traverse " + std::string(accel_name(kind)) +
            "'s structure: use --accel bvh (or kdtree, octree, naive) with --device cuda";
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
  render_flat_pass(job, [&](const FilmParams& film, PassData& pass, RayCounters& counters) {
    const StopToken& stop = job.stop();
    return impl_->error.empty() && impl_->device->run(job.view(), job.sampler(), film, pass,
                                                      [&] { return stop.requested(); }, counters, impl_->error);
  });
}

bool CudaBackend::holds(const SceneView& view) const { return impl_->device->holds(view); }

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
  s.kernel = describe(d.info().kernels[std::size_t(d.kernel())]);
  return s;
}

const std::vector<CudaKernel>& CudaBackend::kernels() const { return impl_->device->info().kernels; }
bool CudaBackend::use_kernel(int index) { return impl_->device->use_kernel(index); }

const std::string& CudaBackend::error() const { return impl_->error; }

double CudaBackend::last_kernel_seconds() const { return impl_->device->last_kernel_seconds(); }

double CudaBackend::primary_seconds(const SceneView& view, int frames, std::string& error) {
  return impl_->device->primary_benchmark(view, frames, error);
}

}  // namespace strahl
