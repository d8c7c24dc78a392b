// Secondary rays start a scale-relative distance off the surface, so a scene renders the same
// (no shadow acne, no light leaks) when it is scaled by 1e-3 … 1e4 or moved away from the origin.

#include <gtest/gtest.h>

#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl {
namespace {

// scenes/lecture-whitted.yaml (mirror, filtering glass, shadows) with every position and length
// multiplied by `s` and shifted by `offset`.
Scene transformed_whitted(Real s, const Vec3& offset) {
  const Scene src = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  Scene out;
  out.camera = src.camera;
  out.settings = src.settings;
  out.settings.width = 48;
  out.settings.height = 27;
  out.camera.position = src.camera.position * s + offset;
  out.camera.look_at = src.camera.look_at * s + offset;
  for (const auto& object : src.objects()) {
    if (const auto* sphere = dynamic_cast<const Sphere*>(object.get())) {
      out.add(Sphere(sphere->center * s + offset, sphere->radius * s, sphere->material));
    } else if (const auto* plane = dynamic_cast<const Plane*>(object.get())) {
      const Vec3 n = normalize(plane->normal);
      out.add(Plane(n, plane->distance / length(plane->normal) * s + dot(n, offset), plane->material));
    } else {
      ADD_FAILURE() << "unexpected object in lecture-whitted.yaml";
    }
  }
  for (Light light : src.lights()) {
    light.position = light.position * s + offset;
    out.add(light);
  }
  return out;
}

TEST(Scale, ScaledAndMovedScenesRenderTheSameImage) {
  const Image reference = test::render_image(transformed_whitted(1, Vec3(0)), 2);
  struct Case { Real scale; Vec3 offset; };
  for (const Case& c : {Case{1e-3, Vec3(0)}, Case{1e4, Vec3(0)}, Case{1, Vec3(1e3, 0, -1e3)},
                        Case{1e-3, Vec3(1, 2, 3)}, Case{50, Vec3(-7, 0, 11)}, Case{1e4, Vec3(1e5, -1e5, 1e5)}}) {
    const Image img = test::render_image(transformed_whitted(c.scale, c.offset), 2);
    EXPECT_LE(test::max_abs_diff(img, reference), 1e-4f) << "scale " << c.scale << ", offset (" << c.offset.x << ", " << c.offset.y << ", "
                                                      << c.offset.z << ")";
  }
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
}  // namespace strahl
