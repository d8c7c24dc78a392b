#include "strahl/render/tile_renderer.h"

#include <algorithm>
#include <bit>

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
  UninitializedLanes<CameraSample, N> samples;  // (each packet's lanes are written before they are read)
  UninitializedLanes<Vec3, N> radiance;
  CameraSample* const cs = samples.at;
  Vec3* const L = radiance.at;
  for (std::uint32_t k = begin; k < end; k += N) {
    if (stop.requested()) return false;
    const int count = end - k < N ? int(end - k) : N;
    packet_radiance<N>(view, sequence, k, count, cs, L, work.counters);
    film.add_pixel_samples(work, x, row, cs, L, count);
    work.taken[i] += std::uint32_t(count);
  }
  return true;
}

// Samples of pixels with fewer than 16 to take (the adaptive sampler's passes of 1, 2, 4, 8 per
// pixel, the viewer's 1-spp frames, a 3×3 grid), gathered across the tile into packets of up to
// 16 lanes (render/packet_radiance.h): a pixel's samples lie in consecutive lanes in sample order
// (or run on into the next packet), and each packet's samples reach the film in lane order, so
// every pixel's sums take the same additions in the same order as sample by sample.
class SamplePackets {
 public:
  // `shared`: what the sequences of the tile's pixels share (shared_sequence()).
  SamplePackets(const SceneView& view, const FilmLayout& film, TileWork& work, const PixelSequence& shared)
      : view_(view),
        film_(film),
        work_(work),
        sobol_(shared.kind == SamplerKind::Sobol || shared.kind == SamplerKind::Adaptive),
        strata_(shared.strata_lanes()),
        lens_(shared.uses_lens),
        time_(shared.uses_time),
        stratified_(shared.kind == SamplerKind::Stratified),
        side_(shared.side),
        side_shift_(shared.side_shift) {}

  // Pixel (x, row), entry i of the tile, takes samples first … first + count − 1 of `sequence`;
  // false when stopped.
  bool add(const PixelSequence& sequence, std::uint32_t first, std::uint32_t count, int x, int row, std::size_t i,
           const StopToken& stop) {
    for (std::uint32_t index = first; index < first + count; ++index) {
      if (sobol_) {  // the film positions come in flush(), the lanes side by side
        s0_[count_] = sequence.h[0], s1_[count_] = sequence.h[1], s2_[count_] = sequence.h[2];
        for (int k = 0; k < 6; ++k) scramble_[k][count_] = sequence.h[3 + k];  // the lens's and the shutter's
        px_[count_] = Real(sequence.x), py_[count_] = Real(sequence.y);
      } else if (strata_) {  // so do these, the film's strata order in s0_, the lens's in s1_, the shutter's in s2_
        s0_[count_] = sequence.strata_order(index);
        if (lens_) s1_[count_] = sequence.strata_order(index, 1);
        if (time_) s2_[count_] = sequence.strata_order(index, 2);
        px_[count_] = Real(sequence.x), py_[count_] = Real(sequence.y);
      } else {
        cs_[count_] = sequence.sample(index);
      }
      key_[count_] = sequence.stream;
      index_[count_] = index;
      x_[count_] = x;
      row_[count_] = row;
      entry_[count_] = i;
      if (++count_ == kLanes && !flush(stop)) return false;
    }
    return true;
  }

