#pragma once
// Between the CUDA back end's host logic (cuda_backend.cpp, plain C++) and the one CUDA
// translation unit (device.cu): what a pass hands the GPU and gets back. No CUDA header here.
//
// A pass is flattened into per-pixel arrays over every tile the job handed out (cuda/flat_pass.h).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "strahl/cuda/cuda_backend.h"
#include "strahl/cuda/flat_pass.h"

namespace strahl {
struct RenderScene;
}

namespace strahl::cuda_detail {

struct DeviceInfo {
  std::string name;
  int major = 0, minor = 0, multiprocessors = 0;
  std::size_t memory_total = 0;
  std::vector<CudaKernel> kernels;  // the render kernel's variants; the first renders unless use_kernel()
};

// One CUDA device holding one uploaded scene.
class Device {
 public:
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  // The first CUDA device, checked to run this build's kernels; nullptr and a one-line reason
  // (no driver, no device, no kernel image for the chip, …) otherwise.
  static std::unique_ptr<Device> open(std::string& error);
  const DeviceInfo& info() const { return info_; }

  // The render kernel's variant that passes launch (an index into info().kernels; 0 at first).
  // False for an index out of range.
  bool use_kernel(int index);
  int kernel() const { return kernel_; }

  // Copies every array of `view` to device memory (once; the scene stays resident) and sizes the
  // threads' stacks. False and a reason (out of memory, …) on failure.
  bool upload(const RenderScene& scene, std::string& error);

  // The job's view of the uploaded scene (its camera and settings may differ from the scene's)
  // has arrays this device holds: false when one was not uploaded, or an accelerator other than
  // the BVH (or the naive loop) is asked for.
  bool holds(const SceneView& view) const;

  // Renders the pass of `view` in place: one thread per pixel, its samples in sample order. `stop` is
  // polled while the kernel runs; when it returns true the kernel stops between two samples
  // (PassData::taken says how far each pixel got).
  bool run(const SceneView& view, const PixelSampler& sampler, const FilmParams& film, PassData& pass, const std::function<bool()>& stop,
           RayCounters& counters, std::string& error);

  // Primary rays only (nearest hit of one camera ray per pixel, pixel centres), `frames` launches
  // over a width × height image after one warm-up; the median kernel time of one launch in
  // seconds, or a negative number and `error`.
  double primary_benchmark(const SceneView& view, int frames, std::string& error);

  std::size_t memory_used() const;  // device memory this scene and the last pass hold, bytes
  // Device memory in use, all of it (cudaMemGetInfo): the above, the CUDA context and the stack
  // the driver reserves for every resident thread.
  std::size_t memory_in_use() const;
  double upload_seconds() const { return upload_seconds_; }
  double kernel_seconds() const { return kernel_seconds_; }  // every launch of run() so far
  std::uint64_t launches() const { return launches_; }
  double last_kernel_seconds() const { return last_kernel_seconds_; }

 private:
  Device() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  DeviceInfo info_;
  double upload_seconds_ = 0, kernel_seconds_ = 0, last_kernel_seconds_ = 0;
  std::uint64_t launches_ = 0;
  int kernel_ = 0;
};

}  // namespace strahl::cuda_detail
