#include "strahl/image/png_writer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "strahl/util/zeroed_array.h"

namespace strahl {

namespace {

constexpr std::size_t kWindow = 32768;  // deflate's window: how far back a match may reach

using Bytes = std::vector<unsigned char>;

void put32(unsigned char* p, std::uint32_t v) {
  p[0] = static_cast<unsigned char>(v >> 24);
  p[1] = static_cast<unsigned char>(v >> 16);
  p[2] = static_cast<unsigned char>(v >> 8);
  p[3] = static_cast<unsigned char>(v);
}

int paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// Row `row` under filter `type` (PNG 1.2, section 6), without the filter byte; `above` is the
// row before, all zeros for the first.
template <int Bpp>
void filter_row(int type, const unsigned char* row, const unsigned char* above, std::size_t n, unsigned char* out) {
  switch (type) {
    case 0:
      std::memcpy(out, row, n);
      return;
    case 1:
      for (std::size_t i = 0; i < Bpp; ++i) out[i] = row[i];
      for (std::size_t i = Bpp; i < n; ++i) out[i] = static_cast<unsigned char>(row[i] - row[i - Bpp]);
      return;
    case 2:
      for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<unsigned char>(row[i] - above[i]);
      return;
    case 3:
      for (std::size_t i = 0; i < Bpp; ++i) out[i] = static_cast<unsigned char>(row[i] - (above[i] >> 1));
      for (std::size_t i = Bpp; i < n; ++i)
        out[i] = static_cast<unsigned char>(row[i] - ((row[i - Bpp] + above[i]) >> 1));
      return;
    default:
      for (std::size_t i = 0; i < Bpp; ++i) out[i] = static_cast<unsigned char>(row[i] - above[i]);  // Paeth(0, b, 0) = b
      for (std::size_t i = Bpp; i < n; ++i)
        out[i] = static_cast<unsigned char>(row[i] - paeth(row[i - Bpp], above[i], above[i - Bpp]));
      return;
  }
}

// The heuristic's cost: the filtered bytes read as signed, summed in magnitude.
unsigned long cost(const unsigned char* p, std::size_t n) {
  unsigned long sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += static_cast<unsigned long>(std::abs(static_cast<int>(static_cast<signed char>(p[i]))));
  return sum;
}

// Filters rows [begin, end) into `out` (stride n + 1: the filter byte, then the row).
template <int Bpp>
void filter_rows(const unsigned char* pixels, std::size_t n, int begin, int end, int fixed, unsigned char* out) {
  const Bytes zeros(fixed < 0 || begin == 0 ? n : 0, 0);
  Bytes trial(fixed < 0 ? 5 * n : 0);
  for (int y = begin; y < end; ++y) {
    const unsigned char* row = pixels + std::size_t(y) * n;
    const unsigned char* above = y > 0 ? row - n : zeros.data();
    unsigned char* dst = out + std::size_t(y) * (n + 1);
    int type = fixed;
    if (fixed < 0) {
      unsigned long best = ~0ul;
      for (int t = 0; t < 5; ++t) {
        filter_row<Bpp>(t, row, above, n, &trial[std::size_t(t) * n]);
        const unsigned long c = cost(&trial[std::size_t(t) * n], n);
        if (c < best) best = c, type = t;
      }
      std::memcpy(dst + 1, &trial[std::size_t(type) * n], n);
    } else {
      filter_row<Bpp>(type, row, above, n, dst + 1);
    }
    dst[0] = static_cast<unsigned char>(type);
  }
}

void filter_all(const unsigned char* pixels, std::size_t n, int height, int channels, int fixed, unsigned char* out) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& r) {
    switch (channels) {
      case 1: return filter_rows<1>(pixels, n, r.begin(), r.end(), fixed, out);
      case 2: return filter_rows<2>(pixels, n, r.begin(), r.end(), fixed, out);
      case 3: return filter_rows<3>(pixels, n, r.begin(), r.end(), fixed, out);
      default: return filter_rows<4>(pixels, n, r.begin(), r.end(), fixed, out);
    }
  });
}

// One band of the zlib stream: its IDAT chunk's data (the zlib header before the first band),
// the band's Adler-32 and the chunk's CRC so far (over type and data).
struct Band {
  Bytes data;
  uLong adler = 0;
  uLong crc = 0;
  std::size_t raw_size = 0;
};

