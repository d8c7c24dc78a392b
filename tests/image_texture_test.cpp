// Image textures (shading/image_texture.h, POV-Ray's image_map): which pixel each mapping reads
// for points worked out by hand (the centres of the pixels under planar, spherical and
// cylindrical mapping), the bilinear blend at and between pixel centres and across the wrapped
// edge, `once`, the placement, the sRGB decoding of 8-bit files, whole rendered images against
// the picture, and the scene file's keys and errors.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/image/image_io.h"
#include "test_helpers.h"
#include "test_picture.h"

namespace strahl::image_texture_test {
namespace {

constexpr int kW = test::kPictureWidth, kH = test::kPictureHeight;
using test::picture;
using test::picture_pixel;

// The compiled texture (and its texels) of one ImageTexture.
struct Compiled {
  RenderScene rs;
  Vec3 at(const Vec3& p, const Vec3& outside = Vec3(-1)) const {
    return kernel::image_color(rs.textures.at(0), rs.texels.data(), p, outside);
  }
};

Compiled compiled(ImageMapping mapping, bool bilinear, bool once = false, const Transform& placement = {}) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  ImageTexture t;
  t.image = picture();
  t.mapping = mapping;
  t.bilinear = bilinear;
  t.once = once;
  t.placement = placement;
  Material m;
  m.texture = s.add_texture(t);
  s.add(Sphere({0, 0, -3}, 1, m));
  return {compile(s)};
}

// The centre of pixel (x, row) in the image's unit square: u across, v up.
Real centre_u(int x) { return (x + 0.5) / kW; }
Real centre_v(int row) { return 1 - (row + 0.5) / kH; }

TEST(ImageTexture, PlanarReadsThePixelAPointFallsIntoRepeatedAlongXAndY) {
  const Compiled c = compiled(ImageMapping::Planar, false);
  for (int row = 0; row < kH; ++row)
    for (int x = 0; x < kW; ++x)
      for (const Vec3 shift : {Vec3(0), Vec3(3, -2, 7), Vec3(-1, 5, -0.5)})
        EXPECT_EQ(c.at(Vec3(centre_u(x), centre_v(row), 0) + shift), picture_pixel(x, row))
            << x << ", " << row << " shifted by " << shift.x << ", " << shift.y;
  // Near the edges of a pixel: the pixel itself (the top row is at y = 1, the first column at x = 0).
  EXPECT_EQ(c.at({0.001, 0.999, 0}), picture_pixel(0, 0));
  EXPECT_EQ(c.at({0.999, 0.001, 0}), picture_pixel(kW - 1, kH - 1));
  EXPECT_EQ(c.at({0.249, 0.501, 0}), picture_pixel(0, 0));
  EXPECT_EQ(c.at({0.251, 0.499, 0}), picture_pixel(1, 1));
}

TEST(ImageTexture, OnceShowsTheMaterialsColourOutsideTheImage) {
  const Compiled c = compiled(ImageMapping::Planar, false, true);
  EXPECT_EQ(c.at({centre_u(1), centre_v(0), 4}), picture_pixel(1, 0));
  for (const Vec3 p : {Vec3(1.2, 0.5, 0), Vec3(-0.1, 0.5, 0), Vec3(0.5, 1.01, 0), Vec3(0.5, -0.3, 0)})
    EXPECT_EQ(c.at(p, Vec3(7)), Vec3(7)) << p.x << ", " << p.y;
  const Compiled repeated = compiled(ImageMapping::Planar, false, false);
  EXPECT_EQ(repeated.at({1.2, 0.8, 0}, Vec3(7)), picture_pixel(0, 0));
}

TEST(ImageTexture, BilinearIsThePixelAtItsCentreAndBlendsBetweenCentres) {
  const Compiled c = compiled(ImageMapping::Planar, true);
  // (To 1e-9: the 1e-10 nudge that POV-Ray gives every point takes that much of a neighbour.)
  for (int row = 0; row < kH; ++row)
    for (int x = 0; x < kW; ++x)
      EXPECT_TRUE(test::vec_near(c.at({centre_u(x), centre_v(row), 0}), picture_pixel(x, row), 1e-9));
  // Halfway between the centres of (1, 0) and (2, 0); a quarter of the way from (2, 1) to (2, 0).
  EXPECT_TRUE(test::vec_near(c.at({2.0 / kW, centre_v(0), 0}), (picture_pixel(1, 0) + picture_pixel(2, 0)) * 0.5, 1e-9));
  EXPECT_TRUE(test::vec_near(c.at({centre_u(2), 0.25 + 0.125, 0}),
                             picture_pixel(2, 1) * 0.75 + picture_pixel(2, 0) * 0.25, 1e-9));
  // On the left edge the blend wraps to the last column; with `once` it keeps to the first.
  EXPECT_TRUE(test::vec_near(c.at({0, centre_v(1), 0}), (picture_pixel(0, 1) + picture_pixel(kW - 1, 1)) * 0.5, 1e-9));
  const Compiled once = compiled(ImageMapping::Planar, true, true);
  EXPECT_TRUE(test::vec_near(once.at({0.0001, centre_v(1), 0}), picture_pixel(0, 1), 1e-9));
}

TEST(ImageTexture, SphericalWrapsLongitudeAcrossAndLatitudeUp) {
  const Compiled c = compiled(ImageMapping::Spherical, false);
  for (int row = 0; row < kH; ++row)
    for (int x = 0; x < kW; ++x) {
      // Longitude from +x towards +z, latitude from −90° (bottom row) to +90° (top row).
      const Real theta = centre_u(x) * 2 * kPi, phi = (centre_v(row) - 0.5) * kPi;
      const Vec3 dir(std::cos(phi) * std::cos(theta), std::sin(phi), std::cos(phi) * std::sin(theta));
      for (const Real r : {1.0, 0.01, 250.0}) EXPECT_EQ(c.at(dir * r), picture_pixel(x, row)) << x << ", " << row;
    }
  EXPECT_EQ(c.at(Vec3(0), Vec3(7)), Vec3(7));  // the centre has no direction
  EXPECT_EQ(c.at(Vec3(0.001, 2, 0)), picture_pixel(0, 0));   // by the north pole: the top row
  EXPECT_EQ(c.at(Vec3(0.001, -2, 0)), picture_pixel(0, 1));  // by the south pole: the bottom row
}

TEST(ImageTexture, CylindricalWrapsAroundTheYAxisOneImagePerUnitHeight) {
  const Compiled c = compiled(ImageMapping::Cylindrical, false);
  for (int row = 0; row < kH; ++row)
    for (int x = 0; x < kW; ++x) {
      const Real theta = centre_u(x) * 2 * kPi;
      for (const Real r : {1.0, 3.0})
        for (const Real lift : {0.0, 2.0, -1.0})
          EXPECT_EQ(c.at({r * std::cos(theta), centre_v(row) + lift, r * std::sin(theta)}), picture_pixel(x, row))
              << x << ", " << row;
    }
  EXPECT_EQ(c.at(Vec3(0, 0.5, 0), Vec3(7)), Vec3(7));  // on the axis: no angle
  const Compiled once = compiled(ImageMapping::Cylindrical, false, true);
  EXPECT_EQ(once.at(Vec3(1, 1.5, 0), Vec3(7)), Vec3(7));
  EXPECT_EQ(once.at(Vec3(1, 0.75, 0), Vec3(7)), picture_pixel(0, 0));
}

TEST(ImageTexture, NotANumberReadsNoPixel) {
  for (const ImageMapping m : {ImageMapping::Planar, ImageMapping::Spherical, ImageMapping::Cylindrical}) {
    const Compiled c = compiled(m, true);
    const Real nan = std::nan("");
    EXPECT_EQ(c.at({nan, 0.5, 0.5}, Vec3(7)), Vec3(7));
    EXPECT_EQ(c.at({0.5, kInfinity, 0.5}, Vec3(7)), Vec3(7));
  }
}

TEST(ImageTexture, ThePlacementCarriesTheTexture) {
  Transform place;
  place.scale = Vec3(2, 3, 0.5);
  place.rotate_degrees = Vec3(10, 90, -30);
  place.translate = Vec3(1, -2, 4);
  const Mat3 l = place.linear();
  for (const ImageMapping m : {ImageMapping::Planar, ImageMapping::Spherical, ImageMapping::Cylindrical}) {
    const Compiled plain = compiled(m, false), placed = compiled(m, false, false, place);
    for (int row = 0; row < kH; ++row)
      for (int x = 0; x < kW; ++x) {
        const Vec3 q(std::cos(centre_u(x) * 2 * kPi) * 0.8, centre_v(row) * 0.9 + 0.05, std::sin(centre_u(x) * 2 * kPi) * 0.8);
        const Vec3 q_planar(centre_u(x), centre_v(row), 0.3);
        const Vec3 p = m == ImageMapping::Planar ? q_planar : q;
        EXPECT_EQ(placed.at(l * p + place.translate), plain.at(p)) << int(m) << ": " << x << ", " << row;
      }
  }
}

TEST(ImageTexture, EightBitFilesAreDecodedFromSrgbUnlessLinear) {
  test::TempDir dir;
  test::write_text(dir / "grey.ppm", std::string("P6\n3 1\n255\n") + std::string("\x00\x00\x00\x80\x80\x80\xff\xff\xff", 9));
  const auto srgb = read_texture_image(dir / "grey.ppm");
  EXPECT_EQ(srgb->at(0, 0).r, 0.0f);
  EXPECT_FLOAT_EQ(srgb->at(1, 0).g, float(std::pow((128 / 255.0 + 0.055) / 1.055, 2.4)));  // 0.2158605
  EXPECT_EQ(srgb->at(2, 0).b, 1.0f);
  const auto linear = read_texture_image(dir / "grey.ppm", true);
  EXPECT_FLOAT_EQ(linear->at(1, 0).g, 128 / 255.0f);
  // Float formats hold linear values already.
  Image f(1, 1);
  f.at(0, 0) = {0.5f, 0.25f, 2.0f};
  write_image(f, dir / "f.pfm");
  EXPECT_EQ(read_texture_image(dir / "f.pfm")->at(0, 0), f.at(0, 0));
  EXPECT_THROW(read_texture_image(dir / "missing.png"), Error);
}

// A material lit by the ambient term alone (k_a = 1, the scene's ambient light 1): its colour is
// the picture's (nearest pixel), exactly.
Material ambient_only_picture(Scene& s) {
  s.settings.ambient_light = Vec3(1);
  ImageTexture t;
  t.image = picture();
  t.bilinear = false;
  Material m = test::phong(Vec3(0.5), 1, 0, Vec3(0), 1);
  m.texture = s.add_texture(t);
  return m;
}

// A plane and a triangle on the wall z = 0 filling a camera's view of the unit square: each pixel
// is the texture's pixel under its centre, exactly.
TEST(ImageTexture, RenderedPixelsAreThePicturesOnAPlaneAndATriangle) {
  for (const bool plane : {true, false}) {
    Scene s;
    constexpr int kN = 8;  // 2×4 image pixels per texture pixel
    test::set_camera(s, {0.5, 0.5, 1}, {0.5, 0.5, 0}, {0, 1, 0}, -0.5, 0.5, -0.5, 0.5, 1, kN, kN);
    const Material m = ambient_only_picture(s);
    if (plane) s.add(Plane({0, 0, 1}, 0, m));
    else s.add(Triangle({-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}, m));
    const RenderScene rs = compile(s);
    for (int row = 0; row < kN; ++row)
      for (int x = 0; x < kN; ++x) {
        RayCounters counters;
        const Vec3 c = render_pixel(rs.view(), x, row, 1, counters);
        EXPECT_EQ(c, picture_pixel(x * kW / kN, row * kH / kN)) << (plane ? "plane " : "triangle ") << x << ", " << row;
      }
  }
}

// On a plane an image is read at the point, as on any other shape (the checker uses the plane's
// own (u, v)): on a floor y = 0 the planar image, carried along z, shows its bottom row (y = 0)
// wherever x puts it.
TEST(ImageTexture, OnAFloorTheImageIsReadAtThePoint) {
  for (const Real x0 : {0.1, 0.3, 0.6, 0.9, 2.35})
    for (const Real z0 : {-3.0, 0.2, 5.0}) {
      Scene s;
      test::one_ray_camera(s, {x0, 1, z0}, {x0, 0, z0}, {0, 0, -1});
      s.add(Plane({0, 1, 0}, 0, ambient_only_picture(s)));
      EXPECT_EQ(test::pixel(s), picture_pixel(int(std::floor(x0 * kW)) % kW, kH - 1)) << x0 << ", " << z0;
    }
}

// In an instanced group the picture is read in the group's own space: it moves and turns with
// each instance. A sphere at the group's origin, spherically mapped, placed twice (moved; turned
// 90° about y and moved): a ray along the direction of a pixel's centre in the group's space, as
// each instance carries it into the world, meets that pixel.
TEST(ImageTexture, InstancesCarryTheirTexture) {
  test::TempDir dir;
  write_image(*picture(), dir / "picture.pfm");
  Scene s = parse_scene(
      "render: {ambient_light: 1}\n"
      "groups:\n  globe:\n    - {type: sphere, center: [0, 0, 0], radius: 1, material: {ambient: 1, diffuse: 0, "
      "specular: 0, image: {file: picture.pfm, mapping: spherical, interpolate: nearest}}}\n"
      "objects:\n  - {type: instance, of: globe, translate: [5, 0, 0]}\n"
      "  - {type: instance, of: globe, rotate: [0, 90, 0], translate: [-5, 0, 0]}\n",
      "t.yaml", dir.path());
  const auto direction = [](Real turn, Real latitude_degrees) {  // in the group's space
    const Real theta = turn * 2 * kPi, phi = test::deg(latitude_degrees);
    return Vec3(std::cos(phi) * std::cos(theta), std::sin(phi), std::cos(phi) * std::sin(theta));
  };
  struct Case {
    Vec3 center, d;  // the instance's centre, the direction in the world
    int x, row;      // the pixel expected
  };
  const Vec3 turned = direction(0.625, -20);  // column 2, the lower row; turned by 90° about y: (z, y, −x)
  for (const Case& c : {Case{{5, 0, 0}, direction(0.375, 20), 1, 0},
                        Case{{-5, 0, 0}, Vec3(turned.z, turned.y, -turned.x), 2, 1}}) {
    test::one_ray_camera(s, c.center + c.d * 3, c.center);
    EXPECT_EQ(test::pixel(s), picture_pixel(c.x, c.row)) << c.center.x;
  }
}

TEST(ImageTexture, SceneFileKeysAndErrors) {
  test::TempDir dir;
  Image img(2, 1);
  img.at(0, 0) = {0.25f, 0.5f, 1.0f};
  img.at(1, 0) = {1.0f, 0.0f, 0.0f};
  write_image(img, dir / "two.pfm");
  const std::string head =
      "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\nobjects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, "
      "material: ";
  const auto load = [&](const std::string& material) { return parse_scene(head + material + "}\n", "t.yaml", dir.path()); };
  const Scene s = load("{image: {file: two.pfm, mapping: spherical, interpolate: nearest, once: true, translate: [1, 2, 3]}}");
  ASSERT_EQ(s.textures().size(), 1u);
  EXPECT_EQ(s.objects().at(0)->material.texture, 0u);
  const ImageTexture& t = s.textures()[0];
  EXPECT_EQ(t.mapping, ImageMapping::Spherical);
  EXPECT_FALSE(t.bilinear);
  EXPECT_TRUE(t.once);
  EXPECT_EQ(t.placement.translate, Vec3(1, 2, 3));
  EXPECT_EQ(t.image->at(0, 0), img.at(0, 0));
  const Scene defaults = load("{image: {file: two.pfm}}");
  EXPECT_EQ(defaults.textures()[0].mapping, ImageMapping::Planar);
  EXPECT_TRUE(defaults.textures()[0].bilinear);
  EXPECT_FALSE(defaults.textures()[0].once);

  const auto error = [&](const std::string& material) {
    try {
      compile(load(material));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("{image: {file: nothing.png}}").find("t.yaml:3:"), std::string::npos);
  EXPECT_NE(error("{image: {file: nothing.png}}").find("image: "), std::string::npos);
  EXPECT_NE(error("{image: {file: two.pfm, mapping: torus}}").find("unknown image mapping 'torus'"), std::string::npos);
  EXPECT_NE(error("{image: {file: two.pfm, interpolate: cubic}}").find("unknown image interpolate"), std::string::npos);
  EXPECT_NE(error("{image: {file: two.pfm, size: 2}}").find("unknown key 'size'"), std::string::npos);
  EXPECT_NE(error("{image: {mapping: planar}}").find("file"), std::string::npos);
  EXPECT_NE(error("{image: {file: two.pfm}, checker: {size: 1}}").find("a checker or an image, not both"), std::string::npos);
  EXPECT_NE(error("{image: {file: two.pfm, scale: [1, 0, 1]}}"), "no error");

  // C++ callers: an index the scene does not have, a texture without pixels.
  Scene c;
  Material m;
  m.texture = 3;
  c.add(Sphere({0, 0, -3}, 1, m));
  EXPECT_THROW(compile(c), Error);
  EXPECT_THROW(c.add_texture(ImageTexture{}), Error);
}

}  // namespace
}  // namespace strahl::image_texture_test