  // Traces the gathered samples; false (and nothing traced) when stopped.
  bool flush(const StopToken& stop) {
    if (count_ == 0) return true;
    if (stop.requested()) return false;
    if (sobol_) {
      for (int j = count_; j < kLanes; ++j)  // lanes nobody reads
        index_[j] = 0, s0_[j] = s1_[j] = s2_[j] = 0, px_[j] = py_[j] = 0;
      for (int k = 0; k < 6; ++k)
        for (int j = count_; j < kLanes; ++j) scramble_[k][j] = 0;
      sobol_film_lanes<kLanes>(index_, s0_, s1_, s2_, px_, py_, cs_, film_lanes_);
      if (lens_ || time_) sobol_lens_time_lanes<kLanes>(lens_, time_, index_, scramble_, cs_, film_lanes_);
      film_lanes_.pad(count_);
    } else if (strata_) {
      for (int j = count_; j < kLanes; ++j)  // lanes nobody reads
        index_[j] = 0, s0_[j] = s1_[j] = s2_[j] = 0, key_[j] = 0, px_[j] = py_[j] = 0;
      strata_film_lanes<kLanes>(stratified_, side_, side_shift_, index_, s0_, key_, px_, py_, cs_, film_lanes_);
      if (lens_ || time_)
        strata_lens_time_lanes<kLanes>(lens_, time_, side_, side_shift_, index_, s1_, s2_, key_, cs_, film_lanes_);
      film_lanes_.pad(count_);
    } else {
      film_lanes_.set(cs_, count_);
    }
    if (count_ > 8)
      packet_radiance_of<16>(view_, cs_, film_lanes_, key_, index_, count_, L_, work_.counters);
    else
      packet_radiance_of<8>(view_, cs_, film_lanes_, key_, index_, count_, L_, work_.counters);
    // Each pixel's run of lanes together (its sums in registers between them).
    for (int j = 0; j < count_;) {
      int run = 1;
      while (j + run < count_ && entry_[j + run] == entry_[j]) ++run;
      film_.add_pixel_samples(work_, x_[j], row_[j], &cs_[j], &L_[j], run);
      work_.taken[entry_[j]] += std::uint32_t(run);
      j += run;
    }
    count_ = 0;
    return true;
  }

 private:
  static constexpr int kLanes = 16;
  const SceneView& view_;
  const FilmLayout& film_;
  TileWork& work_;
  int count_ = 0;
  CameraSample cs_[kLanes];
  FilmLanes<kLanes> film_lanes_;  // cs_'s film positions and times, lane by lane
  std::uint64_t key_[kLanes];
  std::uint32_t index_[kLanes];
  const bool sobol_;  // Sobol samples (film, lens, time): computed in flush()
  const bool strata_;  // grid or stratified samples: so are these, lens and time too
  const bool lens_, time_;  // the camera uses the lens, the shutter
  const bool stratified_;
  const std::uint32_t side_;
  const int side_shift_;
  std::uint32_t s0_[kLanes], s1_[kLanes], s2_[kLanes];
  std::uint32_t scramble_[6][kLanes];  // sobol: the lens's and the shutter's pairs' scrambles (PixelSequence::h[3 … 8])
  Real px_[kLanes], py_[kLanes];
  int x_[kLanes], row_[kLanes];
  std::size_t entry_[kLanes];
  Vec3 L_[kLanes];
};

}  // namespace

void render_tile(const SceneView& view, const PixelSampler& sampler, const FilmLayout& film, const StopToken& stop,
                 TileWork& work) {
  const TileRect& r = work.rect;
  const bool packets = packet_radiance_supported(view);
  PixelSequence sequence = shared_sequence(view, sampler);  // each pixel's own part set below
  SamplePackets gathered(view, film, work, sequence);
  const std::size_t tw = std::size_t(r.width());
  const std::uint32_t* const firsts = work.first.data();
  const std::uint32_t* const counts = work.count.data();
  for (int row = r.row0; row < r.row1; ++row) {
    const std::size_t row_entry = r.index(r.x0, row);
    // The row's pixels with samples to take (few of a sparse adaptive pass's), 64 at a time.
    for (std::size_t k0 = 0; k0 < tw; k0 += 64) {
      for (std::uint64_t bits = counted_bits(&counts[row_entry + k0], std::min<std::size_t>(64, tw - k0)); bits != 0;
           bits &= bits - 1) {
        const std::size_t k = k0 + std::size_t(std::countr_zero(bits));
        const std::size_t i = row_entry + k;
        const int x = r.x0 + int(k);
        std::uint32_t begin = firsts[i];
        const std::uint32_t end = begin + counts[i];
        place_sequence(view, sequence, x, row);
        if (packets) {
          // Whole packets of 16 of the pixel's own, the rest gathered with other pixels' samples.
          const std::uint32_t whole = (end - begin) / 16 * 16;
          if (whole > 0 &&
              !render_samples_packed<16>(view, sequence, film, stop, work, x, row, i, begin, begin + whole))
            return;
          begin += whole;
          if (begin < end && !gathered.add(sequence, begin, end - begin, x, row, i, stop)) return;
          continue;
        }
        for (std::uint32_t n = begin; n < end; ++n) {
          if (stop.requested()) return;
          CameraSample cs;
          const Vec3 L = pixel_sample(view, sequence, n, cs, work.counters);
          film.add_sample(work, x, row, cs, L);
          ++work.taken[i];
        }
      }
    }
  }
  gathered.flush(stop);
}

}  // namespace strahl
