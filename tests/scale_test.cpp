// Any consistent scale renders the same image (docs/scene-format.md, "Units and scale"): the
// lecture scene with every length multiplied by 10^k — positions, radii, plane offsets, triangle
// vertices, light positions and sizes, checker size, lens aperture and focus distance — gives the
// unscaled image for every k in the proven range, and is refused with a message naming that range
// outside it. Secondary rays start an offset relative to the hit's own error bound (the magnitudes
// that went into computing it), never an absolute distance, so nothing here depends on the units.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/render/render_scene.h"
#include "strahl/scene/csg.h"
#include "strahl/scene/solids.h"
#include "strahl/scene/validate.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::scale_test {
namespace {

struct Extras {
  bool triangle = false, area_light = false, checker = false, lens = false, solids = false;
};

// scenes/lecture-whitted.yaml (mirror, filtering glass, shadows) with every position and length
// multiplied by `s` and shifted by `offset`; `extras` adds a triangle, a rect area light, a
// checkered floor, a thin lens and solids (a box, a torus, a box with a sphere cut out of it), each
// carrying lengths of its own.
Scene transformed_whitted(Real s, const Vec3& offset, Extras extras = {}) {
  const Scene src = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  Scene out;
  out.camera = src.camera;
  out.settings = src.settings;
  out.settings.width = 48;
  out.settings.height = 27;
  out.camera.position = src.camera.position * s + offset;
  out.camera.look_at = src.camera.look_at * s + offset;
  if (extras.lens) {
    out.camera.aperture = 0.02 * s;
    out.camera.focus_distance = 2.0 * s;
    out.settings.sampling.spp = 4;
  }
  for (const auto& object : src.objects()) {
    if (const auto* sphere = dynamic_cast<const Sphere*>(object.get())) {
      out.add(Sphere(sphere->center * s + offset, sphere->radius * s, sphere->material));
    } else if (const auto* plane = dynamic_cast<const Plane*>(object.get())) {
      const Vec3 n = normalize(plane->normal);
      Material m = plane->material;
      if (extras.checker) m.checker_size = 0.25 * s;
      out.add(Plane(n, plane->distance / length(plane->normal) * s + dot(n, offset), m));
    } else {
      ADD_FAILURE() << "unexpected object in lecture-whitted.yaml";
    }
  }
  if (extras.triangle)
    out.add(Triangle(Vec3(0.5, 0.05, -0.4) * s + offset, Vec3(0.9, 0.05, -0.2) * s + offset,
                     Vec3(0.7, 0.5, -0.3) * s + offset, material_with_color(Vec3(0.9, 0.6, 0.1))));
  if (extras.solids) {
    const auto at = [&](const Vec3& p) { return p * s + offset; };
    out.add(Box(at({0.55, 0, 0.35}), at({0.75, 0.15, 0.55}), material_with_color(Vec3(0.2, 0.8, 0.3))));
    out.add(Torus(at({-0.05, 0.05, 0.6}), 0.12 * s, 0.04 * s, material_with_color(Vec3(0.9, 0.3, 0.2))));
    std::vector<std::unique_ptr<SceneObject>> parts;
    parts.push_back(std::make_unique<Box>(at({0.6, 0, -0.5}), at({0.9, 0.3, -0.2}), Material{}));
    parts.push_back(std::make_unique<Sphere>(at({0.75, 0.3, -0.35}), 0.12 * s, Material{}));
    out.add(Csg(CsgOperation::Difference, std::move(parts), material_with_color(Vec3(0.3, 0.3, 0.9))));
  }
  for (Light light : src.lights()) {
    light.position = light.position * s + offset;
    out.add(light);
  }
  if (extras.area_light)
    out.add(rect_light(Vec3(-1, 1.5, 0.5) * s + offset, Vec3(0.4, 0, 0) * s, Vec3(0, 0, -0.4) * s, Vec3(0.8), 2));
  return out;
}

std::string describe(Real s, const Vec3& offset) {
  std::ostringstream out;
  out << "scale " << s << ", offset (" << offset.x << ", " << offset.y << ", " << offset.z << ")";
  return out.str();
}

// Pixels whose colour differs by more than `tolerance` in some channel.
int pixels_differing(const Image& a, const Image& b, float tolerance) {
  int n = 0;
  for (std::size_t i = 0; i < a.pixels().size() && i < b.pixels().size(); ++i) {
    const Rgb &p = a.pixels()[i], &q = b.pixels()[i];
    if (std::fabs(p.r - q.r) > tolerance || std::fabs(p.g - q.g) > tolerance || std::fabs(p.b - q.b) > tolerance) ++n;
  }
  return n;
}

TEST(Scale, ScaledAndMovedScenesRenderTheSameImage) {
  const Image reference = test::render_image(transformed_whitted(1, Vec3(0)), 2);
  struct Case { Real scale; Vec3 offset; };
  for (const Case& c : {Case{1e-3, Vec3(0)}, Case{1e4, Vec3(0)}, Case{1, Vec3(1e3, 0, -1e3)},
                        Case{1e-3, Vec3(1, 2, 3)}, Case{50, Vec3(-7, 0, 11)}, Case{1e4, Vec3(1e5, -1e5, 1e5)}}) {
    const Image img = test::render_image(transformed_whitted(c.scale, c.offset), 2);
    EXPECT_LE(test::max_abs_diff(img, reference), 1e-4f) << describe(c.scale, c.offset);
  }
}

// The sweep: 10^k for every k in the proven range, with the default accelerator; every other
// accelerator at the ends and in between. Coordinates like 0.3·10^k round differently at each k,
// so a ray grazing a silhouette may land on its other side: a handful of such pixels may differ,
// nothing like acne, light leaks or lost geometry (which change whole surfaces).
void expect_same_image(const Image& img, const Image& reference, const std::string& what) {
  const int n = int(reference.pixels().size());
  EXPECT_LE(pixels_differing(img, reference, 1e-4f), n / 200) << what;
  EXPECT_LE(test::max_abs_diff(img, reference), 0.5f) << what;
}

TEST(Scale, EveryPowerOfTenInTheProvenRangeRendersTheSameImage) {
  using validate::kMaxScaleExponent;
  static_assert(kMaxScaleExponent == 30, "docs/scene-format.md quotes the range");
  const Extras all{true, true, true, true, true};
  const Image reference = test::render_image(transformed_whitted(1, Vec3(0), all), 2);
  // The solids are in view (a sweep over an image without them would prove nothing about them).
  const Image without_solids = test::render_image(transformed_whitted(1, Vec3(0), {true, true, true, true, false}), 2);
  EXPECT_GT(pixels_differing(reference, without_solids, 1e-3f), int(reference.pixels().size()) / 20);
  for (int k = -kMaxScaleExponent; k <= kMaxScaleExponent; ++k) {
    const Real s = std::pow(Real(10), Real(k));
    expect_same_image(test::render_image(transformed_whitted(s, Vec3(0), all), 2), reference, describe(s, Vec3(0)));
  }
  for (AccelKind kind : accel_kinds()) {
    for (int k : {-kMaxScaleExponent, -17, 0, 13, kMaxScaleExponent}) {
      Scene scene = transformed_whitted(std::pow(Real(10), Real(k)), Vec3(0), all);
      scene.settings.accel = kind;
      expect_same_image(test::render_image(scene, 2), reference, std::string(accel_name(kind)) + " at 1e" + std::to_string(k));
    }
  }
  // Moved far out at a large and a small scale too.
  expect_same_image(test::render_image(transformed_whitted(1e20, Vec3(3e20, -1e21, 2e20), all), 2), reference,
                    describe(1e20, Vec3(3e20, -1e21, 2e20)));
}

// Outside the range: refused with a message naming the limits, not "camera up is parallel" or an
// empty image.
TEST(Scale, BeyondTheRangeTheSceneIsRefusedNamingTheLimits) {
  const Extras all{true, true, true, true};
  for (int k : {-33, -60, -200, -320, 33, 100, 155, 300}) {
    const Real s = std::pow(Real(10), Real(k));
    try {
      compile(transformed_whitted(s, Vec3(0), all));
      ADD_FAILURE() << "scale 1e" << k << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      // At 1e-320 and below the lengths underflow to 0 in this test's own multiplication.
      if (k > -320) {
        EXPECT_NE(what.find("scenes must fit within 1e-32 to 1e32 units"), std::string::npos) << "1e" << k << ": " << what;
      }
      EXPECT_EQ(what.find("parallel"), std::string::npos) << what;
    }
  }
}

// Values finite but overflowing once squared, directions given tiny or huge, denormals.
TEST(Scale, ExtremeValuesRenderRightOrNameTheRealLimit) {
  const auto message = [](const std::string& text) -> std::string {
    try {
      compile(parse_scene(text, "x.yaml", fs::path(STRAHL_SOURCE_DIR) / "tests" / "bad-input"));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const std::string head = "camera: {position: [0, 1, 3], look_at: [0, 0, 0], fov: 40}\nrender: {width: 8, height: 6}\n"
                           "lights:\n  - {type: point, position: [2, 3, 2]}\nobjects:\n";
  EXPECT_NE(message(head + "  - {type: sphere, center: [0, 0, 0], radius: 1e155}\n").find("sphere radius 1e+155 is above 1e32"),
            std::string::npos);
  EXPECT_NE(message(head + "  - {type: triangle, vertices: [[0, 0, 0], [1e200, 0, 0], [0, 1, 0]]}\n")
                .find("triangle vertex has a coordinate of 1e+200, beyond ±1e32"),
            std::string::npos);
  EXPECT_NE(message(head + "  - {type: mesh, file: ../../scenes/meshes/icosahedron.obj, scale: 1e300}\n")
                .find("mesh vertex lands at a coordinate of"),
            std::string::npos);
  EXPECT_NE(message(head + "  - {type: sphere, center: [0, 0, 0], radius: 4e-320}\n").find("sphere radius 4e-320 is below 1e-32"),
            std::string::npos);
  // Directions are normalised without squaring: tiny, huge and denormal components are fine.
  for (const char* normal : {"[0, 1e-300, 0]", "[0, 4e-320, 0]", "[0, 1e300, 0]"}) {
    const std::string text = "camera: {position: [0, 1, 3], look_at: [0, 0, 0], up: " + std::string(normal) +
                             ", fov: 40}\nrender: {width: 8, height: 6}\nlights:\n  - {type: directional, direction: " +
                             normal + "}\nobjects:\n  - {type: plane, normal: " + normal + ", distance: 0}\n";
    EXPECT_EQ(message(text), "") << normal;
    const RenderScene rs = compile(parse_scene(text, "x.yaml", "."));
    EXPECT_EQ(rs.planes[0].normal, Vec3(0, 1, 0)) << normal;
    EXPECT_EQ(rs.planes[0].distance, 0) << normal;
    EXPECT_EQ(rs.lights[0].direction, Vec3(0, 1, 0)) << normal;
  }
  // A shape too small for where it is: below the precision of secondary rays there.
  EXPECT_NE(message(head + "  - {type: sphere, center: [1e30, 0, 0], radius: 1}\n")
                .find("sphere radius 1 is too small for its distance from the origin (1e+30)"),
            std::string::npos);
  // (N·p = d with N tiny puts the plane far away: d/|N| must stay within the limits.)
  EXPECT_NE(message(head + "  - {type: plane, normal: [0, 1e-300, 0], distance: -1}\n").find("lies beyond ±1e32"),
            std::string::npos);
  // Denormal and tiny values where they are harmless: coordinates, colours, intensities.
  EXPECT_EQ(message(head + "  - {type: sphere, center: [4e-320, 0, -1e-310], radius: 1, material: {color: 1e-310}}\n"), "");
}

// The same scene (about 2 units across) moved 1e5 units from the origin. Secondary rays start
// 1e-9·|p| off the surface, 1e-4 units out there: refracted and reflected rays shift by that
// much, which changes a few pixels by about 1e-3 (measured: 36 of 1296, at most 1.3e-3). Acne
// or light leaks would change whole surfaces by far more, so: a small maximum difference, and
// only a few pixels over 1e-4.
TEST(Scale, SceneMovedFarFromTheOriginRendersTheSame) {
  const Image reference = test::render_image(transformed_whitted(1, Vec3(0)), 2);
  for (const Vec3& offset : {Vec3(1e5, 0, 0), Vec3(0, 1e5, 0), Vec3(0, 0, -1e5), Vec3(1e5, 1e5, -1e5)}) {
    const Image img = test::render_image(transformed_whitted(1, offset), 2);
    int over = 0;
    for (std::size_t i = 0; i < img.pixels().size(); ++i) {
      const Rgb &p = img.pixels()[i], &q = reference.pixels()[i];
      if (std::fabs(p.r - q.r) > 1e-4f || std::fabs(p.g - q.g) > 1e-4f || std::fabs(p.b - q.b) > 1e-4f) ++over;
    }
    const std::string where = "offset (" + std::to_string(offset.x) + ", " + std::to_string(offset.y) + ", " +
                              std::to_string(offset.z) + ")";
    EXPECT_LE(test::max_abs_diff(img, reference), 5e-3f) << where;
    EXPECT_LE(over, int(img.pixels().size()) / 20) << where << ": " << over << " pixels differ by more than 1e-4";
  }
}

}  // namespace
}  // namespace strahl::scale_test
