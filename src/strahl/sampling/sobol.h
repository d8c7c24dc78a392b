#pragma once
// The first two dimensions of the Sobol sequence as 0.32 fixed-point values. Together they form
// a (0,2)-sequence: every aligned block of 2^m points is stratified in every 2^a × 2^b
// elementary interval with a + b = m. The pixel sampler pads further dimension pairs with
// independently scrambled and shuffled copies of these two (Burley 2020), so no higher Sobol
// dimensions (and their weaker projections) are needed.

#include <cstdint>

#include "strahl/math/config.h"

namespace strahl {

// Dimension 0: the van der Corput sequence in base 2 (the index's bits reversed).
STRAHL_HOST_DEVICE constexpr std::uint32_t sobol_dim0(std::uint32_t index) {
  std::uint32_t x = 0;
  for (std::uint32_t v = 0x80000000u; index != 0; index >>= 1, v >>= 1)
    if (index & 1u) x ^= v;
  return x;
}

// Dimension 1: primitive polynomial x + 1, direction numbers v_k = v_{k-1} ^ (v_{k-1} >> 1).
STRAHL_HOST_DEVICE constexpr std::uint32_t sobol_dim1(std::uint32_t index) {
  std::uint32_t x = 0;
  for (std::uint32_t v = 0x80000000u; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) x ^= v;
  return x;
}

// 0.32 fixed point to [0, 1) (never 1).
STRAHL_HOST_DEVICE constexpr Real fixed_to_unit(std::uint32_t x) { return Real(x) * Real(1.0 / 4294967296.0); }

}  // namespace strahl
