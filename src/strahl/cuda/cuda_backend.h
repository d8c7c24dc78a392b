#pragma once
// The CUDA back end (docs/gpu.md): the render job's tiles rendered on an NVIDIA GPU by the same
// kernel functions the CPU runs. The scene is uploaded once; each pass's tiles go to the GPU in
// one launch (one thread per pixel, its samples in sample order, so the film's sums are the same
// additions as on the CPU) and come back to the job's film. Only the BVH (and the naive loop)
// run there (gpu_traverses: not Embree's). Built only where CMake found nvcc; elsewhere create()
// says strahl was built without CUDA.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/render/render_job.h"

namespace strahl {

struct RenderScene;

// Whether this strahl was built with the CUDA back end.
bool cuda_built();

// The structures the GPU traverses: the BVH, the kd-tree, the octree (portable code, ropes
// without a stack) and the naive loop — all but Embree's.
constexpr bool gpu_traverses(AccelKind kind) {
  return kind == AccelKind::Bvh || kind == AccelKind::Naive || kind == AccelKind::KdTree || kind == AccelKind::Octree;
}

// One variant of the render kernel as the driver loaded it (cuda/device.cu: ptxas fits the
// registers so that `min_blocks` blocks share a multiprocessor).
struct CudaKernel {
  int min_blocks = 0;           // __launch_bounds__'s second argument
  int block = 0;                // threads per block
  int registers = 0;            // per thread
  std::size_t local_bytes = 0;  // local memory per thread: the stack frame, spills included
  int blocks_per_sm = 0;        // resident blocks per multiprocessor (the occupancy)
};

// "255 registers, 36784 B local memory per thread, 2 blocks of 128 threads per SM"
std::string describe(const CudaKernel& k);

struct CudaStats {
  std::string device;  // e.g. "NVIDIA H200 (compute capability 9.0, 132 SMs, 140 GiB)"
  std::size_t memory_used = 0;   // bytes of device memory held: the scene and the last pass
  std::size_t memory_in_use = 0; // bytes in use on the device (cudaMemGetInfo): the above, the
                                 // CUDA context, the per-thread stacks the driver reserved
  std::size_t memory_total = 0;  // the device's memory, bytes
  double upload_seconds = 0;     // the scene's upload
  double kernel_seconds = 0;     // every kernel launch (device time, CUDA events)
  std::uint64_t launches = 0;
  std::string kernel;            // the render kernel in use, describe()d
};

class CudaBackend final : public TileBackend {
 public:
  // Opens the first CUDA device and uploads `scene`, which must outlive the back end (jobs render
  // views of it: their camera and settings may differ). nullptr and one line in `error` when
  // there is no usable GPU (no driver, no device, no kernel image for the chip, out of memory),
  // when strahl was built without CUDA, or when the scene's structure is Embree's.
  static std::unique_ptr<CudaBackend> create(const RenderScene& scene, std::string& error);
  ~CudaBackend() override;

  void render_pass(RenderJob& job) override;
  // Whether a job over `view` can render here: a view of the uploaded scene (its camera and
  // settings may differ) through a structure the GPU traverses.
  bool holds(const SceneView& view) const;

  CudaStats stats() const;
  // Set when a pass failed on the GPU: the job was cancelled, every tile taken delivered
  // unchanged. Empty otherwise.
  const std::string& error() const;
  // The render kernel's variants this build holds (CMake's STRAHL_CUDA_KERNEL_MIN_BLOCKS; one
  // unless built for measuring), and the one passes launch: an index into kernels(), 0 at first.
  const std::vector<CudaKernel>& kernels() const;
  bool use_kernel(int index);  // false for an index out of range
  // Kernel time of the last pass, seconds.
  double last_kernel_seconds() const;
  // Primary rays (one per pixel through its centre, nearest hit): median kernel seconds of one
  // launch over `frames` launches of `view`'s image; negative and `error` on failure.
  double primary_seconds(const SceneView& view, int frames, std::string& error);

 private:
  CudaBackend();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strahl
