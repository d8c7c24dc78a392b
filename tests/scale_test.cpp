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
                        Case{1e-3, Vec3(1, 2, 3)}, Case{50, Vec3(-7, 0, 11)}}) {
    const Image img = test::render_image(transformed_whitted(c.scale, c.offset), 2);
    EXPECT_LE(test::max_abs_diff(img, reference), 1e-4f) << "scale " << c.scale << ", offset " << c.offset.x;
  }
}

}  // namespace
}  // namespace strahl
