#include "strahl/scene/textures.h"

#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/image/image_io.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"

namespace strahl {

namespace {

// The sRGB transfer function's inverse (IEC 61966-2-1), in double.
double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

bool stores_linear(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".pfm" || ext == ".exr";
}

// An 8- or 16-bit picture's stored values decoded from sRGB. read_image gives an 8-bit code c as
// c/255 and a 16-bit one as c/65535 (in float); both are k/65535 for a whole k (c/255 =
// 257c/65535), which rounding v·65535 finds exactly. So one table of the 65536 decoded values
// serves both depths, exact to the encoded fraction.
void decode_srgb(Image& image) {
  std::vector<float> decoded(65536);
  for (std::size_t k = 0; k < decoded.size(); ++k) decoded[k] = float(srgb_to_linear(double(k) / 65535.0));
  for (int row = 0; row < image.height(); ++row)
    for (int x = 0; x < image.width(); ++x) {
      Rgb& p = image.at(x, row);
      for (float* c : {&p.r, &p.g, &p.b}) *c = decoded[std::size_t(std::lround(double(*c) * 65535.0))];
    }
}

}  // namespace

std::shared_ptr<const Image> read_texture_image(const std::filesystem::path& file, bool linear) {
  auto image = std::make_shared<Image>(read_image(file));
  if (!linear && !stores_linear(file)) decode_srgb(*image);
  return image;
}

std::shared_ptr<Image> decode_texture_image(std::string_view bytes, const std::string& name) {
  auto image = std::make_shared<Image>(decode_image(bytes, name));
  decode_srgb(*image);
  return image;
}

void compile_textures(const Scene& scene, RenderScene& out) {
  std::map<const Image*, std::uint64_t> first_texel;  // each picture's pixels once
  for (const ImageTexture& t : scene.textures()) {
    if (t.image == nullptr || t.image->width() <= 0 || t.image->height() <= 0)
      throw Error(t.loc, "an image texture needs an image with pixels");
    const Image& image = *t.image;
    auto [it, fresh] = first_texel.try_emplace(&image, out.texels.size());
    if (fresh) {
      out.texels.reserve(out.texels.size() + 3 * image.pixels().size());
      for (const Rgb& p : image.pixels()) out.texels.insert(out.texels.end(), {p.r, p.g, p.b});
    }
    kernel::ImageTexture k;
    // to_texture: q = L⁻¹·(p − translate) for the placement p = L·q + translate.
    const Mat3 inverse = t.placement.linear().inverse();
    for (int r = 0; r < 3; ++r) k.to_texture.row[r] = inverse.row[r];
    k.to_texture.translate = t.placement.translate;
    k.first_texel = it->second;
    k.width = static_cast<std::uint32_t>(image.width());
    k.height = static_cast<std::uint32_t>(image.height());
    k.mapping = t.mapping;
    k.bilinear = t.bilinear;
    k.once = t.once;
    out.textures.push_back(k);
  }
}

}  // namespace strahl
