#pragma once
// The viewer's back end under --device (docs/viewer.md, docs/gpu.md): the GPU for the scene shown
// now, where one is asked for and usable, the CPU's threads otherwise. The scene changes (live
// reload, another accelerator) while frames render: each new scene is uploaded as it comes, and
// a frame of a scene the GPU does not hold (an older one, or the kd-tree) renders on the CPU.

#include <memory>
#include <mutex>
#include <string>

#include "strahl/cuda/cuda_backend.h"
#include "strahl/render/cpu_backend.h"
#include "strahl/render/render_scene.h"

namespace strahl::view {

class DeviceBackend final : public TileBackend {
 public:
  // `device`: cpu, cuda or auto (cli::add_device_option); `threads` for the CPU.
  DeviceBackend(std::string device, int threads);

  // The scene frames render from now on: uploaded to the GPU when the device asks for one. The
  // reason the GPU does not render it (none usable, out of memory, the kd-tree), or empty.
  std::string use_scene(std::shared_ptr<const RenderScene> scene);
  // The GPU's back end for `scene` opened elsewhere (the first scene, before the window opens).
  void adopt_gpu(std::shared_ptr<const RenderScene> scene, std::unique_ptr<CudaBackend> gpu);

  void render_pass(RenderJob& job) override;

  // "cuda: <the GPU>" while the GPU renders the current scene, else "cpu".
  std::string device_name() const;
  // A GPU pass that failed since the last call (its frame stopped; the CPU renders from then on),
  // or empty.
  std::string take_failure();

 private:
  std::string device_;
  CpuBackend cpu_;
  mutable std::mutex mutex_;
  std::shared_ptr<const RenderScene> scene_;  // the scene the GPU holds
  std::shared_ptr<CudaBackend> gpu_;
  std::string gpu_name_;
  bool failed_ = false;  // a GPU pass failed: the CPU renders from then on
  std::string failure_;
};

}  // namespace strahl::view
