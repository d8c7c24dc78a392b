#pragma once
// Blinn-Phong's highlight and shade_from()'s term of one light (render/whitted.h), one at a time
// and in lanes side by side: the packet front end shades a pixel's camera samples together
// (render/packet_radiance.h), the area lights a shading point's samples together. The lanes
// take the same operations on the same values as shade_from(), so the images are the same bit
// for bit.

#include <cmath>
#include <cstdint>

#include "strahl/accel/wide_bvh.h"
#include "strahl/math/vec3.h"

namespace strahl {

// x^e for the Blinn-Phong exponent: by repeated squaring when e is a whole number below 2^16
// (a handful of multiplications instead of a call to pow, which dominated the shading cost).
STRAHL_HOST_DEVICE inline Real specular_power(Real x, Real e) {
  if (e >= 0 && e < 65536 && e == Real(static_cast<unsigned>(e))) {
    Real result = 1;
    for (unsigned n = static_cast<unsigned>(e); n != 0; n >>= 1) {
      if (n & 1) result *= x;
      x *= x;
    }
    return result;
  }
  return std::pow(x, e);
}

// specular_power(x[i], e) for a whole exponent e < 65536, the lanes side by side, into power[]:
// the same multiplications in the same order. The lanes are held in vectors of four, so that the
// compiler keeps them in vector registers through the loop over e's bits (as arrays of Reals it
// takes them apart into scalars there).
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void whole_power_lanes(const Real* __restrict x_in, unsigned e,
                                                              Real* __restrict power) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__)
  static_assert(N % 4 == 0);
  using Real4 = Real __attribute__((vector_size(4 * sizeof(Real))));
  Real4 p[N / 4], x[N / 4];
  for (int c = 0; c < N / 4; ++c) {
    p[c] = Real4{1, 1, 1, 1};
    x[c] = Real4{x_in[4 * c], x_in[4 * c + 1], x_in[4 * c + 2], x_in[4 * c + 3]};
  }
  for (unsigned n = e; n != 0; n >>= 1) {
    if (n & 1)
      for (int c = 0; c < N / 4; ++c) p[c] *= x[c];
    for (int c = 0; c < N / 4; ++c) x[c] *= x[c];
  }
  for (int c = 0; c < N / 4; ++c)
    for (int k = 0; k < 4; ++k) power[4 * c + k] = p[c][k];
#else
  Real x[N];
  for (int i = 0; i < N; ++i) power[i] = 1, x[i] = x_in[i];
  for (unsigned n = e; n != 0; n >>= 1) {
    if (n & 1)
      for (int i = 0; i < N; ++i) power[i] *= x[i];
    for (int i = 0; i < N; ++i) x[i] *= x[i];
  }
#endif
}

// The per-surface terms of local_terms() in lanes, as add_light_lanes() reads them.
template <int N>
struct ShadingLanes {
  Real cr[N], cg[N], cb[N];  // the colour c
  Real kd[N];                // k_d times the opacity
  Real sr[N], sg[N], sb[N];  // k_s
  Real shiny[N], shininess[N];
};

// shade_from()'s term of a light of intensity (i_r[i], i_g[i], i_b[i]) in lane i (a point or
// directional light, or one sample of an area light), added to r in the lanes of `lanes` — the
// same operations on the same values, lane by lane: Lambert, Blinn-Phong where dot(n, h) > 0 and
// k_s is not black, times the intensity and the shadow ray's transmittance (tr_x, tr_y, tr_z); 0
// where it is black (in shadow) or where the lane cast no shadow ray (not in `cast`:
// dot(n, to_light) ≤ 0, or a black intensity).
template <int N>
STRAHL_HOST_DEVICE STRAHL_NOINLINE void add_light_lanes(const Real* __restrict i_r, const Real* __restrict i_g,
                                                        const Real* __restrict i_b, std::uint32_t lanes,
                                                        std::uint32_t cast, const Real* __restrict n_dot_l,
                                                        const Real* __restrict n_dot_h, const Real* __restrict tr_x,
                                                        const Real* __restrict tr_y, const Real* __restrict tr_z,
                                                        const ShadingLanes<N>& __restrict terms, Real* __restrict rr,
                                                        Real* __restrict rg, Real* __restrict rb) {
  const Real* const cr = terms.cr; const Real* const cg = terms.cg; const Real* const cb = terms.cb;
  const Real* const kd = terms.kd; const Real* const sr = terms.sr; const Real* const sg = terms.sg;
  const Real* const sb = terms.sb; const Real* const shiny = terms.shiny; const Real* const shininess = terms.shininess;
  // specular_power(n_dot_h, shininess) side by side when the lanes share a whole exponent (one
  // material, as a pixel's samples mostly are), else lane by lane.
  Real power[N] = {};
  const int first = wide_bvh_detail::lowest_bit(lanes);
  const Real e = shininess[first];
  Real exponent[N];  // the lanes' exponents, e outside `lanes`
  for (int i = 0; i < N; ++i) exponent[i] = shininess[i];
  for (std::uint32_t m = ~lanes & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) exponent[wide_bvh_detail::lowest_bit(m)] = e;
  int differ = 0;
  for (int i = 0; i < N; ++i) differ |= int(exponent[i] != e);
  if (differ == 0 && e >= 0 && e < 65536 && e == Real(static_cast<unsigned>(e))) {
    whole_power_lanes<N>(n_dot_h, static_cast<unsigned>(e), power);
  } else {
    for (std::uint32_t m = lanes; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      power[i] = specular_power(n_dot_h[i], shininess[i]);
    }
  }
  // The transmittances side by side, 0 in the lanes that add nothing: then every test below is
  // one on Reals, and the loop runs the lanes together.
  Real tx[N], ty[N], tz[N];
  for (int i = 0; i < N; ++i) tx[i] = tr_x[i], ty[i] = tr_y[i], tz[i] = tr_z[i];
  for (std::uint32_t m = ~(lanes & cast) & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    tx[i] = ty[i] = tz[i] = 0;
  }
  // Every value computed in every lane, then chosen by comparisons of Reals (no bools, no
  // branches): the loop runs the lanes side by side. shiny[i] ≠ 0: k_s is not black.
  for (int i = 0; i < N; ++i) {
    const Real diffuse = kd[i] * n_dot_l[i];
    const Real x = cr[i] * diffuse, y = cg[i] * diffuse, z = cb[i] * diffuse;
    const Real xs = x + sr[i] * power[i], ys = y + sg[i] * power[i], zs = z + sb[i] * power[i];
    const Real ax = (n_dot_h[i] > 0 ? (shiny[i] != 0 ? xs : x) : x) * i_r[i] * tx[i];
    const Real ay = (n_dot_h[i] > 0 ? (shiny[i] != 0 ? ys : y) : y) * i_g[i] * ty[i];
    const Real az = (n_dot_h[i] > 0 ? (shiny[i] != 0 ? zs : z) : z) * i_b[i] * tz[i];
    // shade_from adds nothing where the transmittance is black: (tx, ty, tz) = 0.
    rr[i] = rr[i] + (tx[i] != 0 ? ax : ty[i] != 0 ? ax : tz[i] != 0 ? ax : Real(0));
    rg[i] = rg[i] + (tx[i] != 0 ? ay : ty[i] != 0 ? ay : tz[i] != 0 ? ay : Real(0));
    rb[i] = rb[i] + (tx[i] != 0 ? az : ty[i] != 0 ? az : tz[i] != 0 ? az : Real(0));
  }
}

}  // namespace strahl
