#include "strahl/render/tile_renderer.h"

#include "strahl/render/packet_radiance.h"
#include "strahl/render/pixel.h"

namespace strahl {

namespace {

// A pixel's samples begin … end − 1 in packets of N (render/packet_radiance.h), in sample order.
// False when stopped.
template <int N>
bool render_samples_packed(const SceneView& view, const PixelSequence& sequence, const FilmLayout& film,
                           const StopToken& stop, TileWork& work, int x, int row, std::size_t i, std::uint32_t begin,
                           std::uint32_t end) {
  CameraSample cs[N];
  Vec3 L[N];
  for (std::uint32_t k = begin; k < end; k += N) {
    if (stop.requested()) return false;
    const int count = end - k < N ? int(end - k) : N;
    packet_radiance<N>(view, sequence, k, count, cs, L, work.counters);
    for (int j = 0; j < count; ++j) {
      film.add_sample(work, x, row, cs[j], L[j]);
      ++work.taken[i];
    }
  }
  return true;
}

}  // namespace

void render_tile(const SceneView& view, const PixelSampler& sampler, const FilmLayout& film, const StopToken& stop,
                 TileWork& work) {
  const TileRect& r = work.rect;
  const bool packets = packet_radiance_supported(view);
  for (int row = r.row0; row < r.row1; ++row)
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t i = r.index(x, row);
      const std::uint32_t begin = work.first[i], end = begin + work.count[i];
      if (begin == end) continue;
      const PixelSequence sequence = pixel_sequence(view, sampler, x, row);
      if (packets && end - begin > 1) {
        const bool done = end - begin >= 16 ? render_samples_packed<16>(view, sequence, film, stop, work, x, row, i, begin, end)
                                            : render_samples_packed<8>(view, sequence, film, stop, work, x, row, i, begin, end);
        if (!done) return;
        continue;
      }
      for (std::uint32_t k = begin; k < end; ++k) {
        if (stop.requested()) return;
        CameraSample cs;
        const Vec3 L = pixel_sample(view, sequence, k, cs, work.counters);
        film.add_sample(work, x, row, cs, L);
        ++work.taken[i];
      }
    }
}

}  // namespace strahl
