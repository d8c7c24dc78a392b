#pragma once
// Image textures: a picture wrapped onto surfaces as the colour C, with POV-Ray's `image_map`
// mappings (its map_type 0, 1, 2) and lookups (interpolate 0 and 2), so that a scene imported
// from POV-Ray shows what POV-Ray shows.
//
// The texture is read at the surface point p (world space; for a shape in an instanced group, in
// the group's own space, so that the texture moves with the instance), brought to the texture's
// own space by `to_texture` (the inverse of the texture's placement): q = to_texture(p). There:
//
//   planar       the image covers the square [0, 1]² of the x-y plane, its top row at y = 1,
//                repeated along x and y and carried along z unchanged;
//   spherical    wrapped around the origin: longitude θ = the angle from +x towards +z (0 … 2π)
//                across the image, latitude φ = asin(y/|q|) from the bottom row (−90°) to the
//                top (+90°);
//   cylindrical  wrapped around the y axis (θ as above), one image from y = 0 to y = 1,
//                repeated along y;
//   uv           as planar, at the mesh's own texture coordinates (u, v, 0) interpolated from
//                its vertices (OBJ `vt`, PLY u/v) instead of at p; on a shape without them, at p.
//
// With `once`, the image is not repeated: outside it (and where the mapping is undefined: the
// origin, the y axis for cylindrical) the material's own colour shows. The image's pixel x, row
// r covers [x, x + 1) × [r, r + 1) of image coordinates; `nearest` reads the pixel a point falls
// into, `bilinear` blends the four pixels around it by their centres (wrapping at the edges, or
// clamped to them with `once`).

#include <cmath>
#include <cstdint>
#include <string_view>

#include "strahl/geometry/placement.h"
#include "strahl/math/vec3.h"

