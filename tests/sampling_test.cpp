// Sampling routines: every warp of sampling/warp.h follows its density (chi-square), the pixel
// samplers are stratified as they claim (exact checks) and uniform (chi-square), and the
// reconstruction filters integrate to their closed forms with the stated support.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <set>
#include <vector>

#include "chi_square.h"
#include "strahl/sampling/filter.h"
#include "strahl/sampling/pixel_sampler.h"
#include "strahl/sampling/warp.h"

namespace strahl::sampling_test {
namespace {

// Grid and stratified sides that are powers of two take shifts, masks and exact reciprocals
// (PixelSequence::side_shift) instead of divisions: every sample, in every round, with lens and
// time used, must be the general path's bit for bit; and the shift is set for exactly those sides.
TEST(PixelSampler, PowerOfTwoSidesMatchTheDivisions) {
  for (SamplerKind kind : {SamplerKind::Grid, SamplerKind::Stratified}) {
    for (std::uint32_t side = 1; side <= 33; ++side) {
      PixelSampler sampler;
      sampler.kind = kind;
      sampler.side = side;
      sampler.seed = side * 7;
      PixelSequence fast = sampler.pixel(5, 3, 3 * 640 + 5);
      const bool pow2 = (side & (side - 1)) == 0;
      ASSERT_EQ(fast.side_shift >= 0, pow2) << side;
      if (pow2) {
        ASSERT_EQ(1u << fast.side_shift, side);
      }
      PixelSequence general = fast;
      general.side_shift = -1;
      for (const bool lens_time : {false, true}) {
        fast.uses_lens = fast.uses_time = general.uses_lens = general.uses_time = lens_time;
        for (std::uint32_t k = 0; k < 3 * side * side + 2; ++k) {
          const CameraSample a = fast.sample(k), b = general.sample(k);
          ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << sampler_name(kind) << " side " << side << " sample " << k;
        }
      }
    }
  }
}

// The lanes' paths (PixelSequence::samples, render/packet_radiance.h: strata_film_lanes,
// sobol_film_lanes) against sample() one by one: every side, packets of 8 and 16 starting
// anywhere in the first rounds (straddling two rounds too: each lane its round's order), sides
// that are powers of two and sides that are not, with and without lens and shutter, the film
// lanes (FilmLanes) the same positions and times, padded with lane 0's; the walk-free
// permutation equals the walking one for every power of two n and element, and the lanes' walks
// (permutation_elements) the walk of each for every n up to 300 and element; divide_exactly
// divides exactly.
template <int N>
void expect_lanes_match(const PixelSequence& p, std::uint32_t side) {
  for (std::uint32_t first = 0; first < 2 * side * side + 3; ++first) {
    for (int count = 1; count <= N; ++count) {
      CameraSample lanes[N];
      FilmLanes<N> film;
      p.samples<N>(first, count, lanes, film);
      for (int i = 0; i < N; ++i) {
        const CameraSample one = p.sample(first + std::uint32_t(i < count ? i : 0));  // (padded with lane 0's)
        if (i < count) {
          ASSERT_EQ(std::memcmp(&lanes[i], &one, sizeof one), 0) << "side " << side << " first " << first << " lane " << i;
        }
        ASSERT_EQ(std::memcmp(&film.x[i], &one.film_x, sizeof(Real)), 0) << "side " << side << " first " << first << " lane " << i;
        ASSERT_EQ(std::memcmp(&film.y[i], &one.film_y, sizeof(Real)), 0) << "side " << side << " first " << first << " lane " << i;
        ASSERT_EQ(std::memcmp(&film.time[i], &one.time, sizeof(Real)), 0) << "side " << side << " first " << first << " lane " << i;
      }
    }
  }
}

TEST(PixelSampler, LanesMatchSampleBySample) {
  for (std::uint32_t side : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 10u, 16u}) {
    for (SamplerKind kind : {SamplerKind::Grid, SamplerKind::Stratified, SamplerKind::Sobol}) {
      PixelSampler sampler;
      sampler.kind = kind;
      sampler.side = side;
      sampler.seed = 99 + side;
      for (const bool lens : {false, true})
        for (const bool time : {false, true}) {
          const PixelSequence p = sampler.pixel(7, 2, 2 * 640 + 7, lens, time);
          expect_lanes_match<8>(p, side);
          expect_lanes_match<16>(p, side);
        }
    }
  }
  for (std::uint32_t n = 2; n <= (1u << 12); n *= 2)
    for (std::uint32_t seed : {0u, 1u, 0x9e3779b9u, 0xdeadbeefu, 0xffffffffu})
      for (std::uint32_t i = 0; i < n; ++i)
        ASSERT_EQ(permutation_element_pow2(i, n, seed), permutation_element(i, n, seed)) << n << " " << seed << " " << i;
  constexpr int kLanes = 16;
  for (std::uint32_t n = 2; n <= 300; ++n)
    for (std::uint32_t first = 0; first < n; first += kLanes) {
      std::uint32_t i[kLanes], seed[kLanes], out[kLanes];
      for (int j = 0; j < kLanes; ++j)
        i[j] = (first + std::uint32_t(j)) % n, seed[j] = 0x9e3779b9u * (first + std::uint32_t(j) + n) ^ (j % 3 == 0 ? ~0u : 0u);
      permutation_elements<kLanes>(i, n, seed, out);
      for (int j = 0; j < kLanes; ++j) ASSERT_EQ(out[j], permutation_element(i[j], n, seed[j])) << n << " " << i[j];
    }
  for (std::uint32_t d : {1u, 2u, 3u, 7u, 9u, 36u, 1000u, 1023u, 1u << 20, (1u << 20) - 1}) {
    std::uint64_t k = d;
    for (int trial = 0; trial < 20000; ++trial) {
      k = k * 6364136223846793005ull + 1442695040888963407ull;
      const std::uint32_t x = trial < 3 * 1024 ? std::uint32_t(trial / 3) * d + std::uint32_t(trial % 3) - 1  // near multiples
                              : trial == 3 * 1024 ? ~0u : std::uint32_t(k >> 32);
      std::uint32_t q, r;
      divide_exactly(x, double(d), 1 / double(d), q, r);
      ASSERT_EQ(q, x / d) << x << " / " << d;
      ASSERT_EQ(r, x % d) << x << " % " << d;
    }
  }
}

// sobol_pair leaves out the bit reversals that cancel: it must equal the composition it stands for,
// owen_scramble(sobol_dim0 / sobol_dim1(owen_scramble(index, s0)), s1 / s2), on every bit.
TEST(PixelSampler, SobolPairIsTheComposition) {
  std::uint64_t k = 12345;
  const auto next = [&] {
    k = k * 6364136223846793005ull + 1442695040888963407ull;
    return std::uint32_t(k >> 32);
  };
  for (int trial = 0; trial < 200000; ++trial) {
    const std::uint32_t index = trial < 4096 ? std::uint32_t(trial) : next(), s0 = next(), s1 = next(), s2 = next();
    const std::uint32_t shuffled = owen_scramble(index, s0);
    std::uint32_t a, b;
    sobol_pair(index, s0, s1, s2, a, b);
    ASSERT_EQ(a, owen_scramble(sobol_dim0(shuffled), s1)) << index;
    ASSERT_EQ(b, owen_scramble(sobol_dim1(shuffled), s2)) << index;
  }
}

// A pixel's hashes for the lens and time dimensions are computed only where they are used; the
// samples are the same either way.
TEST(PixelSampler, UnusedDimensionsNeedNoHashes) {
  for (SamplerKind kind : {SamplerKind::Grid, SamplerKind::Stratified, SamplerKind::Sobol, SamplerKind::Adaptive}) {
    PixelSampler sampler;
    sampler.kind = kind;
    sampler.side = 4;
    sampler.seed = 3;
    PixelSequence all = sampler.pixel(7, 2, 2 * 640 + 7);
    all.uses_lens = all.uses_time = false;
    const PixelSequence some = sampler.pixel(7, 2, 2 * 640 + 7, false, false);
    for (std::uint32_t i = 0; i < 40; ++i) {
      const CameraSample a = all.sample(i), b = some.sample(i);
      ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << sampler_name(kind) << " sample " << i;
    }
  }
}

// A pixel's sequence, made in two steps for the tile loop (PixelSampler::sequence once, place per
// pixel), keys the per-sample random numbers as rng.h defines them — random_bits(seed, pixel,
// sample, dimension) — and is the same sequence wherever the shared part was made.
TEST(PixelSampler, SequencePlacedPerPixelKeysTheRandomNumbersOfRngH) {
  for (SamplerKind kind : {SamplerKind::Grid, SamplerKind::Stratified, SamplerKind::Random, SamplerKind::Sobol}) {
    for (std::uint64_t seed : {0ull, 1ull, 0x9e3779b97f4a7c15ull, ~0ull}) {
      PixelSampler sampler;
      sampler.kind = kind;
      sampler.side = 3;
      sampler.seed = seed;
      PixelSequence placed = sampler.sequence();
      for (const auto& [x, y] : {std::pair{0, 0}, std::pair{639, 0}, std::pair{5, 3}, std::pair{17, 479}}) {
        const std::uint64_t pixel = std::uint64_t(y) * 640 + std::uint64_t(x);
        PixelSampler::place(placed, x, y, pixel);
        const PixelSequence fresh = sampler.pixel(x, y, pixel);
        ASSERT_EQ(placed.stream, pixel_key(seed, pixel));
        SampleStream rng{placed.stream, 11};
        ASSERT_EQ(rng.next(), random_real(seed, pixel, 11, kDimIntegrator));
        for (std::uint32_t i = 0; i < 12; ++i) {
          const CameraSample a = placed.sample(i), b = fresh.sample(i);
          ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << sampler_name(kind) << " sample " << i;
        }
      }
    }
  }
}

constexpr int kSamples = 200000;
constexpr int kThetaBins = 10, kPhiBins = 20;
const double kAlpha = test::significance(0.01, 8);  // eight chi-square tests below

Vec2 uniform2(std::uint32_t i) { return {random_real(42, 7, i, 0), random_real(42, 7, i, 1)}; }

// Directions binned by (z, φ): equal steps of z over [z_min, 1] are equal solid angles, so
// a bin's probability is ∫ pdf dz dφ, integrated here numerically from the routine's own pdf.
test::ChiSquare direction_test(const std::function<Vec3(Vec2)>& warp, const std::function<Real(const Vec3&)>& pdf,
                               Real z_min) {
  std::vector<double> observed(kThetaBins * kPhiBins, 0), expected(kThetaBins * kPhiBins, 0);
  const Real dz = (1 - z_min) / kThetaBins, dphi = 2 * kPi / kPhiBins;
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 d = warp(uniform2(std::uint32_t(i)));
    EXPECT_NEAR(d.length(), 1, 1e-9);
    Real phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * kPi;
    const int zi = std::min(kThetaBins - 1, std::max(0, int((d.z - z_min) / dz)));
    const int pi = std::min(kPhiBins - 1, int(phi / dphi));
    observed[std::size_t(zi * kPhiBins + pi)] += 1;
  }
  constexpr int kSub = 16;  // midpoint rule per bin
  for (int zi = 0; zi < kThetaBins; ++zi)
    for (int pi = 0; pi < kPhiBins; ++pi) {
      double integral = 0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const Real z = z_min + (zi + (a + 0.5) / kSub) * dz, phi = (pi + (b + 0.5) / kSub) * dphi;
          const Real r = std::sqrt(std::fmax(Real(0), 1 - z * z));
          integral += pdf(Vec3(r * std::cos(phi), r * std::sin(phi), z));
        }
      expected[std::size_t(zi * kPhiBins + pi)] = integral * (dz / kSub) * (dphi / kSub) * kSamples;
    }
  return test::chi_square(observed, expected);
}

