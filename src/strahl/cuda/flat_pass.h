#pragma once
// A pass flattened for the GPU (docs/gpu.md): every tile the job handed out, as per-pixel arrays
// that one thread per pixel reads and writes, and what one such thread does. Plain C++ and
// STRAHL_HOST_DEVICE functions: the CUDA kernel (device.cu) runs render_flat_pixel() for its pixel,
// and the tests run the same function on the host over every pixel of a pass
// (tests/flat_pass_test.cpp), so all of the back end but the CUDA calls is checked on machines
// without a GPU.
//
// Pixel i belongs to tile pixels[i].tile, takes samples first … first + count − 1 and carries its
// film sums in and out (local: four doubles; stats: PixelStats). Wide filters' contributions go
// to each tile's own fixed-point buffer (the TileWork layout), the tiles' buffers one after the
// other.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "strahl/render/film_sample.h"
#include "strahl/render/pixel.h"
#include "strahl/render/ray_counters.h"
#include "strahl/render/scene_view.h"
#include "strahl/render/tile.h"
#include "strahl/sampling/pixel_sampler.h"

namespace strahl {

struct PassPixel {
  std::int32_t x = 0, row = 0;
  std::uint32_t first = 0, count = 0, tile = 0;
};

struct PassTile {
  std::int32_t bx0 = 0, brow0 = 0, bw = 0, bh = 0;
  std::uint64_t fixed_offset = 0;  // into PassData::fixed, in int64 units
};

struct PassData {
  std::vector<PassPixel> pixels;
  std::vector<double> local;         // 4 per pixel (pixel-local filters), else empty
  std::vector<PixelStats> stats;     // 1 per pixel when kept, else empty
  std::vector<std::uint32_t> taken;  // out: samples taken per pixel
  std::vector<PassTile> tiles;
  std::vector<std::int64_t> fixed;   // wide filters: every tile's buffer, zero in, sums out
};

// What every thread of a pass reads: the scene (device pointers on the GPU), the sampler, the
// film's parameters and PassData's arrays (device copies on the GPU, the vectors' data on the
// host), n pixels; `stop` is read before each sample.
struct PassArgs {
  SceneView view;
  PixelSampler sampler;
  FilmParams film;
  const PassPixel* pixels = nullptr;
  double* local = nullptr;
  PixelStats* stats = nullptr;
  std::uint32_t* taken = nullptr;
  const PassTile* tiles = nullptr;
  std::int64_t* fixed = nullptr;
  std::uint32_t n = 0;
  const volatile int* stop = nullptr;
};

// A pass's ray counters as the launch sums them: each thread's own, then per warp, then into
// kPassCounters device counters with atomic adds.
inline constexpr int kPassCounters = 6;
STRAHL_HOST_DEVICE inline void counter_array(const RayCounters& c, unsigned long long (&v)[kPassCounters]) {
  v[0] = c.camera;
  v[1] = c.shadow;
  v[2] = c.reflection;
  v[3] = c.refraction;
  v[4] = c.invalid_samples;
  v[5] = c.cut;
}
inline void add_counter_array(RayCounters& c, const unsigned long long (&v)[kPassCounters]) {
  RayCounters d;
  d.camera = v[0];
  d.shadow = v[1];
  d.reflection = v[2];
  d.refraction = v[3];
  d.invalid_samples = v[4];
  d.cut = v[5];
  c += d;
}

// Pixel i of the pass (i < a.n): its samples in sample order, continuing the pixel's sums, so a
// pixel-local filter's sums are the same additions as on the CPU; a wide filter's contributions
// through add(q, v) (an atomic add on the GPU: integer additions commute). Stops between two
// samples once *a.stop is set; a.taken[i] says how many it took.
template <class Add>
STRAHL_HOST_DEVICE inline void render_flat_pixel(const PassArgs& a, std::uint32_t i, RayCounters& c, Add&& add) {
  const PassPixel p = a.pixels[i];
  std::uint32_t taken = 0;
  if (p.count > 0) {
    const PixelSequence sequence = pixel_sequence(a.view, a.sampler, p.x, p.row);
    double sums[4] = {0, 0, 0, 0};
    if (a.film.local)
      for (int k = 0; k < 4; ++k) sums[k] = a.local[std::size_t(i) * 4 + std::size_t(k)];
    PixelStats st;
    if (a.film.stats) st = a.stats[i];
    const PassTile tile = a.tiles[p.tile];
    for (std::uint32_t k = p.first; k < p.first + p.count; ++k) {
      if (*a.stop) break;  // stop between two samples
      CameraSample cs;
      const Vec3 L = pixel_sample(a.view, sequence, k, cs, c);
      if (a.film.stats) film_add_stats(st, L);
      if (a.film.local)
        film_add_local(sums, L);
      else
        film_add_wide(a.film, p.x, p.row, cs, L, a.fixed + tile.fixed_offset, tile.bx0, tile.brow0, tile.bw, add);
      ++taken;
    }
    if (a.film.local)
      for (int k = 0; k < 4; ++k) a.local[std::size_t(i) * 4 + std::size_t(k)] = sums[k];
    if (a.film.stats) a.stats[i] = st;
  }
  a.taken[i] = taken;
}

}  // namespace strahl
