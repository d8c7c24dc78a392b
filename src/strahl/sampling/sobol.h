#pragma once
// The first two dimensions of the Sobol sequence as 0.32 fixed-point values. Together they form
// a (0,2)-sequence: every aligned block of 2^m points is stratified in every 2^a × 2^b
// elementary interval with a + b = m. The pixel sampler pads further dimension pairs with
// independently scrambled and shuffled copies of these two (Burley 2020), so no higher Sobol
// dimensions (and their weaker projections) are needed.

#include <cstdint>

#include "strahl/math/config.h"
#include "strahl/sampling/permute.h"

namespace strahl {

// Dimension 0: the van der Corput sequence in base 2 (the index's bits reversed).
STRAHL_HOST_DEVICE constexpr std::uint32_t sobol_dim0(std::uint32_t index) { return reverse_bits(index); }

// Dimension 1: primitive polynomial x + 1, direction numbers v_k = v_{k-1} ^ (v_{k-1} >> 1), i.e.
// the Pascal matrix mod 2: by Lucas' theorem output bit k (from the top) is the parity of the
// index bits i whose binary digits contain k's. That superset-parity transform takes five steps
// (one per bit of the 5-bit bit position), then the bits are reversed: sobol_dim1 is
// reverse_bits(sobol_dim1_unreversed(index)).
STRAHL_HOST_DEVICE constexpr std::uint32_t sobol_dim1_unreversed(std::uint32_t x) {
  x ^= (x >> 1) & 0x55555555u;
  x ^= (x >> 2) & 0x33333333u;
  x ^= (x >> 4) & 0x0f0f0f0fu;
  x ^= (x >> 8) & 0x00ff00ffu;
  x ^= (x >> 16) & 0x0000ffffu;
  return x;
}

STRAHL_HOST_DEVICE constexpr std::uint32_t sobol_dim1(std::uint32_t index) { return reverse_bits(sobol_dim1_unreversed(index)); }

// One Owen-scrambled, shuffled Sobol pair (Burley 2020) as 0.32 fixed-point values:
//   shuffled = owen_scramble(index, s0)
//   a = owen_scramble(sobol_dim0(shuffled), s1),  b = owen_scramble(sobol_dim1(shuffled), s2)
// with the bit reversals that cancel left out (owen_scramble(x, s) = reverse(laine_karras(reverse(x), s))
// and sobol_dim0 = reverse, sobol_dim1 = reverse ∘ parity): four reversals instead of eight, the
// same bits (PixelSampler.SobolPairIsTheComposition).
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE constexpr void sobol_pair(std::uint32_t index, std::uint32_t s0, std::uint32_t s1,
                                                                 std::uint32_t s2, std::uint32_t& a, std::uint32_t& b) {
  const std::uint32_t shuffled = reverse_bits(laine_karras(reverse_bits(index), s0));
  a = reverse_bits(laine_karras(shuffled, s1));
  b = reverse_bits(laine_karras(sobol_dim1_unreversed(shuffled), s2));
}

// 0.32 fixed point to [0, 1) (never 1).
STRAHL_HOST_DEVICE constexpr Real fixed_to_unit(std::uint32_t x) { return Real(x) * Real(1.0 / 4294967296.0); }

}  // namespace strahl