TEST(Warp, UniformHemisphereFollowsItsDensity) {
  const auto r = direction_test(square_to_uniform_hemisphere, [](const Vec3&) { return uniform_hemisphere_pdf(); }, 0);
  EXPECT_GT(r.p_value, kAlpha) << "chi² " << r.statistic << " dof " << r.dof;
}

TEST(Warp, CosineHemisphereFollowsItsDensity) {
  const auto r =
      direction_test(square_to_cosine_hemisphere, [](const Vec3& d) { return cosine_hemisphere_pdf(d.z); }, 0);
  EXPECT_GT(r.p_value, kAlpha) << "chi² " << r.statistic << " dof " << r.dof;
}

TEST(Warp, UniformSphereFollowsItsDensity) {
  const auto r = direction_test(square_to_uniform_sphere, [](const Vec3&) { return uniform_sphere_pdf(); }, -1);
  EXPECT_GT(r.p_value, kAlpha) << "chi² " << r.statistic << " dof " << r.dof;
}

TEST(Warp, ConeFollowsItsDensity) {
  for (const Real cos_max : {Real(0.3), Real(0.9), Real(0.999)}) {
    const auto r = direction_test([&](Vec2 u) { return square_to_uniform_cone(u, cos_max); },
                                  [&](const Vec3&) { return uniform_cone_pdf(cos_max); }, cos_max);
    EXPECT_GT(r.p_value, kAlpha) << "cos_max " << cos_max << ": chi² " << r.statistic << " dof " << r.dof;
  }
}

