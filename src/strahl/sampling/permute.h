#pragma once
// Hash-based permutations for the pixel samplers: Owen scrambling of 32-bit fixed-point values
// (Laine–Karras, as in Burley 2020, "Practical Hash-based Owen Scrambling") and random
// permutations of [0, n) evaluated element by element (Kensler 2013, "Correlated Multi-Jittered
// Sampling"). Pure functions of their arguments: no tables, no state.

#include <cmath>
#include <cstdint>

#include "strahl/math/config.h"

namespace strahl {

STRAHL_HOST_DEVICE constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
#if defined(__GNUC__) && !defined(__CUDA_ARCH__)
  return __builtin_bswap32(x);  // the bytes' order in one instruction
#else
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
#endif
}

// Each bit flipped by a hash of the bits below it (a Laine–Karras permutation). Applied to
// bit-reversed values it is an Owen scramble: a bit's flip depends only on the more significant ones.
STRAHL_HOST_DEVICE constexpr std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Owen scrambling (nested uniform scrambling) of a 0.32 fixed-point value.
STRAHL_HOST_DEVICE constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(x), seed));
}

// One round of Kensler's hash of i within the mask w (2^k − 1 ≥ n − 1).
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE constexpr std::uint32_t permutation_round(std::uint32_t i, std::uint32_t w, std::uint32_t seed) {
  i ^= seed;
  i *= 0xe170893du;
  i ^= seed >> 16;
  i ^= (i & w) >> 4;
  i ^= seed >> 8;
  i *= 0x0929eb3fu;
  i ^= seed >> 23;
  i ^= (i & w) >> 1;
  i *= 1 | seed >> 27;
  i *= 0x6935fa69u;
  i ^= (i & w) >> 11;
  i *= 0x74dcb303u;
  i ^= (i & w) >> 2;
  i *= 0x9e501cc3u;
  i ^= (i & w) >> 2;
  i *= 0xc860a3dfu;
  i &= w;
  i ^= i >> 5;
  return i;
}

// The mask 2^k − 1 ≥ n − 1 of the hash's rounds (n ≥ 1).
STRAHL_HOST_DEVICE constexpr std::uint32_t permutation_mask(std::uint32_t n) {
  std::uint32_t w = n - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  return w;
}

// Element i of a random permutation of [0, n) chosen by `seed` (Kensler's cycle-walking hash).
STRAHL_HOST_DEVICE constexpr std::uint32_t permutation_element(std::uint32_t i, std::uint32_t n, std::uint32_t seed) {
  if (n <= 1) return 0;
  const std::uint32_t w = permutation_mask(n);
  do {
    i = permutation_round(i, w, seed);
  } while (i >= n);
  if ((n & (n - 1)) == 0) return (i + seed) & (n - 1);  // n a power of two: the same as % n
  return (i + seed) % n;
}

// permutation_element(i, n, seed) for a power of two n > 1: one round always lands below n
// (the round's result has no bit above w = n − 1), so there is no walk — a loop over many i
// runs side by side.
STRAHL_HOST_DEVICE constexpr std::uint32_t permutation_element_pow2(std::uint32_t i, std::uint32_t n, std::uint32_t seed) {
  return (permutation_round(i, n - 1, seed) + seed) & (n - 1);
}

// x / d and x % d for x < 2^32 and 1 ≤ d ≤ 2^20, exactly, in doubles (which a loop over lanes
// runs side by side, where integer division has no SIMD instruction): x·(1/d) lies within 2^-20
// of x/d, so its integer part is off by at most one, which the remainder's range then corrects.
// `inv` is 1/d.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void divide_exactly(std::uint32_t x, double d, double inv, std::uint32_t& quotient,
                                                           std::uint32_t& remainder) {
  double q = std::trunc(double(x) * inv);
  double r = double(x) - q * d;  // exact: integers below 2^53
  if (r < 0) {
    q -= 1, r += d;
  } else if (r >= d) {
    q += 1, r -= d;
  }
  quotient = std::uint32_t(q);
  remainder = std::uint32_t(r);
}

// permutation_element(i[j], n, seed[j]) for N lanes and any n > 1 (n ≤ 2^20): the lanes' walks
// side by side — while any lane's value is still ≥ n, every such lane takes one more round (the
// others keep theirs) — then (value + seed) % n by divide_exactly.
template <int N>
STRAHL_HOST_DEVICE inline void permutation_elements(const std::uint32_t* __restrict i, std::uint32_t n,
                                                    const std::uint32_t* __restrict seed, std::uint32_t* __restrict out) {
  const std::uint32_t w = permutation_mask(n);
  std::uint32_t v[N];
  for (int j = 0; j < N; ++j) v[j] = permutation_round(i[j], w, seed[j]);
  for (;;) {
    std::uint32_t walking = 0;
    for (int j = 0; j < N; ++j) walking |= std::uint32_t(v[j] >= n);
    if (walking == 0) break;
    for (int j = 0; j < N; ++j) {
      const std::uint32_t next = permutation_round(v[j], w, seed[j]);
      v[j] = v[j] >= n ? next : v[j];
    }
  }
  const double d = double(n), inv = 1 / d;
  for (int j = 0; j < N; ++j) {
    std::uint32_t q;
    divide_exactly(v[j] + seed[j], d, inv, q, out[j]);
  }
}

}  // namespace strahl
