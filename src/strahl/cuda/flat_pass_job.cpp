// The render job's side of a flat pass (cuda/flat_pass_job.h): tiles in, PassData, tiles out.

#include "strahl/cuda/flat_pass_job.h"

#include <algorithm>
#include <optional>
#include <vector>

namespace strahl {

namespace {

PassData flatten(const std::vector<TileWork>& works, const FilmParams& film) {
  PassData pass;
  std::size_t pixels = 0, fixed = 0;
  for (const TileWork& w : works) {
    pixels += w.rect.pixels();
    fixed += w.fixed.size();
  }
  pass.pixels.reserve(pixels);
  if (film.local) pass.local.reserve(pixels * 4);
  if (film.stats) pass.stats.reserve(pixels);
  pass.fixed.assign(fixed, 0);
  pass.taken.assign(pixels, 0);
  pass.tiles.reserve(works.size());
  std::uint64_t offset = 0;
  for (std::size_t t = 0; t < works.size(); ++t) {
    const TileWork& w = works[t];
    const TileRect& r = w.rect;
    for (int row = r.row0; row < r.row1; ++row)
      for (int x = r.x0; x < r.x1; ++x) {
        const std::size_t i = r.index(x, row);
        pass.pixels.push_back({x, row, w.first[i], w.count[i], std::uint32_t(t)});
      }
    if (film.local) pass.local.insert(pass.local.end(), w.local.begin(), w.local.end());
    if (film.stats) pass.stats.insert(pass.stats.end(), w.stats.begin(), w.stats.end());
    pass.tiles.push_back({w.bx0, w.brow0, w.bw, w.bh, offset});
    offset += w.fixed.size();
  }
  return pass;
}

void unflatten(const PassData& pass, const FilmParams& film, std::vector<TileWork>& works) {
  std::size_t p = 0;
  for (std::size_t t = 0; t < works.size(); ++t) {
    TileWork& w = works[t];
    const std::size_t n = w.rect.pixels();
    std::copy(pass.taken.begin() + std::ptrdiff_t(p), pass.taken.begin() + std::ptrdiff_t(p + n), w.taken.begin());
    if (film.local)
      std::copy(pass.local.begin() + std::ptrdiff_t(p * 4), pass.local.begin() + std::ptrdiff_t((p + n) * 4),
                w.local.begin());
    if (film.stats)
      std::copy(pass.stats.begin() + std::ptrdiff_t(p), pass.stats.begin() + std::ptrdiff_t(p + n), w.stats.begin());
    const std::size_t off = pass.tiles[t].fixed_offset;
    std::copy(pass.fixed.begin() + std::ptrdiff_t(off), pass.fixed.begin() + std::ptrdiff_t(off + w.fixed.size()),
              w.fixed.begin());
    p += n;
  }
}

}  // namespace

void render_flat_pass(RenderJob& job, const FlatPassRun& run) {
  std::vector<TileWork> works;
  while (std::optional<TileWork> w = job.next_tile()) works.push_back(std::move(*w));
  if (works.empty()) return;
  const FilmParams film = job.film_layout().params();
  PassData pass = flatten(works, film);
  RayCounters counters;
  if (!run(film, pass, counters)) {  // every tile back unchanged (no samples taken), and the job stops
    job.cancel();
    for (TileWork& w : works) job.deliver(w);
    return;
  }
  unflatten(pass, film, works);
  works[0].counters = counters;  // the job sums the tiles' counters
  for (TileWork& w : works) job.deliver(w);
}

PassArgs host_pass_args(const SceneView& view, const PixelSampler& sampler, const FilmParams& film, PassData& pass,
                        const volatile int* stop) {
  PassArgs a;
  a.view = view;
  a.sampler = sampler;
  a.film = film;
  a.pixels = pass.pixels.data();
  a.local = pass.local.data();
  a.stats = pass.stats.data();
  a.taken = pass.taken.data();
  a.tiles = pass.tiles.data();
  a.fixed = pass.fixed.data();
  a.n = std::uint32_t(pass.pixels.size());
  a.stop = stop;
  return a;
}

}  // namespace strahl
