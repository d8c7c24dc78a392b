#pragma once
// Text for the HUD and the help overlay: a built-in 5×7 pixel font (printable ASCII, drawn
// for strahl) rendered into an RGBA canvas, which the window then lays over the image.

#include <cstdint>
#include <string>
#include <vector>

namespace strahl::view {

struct Rgba {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

// Straight (not premultiplied) RGBA bytes, row 0 at the top; starts transparent.
class Canvas {
 public:
  Canvas(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  Rgba at(int x, int y) const;

  void fill(int x, int y, int w, int h, Rgba colour);  // clipped to the canvas
  // One line of text (no wrapping), glyphs scaled by `scale`, its top-left corner at (x, y).
  // Characters outside printable ASCII are drawn as '?'.
  void text(int x, int y, const std::string& line, Rgba colour, int scale = 1);

 private:
  int width_, height_;
  std::vector<std::uint8_t> bytes_;
};

// A glyph cell, spacing included: 6 × 9 pixels at scale 1.
inline constexpr int kGlyphWidth = 6, kGlyphHeight = 9;
// Whether pixel (col, row) of the 5×7 glyph of `c` is set.
bool glyph_pixel(char c, int col, int row);

// A box of lines on a translucent dark background, sized to fit them, with a margin.
Canvas text_box(const std::vector<std::string>& lines, Rgba colour, int scale = 1, const std::vector<Rgba>& line_colours = {});

}  // namespace strahl::view
