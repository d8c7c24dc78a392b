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
    film.add_pixel_samples(work, x, row, cs, L, count);
    work.taken[i] += std::uint32_t(count);
  }
  return true;
}

// Pixels of one row with one sample each (a 1-spp pass: the adaptive sampler's first, the
// viewer's), gathered into packets of up to 16 neighbours (render/packet_radiance.h).
class NeighbourPackets {
 public:
  NeighbourPackets(const SceneView& view, const FilmLayout& film, TileWork& work)
      : view_(view), film_(film), work_(work) {}

  // Pixel (x, row), entry i of the tile, takes its sample `index` of `sequence`; false when stopped.
  bool add(const PixelSequence& sequence, std::uint32_t index, int x, int row, std::size_t i, const StopToken& stop) {
    if (count_ > 0 && row != row_) {
      if (!flush(stop)) return false;
    }
    row_ = row;
    // (The same for every pixel of a render: one sampler, one camera.)
    sobol_ = (sequence.kind == SamplerKind::Sobol || sequence.kind == SamplerKind::Adaptive) && !sequence.uses_lens &&
             !sequence.uses_time;
    if (sobol_) {  // the film positions come in flush(), the lanes side by side
      s0_[count_] = sequence.h[0], s1_[count_] = sequence.h[1], s2_[count_] = sequence.h[2];
      px_[count_] = Real(sequence.x), py_[count_] = Real(sequence.y);
    } else {
      cs_[count_] = sequence.sample(index);
    }
    key_[count_] = sequence.stream;
    index_[count_] = index;
    x_[count_] = x;
    entry_[count_] = i;
    return ++count_ < kLanes || flush(stop);
  }

  // Traces the gathered samples; false (and nothing traced) when stopped.
  bool flush(const StopToken& stop) {
    if (count_ == 0) return true;
    if (stop.requested()) return false;
    if (sobol_) {
      for (int j = count_; j < kLanes; ++j)  // lanes nobody reads
        index_[j] = 0, s0_[j] = s1_[j] = s2_[j] = 0, px_[j] = py_[j] = 0;
      sobol_film_lanes<kLanes>(index_, s0_, s1_, s2_, px_, py_, cs_);
    }
    if (count_ > 8)
      packet_radiance_of<16>(view_, cs_, key_, index_, count_, L_, work_.counters);
    else
      packet_radiance_of<8>(view_, cs_, key_, index_, count_, L_, work_.counters);
    for (int j = 0; j < count_; ++j) {
      film_.add_sample(work_, x_[j], row_, cs_[j], L_[j]);
      ++work_.taken[entry_[j]];
    }
    count_ = 0;
    return true;
  }

 private:
  static constexpr int kLanes = 16;
  const SceneView& view_;
  const FilmLayout& film_;
  TileWork& work_;
  int count_ = 0, row_ = 0;
  CameraSample cs_[kLanes];
  std::uint64_t key_[kLanes];
  std::uint32_t index_[kLanes];
  bool sobol_ = false;  // Sobol film positions without lens and time: computed in flush()
  std::uint32_t s0_[kLanes], s1_[kLanes], s2_[kLanes];
  Real px_[kLanes], py_[kLanes];
  int x_[kLanes];
  std::size_t entry_[kLanes];
  Vec3 L_[kLanes];
};

}  // namespace

void render_tile(const SceneView& view, const PixelSampler& sampler, const FilmLayout& film, const StopToken& stop,
                 TileWork& work) {
  const TileRect& r = work.rect;
  const bool packets = packet_radiance_supported(view);
  NeighbourPackets neighbours(view, film, work);
  for (int row = r.row0; row < r.row1; ++row)
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t i = r.index(x, row);
      const std::uint32_t begin = work.first[i], end = begin + work.count[i];
      if (begin == end) continue;
      const PixelSequence sequence = pixel_sequence(view, sampler, x, row);
      if (packets && end - begin == 1) {
        if (!neighbours.add(sequence, begin, x, row, i, stop)) return;
        continue;
      }
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
  neighbours.flush(stop);
}

}  // namespace strahl
