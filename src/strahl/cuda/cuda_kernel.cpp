// What a variant of the CUDA render kernel became on the chip, in words (cuda/cuda_backend.h).
// Part of libstrahl: the front ends print it with or without CUDA.

#include <string>

#include "strahl/cuda/cuda_backend.h"

namespace strahl {

std::string describe(const CudaKernel& k) {
  return std::to_string(k.registers) + " registers, " + std::to_string(k.local_bytes) +
         " B local memory per thread, " + std::to_string(k.blocks_per_sm) + (k.blocks_per_sm == 1 ? " block" : " blocks") +
         " of " + std::to_string(k.block) + " threads per SM";
}

}  // namespace strahl
