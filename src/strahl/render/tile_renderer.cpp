#include "strahl/render/tile_renderer.h"

#include "strahl/render/pixel.h"

namespace strahl {

void render_tile(const SceneView& view, const PixelSampler& sampler, const FilmLayout& film, const StopToken& stop,
                 TileWork& work) {
  const TileRect& r = work.rect;
  for (int row = r.row0; row < r.row1; ++row)
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t i = r.index(x, row);
      const std::uint32_t begin = work.first[i], end = begin + work.count[i];
      if (begin == end) continue;
      const PixelSequence sequence = pixel_sequence(view, sampler, x, row);
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