// The test has power: cosine-distributed directions are not uniform.
TEST(Warp, ChiSquareRejectsAWrongDensity) {
  const auto r = direction_test(square_to_cosine_hemisphere, [](const Vec3&) { return uniform_hemisphere_pdf(); }, 0);
  EXPECT_LT(r.p_value, 1e-6);
}

// The disk, binned by (r², φ): equal steps of r² are equal areas; the pdf is per unit area.
TEST(Warp, DiskFollowsItsDensity) {
  constexpr int kR = 10;
  std::vector<double> observed(kR * kPhiBins, 0), expected(kR * kPhiBins, 0);
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 p = square_to_disk(uniform2(std::uint32_t(i)));
    const Real r2 = p.x * p.x + p.y * p.y;
    ASSERT_LE(r2, 1 + 1e-12);
    Real phi = std::atan2(p.y, p.x);
    if (phi < 0) phi += 2 * kPi;
    observed[std::size_t(std::min(kR - 1, int(r2 * kR)) * kPhiBins + std::min(kPhiBins - 1, int(phi / (2 * kPi) * kPhiBins)))] += 1;
  }
  // Bin area = Δ(r²)/2 · Δφ.
  for (double& e : expected) e = disk_pdf() * (1.0 / kR) / 2 * (2 * kPi / kPhiBins) * kSamples;
  const auto r = test::chi_square(observed, expected);
  EXPECT_GT(r.p_value, kAlpha) << "chi² " << r.statistic << " dof " << r.dof;
}

