// The CUDA back end where CMake found no nvcc (or -DSTRAHL_CUDA=OFF): every request for it says
// that strahl was built without CUDA.

#include "strahl/cuda/cuda_backend.h"

namespace strahl {

struct CudaBackend::Impl {
  std::string error;
};

bool cuda_built() { return false; }

CudaBackend::CudaBackend() : impl_(std::make_unique<Impl>()) {}
CudaBackend::~CudaBackend() = default;

std::unique_ptr<CudaBackend> CudaBackend::create(const RenderScene&, std::string& error) {
  error = "strahl was built without CUDA (no nvcc found at configure time; see docs/gpu.md)";
  return nullptr;
}

void CudaBackend::render_pass(RenderJob&) {}
bool CudaBackend::holds(const SceneView&) const { return false; }
CudaStats CudaBackend::stats() const { return {}; }
const std::string& CudaBackend::error() const { return impl_->error; }
const std::vector<CudaKernel>& CudaBackend::kernels() const {
  static const std::vector<CudaKernel> none;
  return none;
}
bool CudaBackend::use_kernel(int) { return false; }
double CudaBackend::last_kernel_seconds() const { return 0; }
double CudaBackend::primary_seconds(const SceneView&, int, std::string& error) {
  error = "strahl was built without CUDA";
  return -1;
}

}  // namespace strahl
