#pragma once
// strahl's own PNG encoder (8-bit samples; built where zlib is found, STRAHL_HAVE_ZLIB): the rows
// are filtered in parallel (one filter for all, or per row the one of least sum of absolute
// differences: libpng's and stb's heuristic), then deflated in parallel in bands of rows, as pigz
// does: each band a raw deflate stream primed with the bytes before it (deflate's 32 KiB window;
// one byte for run-length matches) and ended by a sync flush (the last by Z_FINISH), their
// concatenation one zlib stream whose Adler-32 is joined from the bands' (adler32_combine). Each
// band is its own IDAT chunk.

#include <cstddef>
#include <functional>

namespace strahl {

// The defaults, measured on 1920×1080 renders (lecture, lecture-whitted, the bunny; two cores):
// the Up filter on every row and zlib's run-length strategy encode in ~10–12 ms, 17–19 % smaller
// than stb_image_write at level 4 (70–90 ms even compiled -O3 -march=native); choosing the filter
// per row saves 1–6 % more for ~6 ms more; zlib's default strategy at levels 1–3 is as fast at
// level 1 but 5–10 % larger (docs/benchmark.md, "Writing the PNG").
struct PngEncoding {
  int filter = 2;                       // the PNG filter of every row, 0 (None) … 4 (Paeth); -1: chosen per row
  bool run_length = true;               // zlib's Z_RLE strategy (matches at distance one only), else Z_DEFAULT_STRATEGY
  int level = 1;                        // zlib's compression level, 1 (fastest) … 9 (smallest)
  std::size_t band_bytes = 256 * 1024;  // filtered bytes per deflate band (rounded to whole rows)
};

// Encodes `height` rows of `width` × `channels` samples (1 grey, 2 grey + alpha, 3 RGB,
// 4 RGBA; 8 bits each, rows `width × channels` bytes apart, top row first) as a PNG file, handing
// its bytes to `sink` in order. Returns false, having handed over nothing, when zlib fails (out
// of memory); throws std::bad_alloc when a buffer cannot be had.
bool encode_png(const unsigned char* pixels, int width, int height, int channels,
                const std::function<void(const void* data, std::size_t size)>& sink, const PngEncoding& encoding = {});

}  // namespace strahl