// ---- pixel samplers ----

SamplingSettings settings(SamplerKind kind, int spp, std::uint64_t seed = 3) {
  SamplingSettings s;
  s.sampler = kind;
  s.spp = spp;
  s.seed = seed;
  return s;
}

TEST(PixelSampler, GridPutsOneSampleAtEachSubpixelCentre) {
  const PixelSampler ps = make_pixel_sampler(settings(SamplerKind::Grid, 16));
  for (std::uint64_t pixel : {0ull, 5ull, 99ull}) {
    std::set<std::pair<int, int>> seen;
    for (std::uint32_t i = 0; i < 16; ++i) {
      const CameraSample cs = ps.sample(2, 3, pixel, i);
      const Real fx = (cs.film_x - 2) * 4 - 0.5, fy = (cs.film_y - 3) * 4 - 0.5;
      EXPECT_NEAR(fx, std::round(fx), 1e-12);
      EXPECT_NEAR(fy, std::round(fy), 1e-12);
      seen.insert({int(std::round(fx)), int(std::round(fy))});
    }
    EXPECT_EQ(seen.size(), 16u);
  }
  // One sample: the lecture's ray through the pixel centre.
  const CameraSample c = make_pixel_sampler(settings(SamplerKind::Grid, 1)).sample(7, 9, 0, 0);
  EXPECT_EQ(c.film_x, 7.5);
  EXPECT_EQ(c.film_y, 9.5);
}