// Deflates filtered[begin, end) as one raw deflate stream that continues the one before it:
// primed with the bytes before `begin`, ended by a sync flush (by Z_FINISH if it is the last).
bool deflate_band(const unsigned char* filtered, std::size_t begin, std::size_t end, bool last, bool first,
                  const PngEncoding& encoding, Band& band) {
  z_stream z{};
  if (deflateInit2(&z, encoding.level, Z_DEFLATED, -15, 8, encoding.run_length ? Z_RLE : Z_DEFAULT_STRATEGY) != Z_OK) return false;
  bool ok = true;
  if (begin > 0) {
    // Run-length matches reach back one byte only: a longer window would be hashed for nothing.
    const std::size_t dict = std::min(begin, encoding.run_length ? std::size_t(1) : kWindow);
    ok = deflateSetDictionary(&z, filtered + begin - dict, uInt(dict)) == Z_OK;
  }
  const std::size_t header = first ? 2 : 0;
  // deflateBound covers a stream's end, not the sync flush's empty stored block: room for it too.
  band.data.resize(header + deflateBound(&z, uLong(end - begin)) + 16);
  if (first) {
    // CMF: deflate with a 32 KiB window; FLG: the level's class (RFC 1950), checked modulo 31.
    const unsigned cmf = 0x78, flevel = encoding.level <= 1 ? 0 : encoding.level <= 5 ? 1 : encoding.level == 6 ? 2 : 3;
    unsigned flg = flevel << 6;
    flg += 31 - (cmf * 256 + flg) % 31;
    band.data[0] = static_cast<unsigned char>(cmf);
    band.data[1] = static_cast<unsigned char>(flg);
  }
  z.next_in = const_cast<Bytef*>(filtered + begin);
  z.avail_in = uInt(end - begin);
  std::size_t produced = header;
  const int flush = last ? Z_FINISH : Z_SYNC_FLUSH;
  while (ok) {
    if (produced == band.data.size()) band.data.resize(band.data.size() * 2);
    z.next_out = band.data.data() + produced;
    z.avail_out = uInt(band.data.size() - produced);
    const int status = deflate(&z, flush);
    produced = band.data.size() - z.avail_out;
    if (status == Z_STREAM_END || (!last && status == Z_OK && z.avail_out > 0 && z.avail_in == 0)) break;
    ok = status == Z_OK || (status == Z_BUF_ERROR && z.avail_out == 0);  // else: no progress possible
  }
  deflateEnd(&z);
  if (!ok) return false;
  band.data.resize(produced);
  band.raw_size = end - begin;
  band.adler = adler32(adler32(0, nullptr, 0), filtered + begin, uInt(end - begin));
  band.crc = crc32(crc32(0, reinterpret_cast<const Bytef*>("IDAT"), 4), band.data.data(), uInt(band.data.size()));
  return true;
}

}  // namespace

bool encode_png(const unsigned char* pixels, int width, int height, int channels,
                const std::function<void(const void* data, std::size_t size)>& sink, const PngEncoding& encoding) {
  const std::size_t n = std::size_t(width) * std::size_t(channels), stride = n + 1;
  ZeroedArray<unsigned char> filtered(stride * std::size_t(height));  // fresh pages (util/zeroed_array.h)
  filter_all(pixels, n, height, channels, encoding.filter, filtered.data());

  const int rows_per_band = int(std::max<std::size_t>(1, encoding.band_bytes / stride));
  const int bands = (height + rows_per_band - 1) / rows_per_band;
  std::vector<Band> band(std::size_t(bands), Band{});
  std::atomic<bool> ok{true};
  tbb::parallel_for(0, bands, [&](int b) {
    const std::size_t begin = std::size_t(b) * std::size_t(rows_per_band) * stride;
    const std::size_t end = std::min(filtered.size(), begin + std::size_t(rows_per_band) * stride);
    if (!deflate_band(filtered.data(), begin, end, b == bands - 1, b == 0, encoding, band[std::size_t(b)])) ok = false;
  });
  if (!ok) return false;

  // The stream's Adler-32 (RFC 1950: big-endian, after the last deflate block) ends the last band.
  uLong adler = band[0].adler;
  for (std::size_t b = 1; b < band.size(); ++b) adler = adler32_combine(adler, band[b].adler, z_off_t(band[b].raw_size));
  unsigned char tail[4];
  put32(tail, std::uint32_t(adler));
  band.back().data.insert(band.back().data.end(), tail, tail + 4);
  band.back().crc = crc32(band.back().crc, tail, 4);

  const auto chunk = [&](const char* type, const unsigned char* data, std::size_t size, uLong crc) {
    unsigned char head[8];
    put32(head, std::uint32_t(size));
    std::memcpy(head + 4, type, 4);
    sink(head, 8);
    if (size > 0) sink(data, size);
    unsigned char end[4];
    put32(end, std::uint32_t(crc));
    sink(end, 4);
  };
  const auto crc_of = [](const char* type, const unsigned char* data, std::size_t size) {
    return crc32(crc32(0, reinterpret_cast<const Bytef*>(type), 4), data, uInt(size));
  };
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  sink(kSignature, 8);
  // IHDR: size, 8 bits per sample, the colour type (0 grey, 4 grey + alpha, 2 RGB, 6 RGBA),
  // deflate, adaptive filtering, no interlace.
  static constexpr unsigned char kColourType[5] = {0, 0, 4, 2, 6};
  unsigned char ihdr[13];
  put32(ihdr, std::uint32_t(width));
  put32(ihdr + 4, std::uint32_t(height));
  ihdr[8] = 8;
  ihdr[9] = kColourType[channels];
  ihdr[10] = ihdr[11] = ihdr[12] = 0;
  chunk("IHDR", ihdr, 13, crc_of("IHDR", ihdr, 13));
  for (const Band& b : band) chunk("IDAT", b.data.data(), b.data.size(), b.crc);
  chunk("IEND", ihdr, 0, crc_of("IEND", ihdr, 0));  // (crc32 of a null pointer is its initial value)
  return true;
}

}  // namespace strahl
