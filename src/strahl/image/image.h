#pragma once
// A linear-RGB float image, row 0 at the top.

#include <cstddef>
#include <vector>

#include "strahl/util/zeroed_array.h"

namespace strahl {

struct Rgb {
  float r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

class Image {
 public:
  Image() = default;
  Image(int width, int height) : width_(width), height_(height), pixels_(std::size_t(width) * std::size_t(height)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb& at(int x, int row) { return pixels_[std::size_t(row) * width_ + x]; }
  const Rgb& at(int x, int row) const { return pixels_[std::size_t(row) * width_ + x]; }
  const ZeroedArray<Rgb>& pixels() const { return pixels_; }
  friend bool operator==(const Image&, const Image&) = default;

 private:
  int width_ = 0, height_ = 0;
  ZeroedArray<Rgb> pixels_;
};

}  // namespace strahl