// One stratum (1 spp, and every pass of a progressive 1-spp render): the sample is the pixel's
// own random numbers, with no order to draw — pixel() skips the hashes and sample() the
// divisions; the values are those of the general formula (a stratum's corner 0 plus the jitter).
TEST(PixelSampler, OneStratumIsThePixelsOwnRandomNumbers) {
  for (SamplerKind kind : {SamplerKind::Grid, SamplerKind::Stratified}) {
    const PixelSampler ps = make_pixel_sampler(settings(kind, 1, 11));
    for (std::uint64_t pixel : {0ull, 17ull, 123456ull})
      for (std::uint32_t i : {0u, 1u, 2u, 7u, 1000u}) {
        const CameraSample cs = ps.sample(4, 6, pixel, i);
        const auto u = [&](std::uint32_t dim) { return random_real(11, pixel, i, dim); };
        const bool jitter = kind == SamplerKind::Stratified;
        EXPECT_EQ(cs.film_x, 4 + (jitter ? u(kDimPixel) : 0.5));
        EXPECT_EQ(cs.film_y, 6 + (jitter ? u(kDimPixel + 1) : 0.5));
        EXPECT_EQ(cs.lens.x, u(kDimLens));
        EXPECT_EQ(cs.lens.y, u(kDimLens + 1));
        EXPECT_EQ(cs.time, u(kDimTime));
      }
  }
}

// Stratified: each of the n×n film strata, lens strata and n² time strata holds exactly one of
// the first n² samples, and again one of the next n².
TEST(PixelSampler, StratifiedFillsEveryStratumOncePerRound) {
  constexpr int n = 5;
  const PixelSampler ps = make_pixel_sampler(settings(SamplerKind::Stratified, n * n));
  EXPECT_EQ(effective_spp(SamplerKind::Stratified, 24), 25);
  EXPECT_EQ(effective_spp(SamplerKind::Stratified, 10), 9);
  for (std::uint64_t pixel = 0; pixel < 50; ++pixel)
    for (std::uint32_t round = 0; round < 2; ++round) {
      std::set<int> film, lens, time;
      for (std::uint32_t i = round * n * n; i < (round + 1) * n * n; ++i) {
        const CameraSample cs = ps.sample(0, 0, pixel, i);
        film.insert(int(cs.film_x * n) + n * int(cs.film_y * n));
        lens.insert(int(cs.lens.x * n) + n * int(cs.lens.y * n));
        time.insert(int(cs.time * n * n));
      }
      ASSERT_EQ(film.size(), std::size_t(n * n)) << pixel;
      ASSERT_EQ(lens.size(), std::size_t(n * n)) << pixel;
      ASSERT_EQ(time.size(), std::size_t(n * n)) << pixel;
    }
}

// The O(1) Sobol dimensions against the textbook loop over the index's bits.
// reverse_bits against the bit-by-bit definition: bit k of x is bit 31 − k of the result.
TEST(PixelSampler, ReverseBitsMirrorsEveryBit) {
  std::uint32_t state = 12345;
  for (int n = 0; n < 100000; ++n) {
    state = state * 1664525u + 1013904223u;  // (any spread of values will do)
    const std::uint32_t x = n < 33 ? (n == 32 ? 0xffffffffu : 1u << n) : state ^ (state >> 13);
    std::uint32_t expected = 0;
    for (int k = 0; k < 32; ++k) expected |= ((x >> k) & 1u) << (31 - k);
    ASSERT_EQ(reverse_bits(x), expected) << x;
  }
  static_assert(reverse_bits(1u) == 0x80000000u && reverse_bits(0x12345678u) == 0x1e6a2c48u);
}

TEST(PixelSampler, SobolDimensionsMatchTheDirectionNumbers) {
  for (std::uint32_t index : {0u, 1u, 2u, 3u, 7u, 100u, 12345u, 0x80000000u, 0xdeadbeefu, 0xffffffffu}) {
    std::uint32_t d0 = 0, d1 = 0;
    std::uint32_t v0 = 0x80000000u, v1 = 0x80000000u;
    for (std::uint32_t i = index; i != 0; i >>= 1, v0 >>= 1, v1 ^= v1 >> 1) {
      if (i & 1u) {
        d0 ^= v0;
        d1 ^= v1;
      }
    }
    EXPECT_EQ(sobol_dim0(index), d0) << index;
    EXPECT_EQ(sobol_dim1(index), d1) << index;
  }
}

