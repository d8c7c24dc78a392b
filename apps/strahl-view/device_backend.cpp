#include "device_backend.h"

#include <utility>

namespace strahl::view {

DeviceBackend::DeviceBackend(std::string device, int threads) : device_(std::move(device)), cpu_(threads) {}

std::string DeviceBackend::use_scene(std::shared_ptr<const RenderScene> scene) {
  {
    const std::lock_guard lock(mutex_);
    if (device_ == "cpu" || failed_) return {};
    gpu_.reset();  // the old scene's device memory first (a frame rendering it keeps its own share)
    scene_.reset();
  }
  // The upload without the lock: a frame of the old scene meanwhile renders on the CPU.
  std::string why;
  std::unique_ptr<CudaBackend> gpu = CudaBackend::create(*scene, why);
  if (!gpu) return "the GPU does not render this scene (" + why + "); rendering on the CPU";
  adopt_gpu(std::move(scene), std::move(gpu));
  return {};
}

void DeviceBackend::adopt_gpu(std::shared_ptr<const RenderScene> scene, std::unique_ptr<CudaBackend> gpu) {
  const std::lock_guard lock(mutex_);
  scene_ = std::move(scene);
  gpu_ = std::move(gpu);
  gpu_name_ = gpu_ ? "cuda: " + gpu_->stats().device : "";
}

void DeviceBackend::render_pass(RenderJob& job) {
  std::shared_ptr<CudaBackend> gpu;
  {
    const std::lock_guard lock(mutex_);
    gpu = gpu_;
  }
  if (!gpu || !gpu->holds(job.view())) {
    cpu_.render_pass(job);
    return;
  }
  gpu->render_pass(job);
  if (gpu->error().empty()) return;
  const std::lock_guard lock(mutex_);
  failed_ = true;
  failure_ = "--device " + device_ + ": " + gpu->error() + "; rendering on the CPU from now on";
  if (gpu_ == gpu) {
    gpu_.reset();
    scene_.reset();
  }
}

std::string DeviceBackend::device_name() const {
  const std::lock_guard lock(mutex_);
  return gpu_ ? gpu_name_ : "cpu";
}

std::string DeviceBackend::take_failure() {
  const std::lock_guard lock(mutex_);
  return std::exchange(failure_, {});
}

}  // namespace strahl::view