namespace strahl {

inline constexpr std::uint32_t kNoTexture = ~std::uint32_t(0);

enum class ImageMapping : std::uint8_t { Planar, Spherical, Cylindrical, UV };

// The mapping's name, as scene files, Python and messages spell it.
constexpr const char* image_mapping_name(ImageMapping mapping) {
  switch (mapping) {
    case ImageMapping::Planar: return "planar";
    case ImageMapping::Spherical: return "spherical";
    case ImageMapping::Cylindrical: return "cylindrical";
    case ImageMapping::UV: return "uv";
  }
  return "mapping";
}

// The mapping named `name`; false where no mapping has that name.
constexpr bool image_mapping_from(std::string_view name, ImageMapping& mapping) {
  for (const ImageMapping m : {ImageMapping::Planar, ImageMapping::Spherical, ImageMapping::Cylindrical, ImageMapping::UV})
    if (name == image_mapping_name(m)) {
      mapping = m;
      return true;
    }
  return false;
}
inline constexpr const char* kImageMappingNames = "planar, spherical, cylindrical or uv";

// The lookup's name (ImageTexture::bilinear), and the lookup named `name` (false: no such name).
constexpr const char* image_interpolate_name(bool bilinear) { return bilinear ? "bilinear" : "nearest"; }
constexpr bool image_interpolate_from(std::string_view name, bool& bilinear) {
  if (name != "nearest" && name != "bilinear") return false;
  bilinear = name == "bilinear";
  return true;
}
inline constexpr const char* kImageInterpolateNames = "nearest or bilinear";

namespace kernel {

// One image texture as the renderer reads it. Its pixels are `width`·`height` RGB triples of
// linear float in the scene's texel array, row 0 (the top) first, from `first_texel` (an index
// of floats) on.
struct ImageTexture {
  Placement to_texture;  // texture coordinate → texture space
  std::uint64_t first_texel = 0;
  std::uint32_t width = 0, height = 0;
  ImageMapping mapping = ImageMapping::Planar;
  bool bilinear = false;
  bool once = false;
};

// The scene's image textures and their texels (SceneView::textures).
struct Textures {
  const ImageTexture* images = nullptr;
  const float* texels = nullptr;
};

// v modulo m in [0, m): m > 0 and v finite.
STRAHL_HOST_DEVICE inline Real wrap(Real v, Real m) {
  Real r = std::fmod(v, m);
  if (r < 0) r += m;
  return r < m ? r : 0;  // (−tiny + m rounds to m)
}

// The angle of (x, z) from +x towards +z as a fraction of a turn, in [0, 1); (x, z) ≠ 0.
STRAHL_HOST_DEVICE inline Real turn_fraction(Real x, Real z) {
  const Real len = std::sqrt(x * x + z * z);
  Real theta;
  if (z == 0) theta = x > 0 ? 0 : kPi;
  else theta = std::acos(x / len);
  if (z < 0) theta = 2 * kPi - theta;
  return theta / (2 * kPi);
}

// Where texture-space point q falls in image coordinates (x across from the left, y down from
// the top, both wrapped into the image); false where the image does not cover q.
STRAHL_HOST_DEVICE inline bool image_position(const ImageTexture& t, const Vec3& q, Real& x, Real& y) {
  const Real w = t.width, h = t.height;
  Real u = 0, v = 0;  // across, up
  if (t.mapping == ImageMapping::Planar || t.mapping == ImageMapping::UV) {
    if (t.once && !(q.x >= 0 && q.x <= 1 && q.y >= 0 && q.y <= 1)) return false;
    u = std::fmod(q.x * w, w);  // (reduced first, as POV-Ray does: the nudge below then rounds alike)
    v = std::fmod(q.y * h, h);
  } else {
    const Real len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(len > 0) || !std::isfinite(len)) return false;
    const Real nx = q.x / len, ny = q.y / len, nz = q.z / len;
    if (t.mapping == ImageMapping::Cylindrical) {
      if (t.once && !(q.y >= 0 && q.y <= 1)) return false;
      if (nx == 0 && nz == 0) return false;
      u = turn_fraction(nx, nz) * w;
      v = std::fmod(q.y * h, h);
    } else {
      u = (nx == 0 && nz == 0 ? 0 : turn_fraction(nx, nz)) * w;
      v = (Real(0.5) + std::asin(ny) / kPi) * h;
    }
  }
  if (!std::isfinite(u) || !std::isfinite(v)) return false;
  // POV-Ray nudges by 1e-10 (its EPSILON), so that a point on a pixel edge reads the pixel
  // above and to the right of it.
  u += Real(1e-10);
  v += Real(1e-10);
  if (t.once && !(u >= 0 && u < w && v >= 0 && v < h)) return false;
  x = wrap(u, w);
  y = wrap(-v, h);  // rows count down from the top
  return true;
}

// Pixel (ix, row) of the texture, its indices wrapped into the image (clamped with `once`).
STRAHL_HOST_DEVICE inline Vec3 texel(const ImageTexture& t, const float* texels, long long ix, long long row) {
  const long long w = t.width, h = t.height;
  if (t.once) {
    ix = ix < 0 ? 0 : (ix >= w ? w - 1 : ix);
    row = row < 0 ? 0 : (row >= h ? h - 1 : row);
  } else {
    ix = ((ix % w) + w) % w;
    row = ((row % h) + h) % h;
  }
  const float* p = texels + t.first_texel + 3 * (std::uint64_t(row) * t.width + std::uint64_t(ix));
  return {p[0], p[1], p[2]};
}

// The texture's colour at texture coordinate p, or `outside` where the image does not cover it.
STRAHL_HOST_DEVICE inline Vec3 image_color(const ImageTexture& t, const float* texels, const Vec3& p,
                                           const Vec3& outside) {
  Real x, y;
  if (!image_position(t, object_point(t.to_texture, p), x, y)) return outside;
  if (!t.bilinear) return texel(t, texels, static_cast<long long>(x), static_cast<long long>(y));
  // The four pixels whose centres surround (x, y), weighted by the distances to them (x, y ≥ 0:
  // truncation is floor).
  x += Real(0.5);
  y += Real(0.5);
  const auto ix = static_cast<long long>(x), iy = static_cast<long long>(y);
  const Real px = x - Real(ix), py = y - Real(iy);
  return texel(t, texels, ix, iy) * (px * py) + texel(t, texels, ix - 1, iy) * ((1 - px) * py) +
         texel(t, texels, ix, iy - 1) * (px * (1 - py)) + texel(t, texels, ix - 1, iy - 1) * ((1 - px) * (1 - py));
}

}  // namespace kernel
}  // namespace strahl