// Sobol: the first 2^m samples of a pixel form a (0, m, 2)-net in film and in lens: every
// elementary interval of area 2^-m holds exactly one; time takes one value per 1/2^m.
TEST(PixelSampler, SobolPrefixesAreZeroTwoNets) {
  const PixelSampler ps = make_pixel_sampler(settings(SamplerKind::Sobol, 64));
  for (std::uint64_t pixel = 0; pixel < 40; ++pixel)
    for (int m = 0; m <= 6; ++m) {
      const std::uint32_t count = 1u << m;
      for (int a = 0; a <= m; ++a) {
        const int b = m - a;
        std::set<std::pair<int, int>> film, lens;
        std::set<int> time;
        for (std::uint32_t i = 0; i < count; ++i) {
          const CameraSample cs = ps.sample(0, 0, pixel, i);
          film.insert({int(cs.film_x * (1 << a)), int(cs.film_y * (1 << b))});
          lens.insert({int(cs.lens.x * (1 << a)), int(cs.lens.y * (1 << b))});
          time.insert(int(cs.time * count));
        }
        ASSERT_EQ(film.size(), count) << "pixel " << pixel << " m " << m << " a " << a;
        ASSERT_EQ(lens.size(), count) << "pixel " << pixel << " m " << m << " a " << a;
        ASSERT_EQ(time.size(), count) << "pixel " << pixel << " m " << m;
      }
    }
}

// Over many pixels every sampler's film, lens and time values are uniform, and the film and lens
// values of one sample are independent (chi-square on the 4D product of 3×3 bins).
TEST(PixelSampler, SamplesAreUniformAndFilmIndependentOfLens) {
  for (const SamplerKind kind : {SamplerKind::Stratified, SamplerKind::Random, SamplerKind::Sobol}) {
    const PixelSampler ps = make_pixel_sampler(settings(kind, 16));
    std::vector<double> observed(81, 0), time_obs(16, 0);
    int total = 0;
    for (std::uint64_t pixel = 0; pixel < 4000; ++pixel)
      for (std::uint32_t i = 0; i < 16; ++i) {
        const CameraSample cs = ps.sample(0, 0, pixel, i);
        ASSERT_TRUE(cs.film_x >= 0 && cs.film_x < 1 && cs.film_y >= 0 && cs.film_y < 1);
        ASSERT_TRUE(cs.lens.x >= 0 && cs.lens.x < 1 && cs.lens.y >= 0 && cs.lens.y < 1 && cs.time >= 0 && cs.time < 1);
        const int bin = int(cs.film_x * 3) + 3 * int(cs.film_y * 3) + 9 * int(cs.lens.x * 3) + 27 * int(cs.lens.y * 3);
        observed[std::size_t(bin)] += 1;
        time_obs[std::size_t(cs.time * 16)] += 1;
        ++total;
      }
    const auto r = test::chi_square(observed, std::vector<double>(81, total / 81.0));
    EXPECT_GT(r.p_value, test::significance(0.01, 6)) << sampler_name(kind) << ": chi² " << r.statistic;
    // Time: stratified and Sobol are exact per pixel; random is checked statistically.
    const auto t = test::chi_square(time_obs, std::vector<double>(16, total / 16.0));
    EXPECT_GT(t.p_value, test::significance(0.01, 6)) << sampler_name(kind) << " time: chi² " << t.statistic;
  }
}

TEST(PixelSampler, SeedsChangeTheSamplesAndNamesRoundTrip) {
  const CameraSample a = make_pixel_sampler(settings(SamplerKind::Sobol, 4, 1)).sample(0, 0, 3, 2);
  const CameraSample b = make_pixel_sampler(settings(SamplerKind::Sobol, 4, 2)).sample(0, 0, 3, 2);
  EXPECT_NE(a.film_x, b.film_x);
  for (const SamplerKind k :
       {SamplerKind::Grid, SamplerKind::Stratified, SamplerKind::Random, SamplerKind::Sobol, SamplerKind::Adaptive})
    EXPECT_EQ(sampler_from_name(sampler_name(k)), k);
  EXPECT_FALSE(sampler_from_name("halton"));
}

// ---- filters ----

TEST(Filter, IntegralsMatchTheClosedFormsAndSupportIsHalfOpen) {
  for (const FilterKind kind : {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian, FilterKind::Mitchell})
    for (const Real radius : {Real(0.5), Real(1), Real(1.5), Real(2), Real(4)}) {
      const Filter f{kind, radius};
      constexpr int kSteps = 200000;
      double integral = 0;
      for (int i = 0; i < kSteps; ++i) integral += filter_1d(f, -radius + (i + 0.5) * 2 * radius / kSteps);
      integral *= 2 * radius / kSteps;
      EXPECT_NEAR(integral, filter_integral_1d(f), 1e-6 * radius) << filter_name(kind) << " r " << radius;
      EXPECT_EQ(filter_1d(f, radius), 0) << filter_name(kind);
      EXPECT_EQ(filter_1d(f, radius + 1e-9), 0);
      EXPECT_EQ(filter_1d(f, -radius - 1e-9), 0);
      EXPECT_GT(filter_1d(f, 0), 0);
      EXPECT_EQ(filter_1d(f, Real(0.3) * radius), filter_1d(f, Real(-0.3) * radius)) << "symmetric";
      EXPECT_EQ(filter_weight(f, 0.2, 0.1), filter_1d(f, 0.2) * filter_1d(f, 0.1));
    }
}

// The film's weights of a row of pixels (filter_weights_1d, the kind chosen once, the Gaussian's
// edge computed once) are filter_1d's, bit for bit, at every offset, inside the support and out.
TEST(Filter, RowWeightsAreFilter1dBitForBit) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Real> position(-2, 20);
  for (const FilterKind kind : {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian, FilterKind::Mitchell})
    for (const Real radius : {Real(0.5), Real(1), Real(1.5), Real(2.7), Real(4)}) {
      const Filter f{kind, radius};
      EXPECT_NEAR(filter_edge(f), kind == FilterKind::Gaussian ? std::exp(-Real(4.5)) : Real(0), 1e-15) << filter_name(kind);
      for (int trial = 0; trial < 2000; ++trial) {
        const Real c = trial == 0 ? Real(3) : trial == 1 ? Real(3.5) : position(rng);
        const int p0 = int(std::floor(c - Real(0.5) - radius)) - trial % 2, count = 2 * int(std::ceil(radius)) + 3;
        Real w[16];
        filter_weights_1d(f, filter_edge(f), c, p0, count, w);
        for (int i = 0; i < count; ++i) {
          const Real expected = filter_1d(f, c - (Real(p0 + i) + Real(0.5)));
          ASSERT_EQ(std::memcmp(&w[i], &expected, sizeof expected), 0) << filter_name(kind) << " r " << radius << " c " << c << " i " << i;
        }
      }
    }
}

// Box 0.5 gives every sample to exactly one pixel; tent 1 and Mitchell 2 are partitions of
// unity (their integer translates sum to 1), so a flat image stays flat.
TEST(Filter, PartitionsOfUnity) {
  const Filter box{FilterKind::Box, 0.5}, tent{FilterKind::Tent, 1}, mitchell{FilterKind::Mitchell, 2};
  for (Real x = -0.5; x < 0.5; x += 0.0137) {
    double b = 0, t = 0, m = 0;
    int owners = 0;
    for (int k = -4; k <= 4; ++k) {
      b += filter_1d(box, x + k);
      owners += filter_1d(box, x + k) > 0;
      t += filter_1d(tent, x + k);
      m += filter_1d(mitchell, x + k);
    }
    EXPECT_EQ(owners, 1) << x;
    EXPECT_NEAR(b, 1, 1e-12);
    EXPECT_NEAR(t, 1, 1e-12);
    EXPECT_NEAR(m, 1, 1e-12);
  }
  EXPECT_TRUE(filter_is_pixel_local(box));
  EXPECT_FALSE(filter_is_pixel_local(tent));
  EXPECT_LT(filter_1d(mitchell, 1.5), 0) << "Mitchell's negative lobe";
}

}  // namespace
}  // namespace strahl::sampling_test
