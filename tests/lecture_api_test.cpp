// The lecture's C++ API compiles as written on its slides and builds the scene it describes.

#include <gtest/gtest.h>

#include <memory>

#include "test_helpers.h"

namespace strahl::lecture_api_test {
namespace {

TEST(LectureApi, SlideCodeBuildsTheScene) {
  Scene* s = new Scene();
  s->addSceneObject(new Sphere(Vec3(0.05, 0.3, 0.0), 0.3, Vec3(0.8, 0.2, 0.2)));
  s->addSceneObject(new Plane(Vec3(0, 1, 0), 0.0, Vec3(0.3)));
  s->addLightSource(Vec3(1, 1.5, 1));
  s->addLightSource(Vec3(-1, 2, 0.5));
  EXPECT_EQ(s->getNumLightSources(), 2);
  EXPECT_EQ(s->getLightSource(0), Vec3(1, 1.5, 1));
  EXPECT_EQ(s->getLightSource(1), Vec3(-1, 2, 0.5));
  ASSERT_EQ(s->objects().size(), 2u);

  const RenderScene rs = compile(*s);
  ASSERT_EQ(rs.spheres.size(), 1u);
  ASSERT_EQ(rs.planes.size(), 1u);
  ASSERT_EQ(rs.lights.size(), 2u);
  EXPECT_EQ(rs.spheres[0].center, Vec3(0.05, 0.3, 0.0));
  EXPECT_EQ(rs.spheres[0].radius, 0.3);
  EXPECT_EQ(rs.materials[rs.spheres[0].material].color, Vec3(0.8, 0.2, 0.2));
  EXPECT_EQ(rs.materials[rs.planes[0].material].color, Vec3(0.3));
  EXPECT_EQ(rs.planes[0].normal, Vec3(0, 1, 0));
  EXPECT_EQ(rs.planes[0].distance, 0);
  // addLightSource adds a white point light of intensity 1.
  EXPECT_EQ(rs.lights[0].kind, LightKind::Point);
  EXPECT_EQ(rs.lights[0].position, Vec3(1, 1.5, 1));
  EXPECT_EQ(rs.lights[0].radiance, Vec3(1));
  // A colour alone gives the default finish.
  const Material& m = rs.materials[rs.spheres[0].material];
  EXPECT_EQ(m.ambient, Material{}.ambient);
  EXPECT_EQ(m.diffuse, Material{}.diffuse);
  EXPECT_EQ(m.reflectivity, 0);
  EXPECT_EQ(m.transparency, 0);
  delete s;
}

TEST(LectureApi, LectureSceneIsTheSlidesScene) {
  const Scene s = lecture_scene();
  EXPECT_EQ(s.getNumLightSources(), 1);
  EXPECT_EQ(s.getLightSource(0), Vec3(1.0, 1.5, 1.0));
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.planes.size(), 1u);
  ASSERT_EQ(rs.spheres.size(), 5u);
  EXPECT_EQ(rs.spheres[0].center, Vec3(0.05, 0.3, 0.0));
  EXPECT_EQ(rs.spheres[4].center, Vec3(0.15, 0.6, -1.0));
  EXPECT_EQ(rs.spheres[4].radius, 0.6);
  EXPECT_EQ(rs.materials[rs.spheres[2].material].color, Vec3(0.5, 0.5, 0.1));
}

TEST(LectureApi, LectureSceneRendersAPlausibleImage) {
  Scene s = lecture_scene();
  s.settings.width = 32;
  s.settings.height = 18;
  const Image img = test::render_image(s, 2, 8);
  ASSERT_EQ(img.width(), 32);
  ASSERT_EQ(img.height(), 18);
  // The floor at the bottom is grey and lit.
  const Rgb floor = img.at(2, 17);
  EXPECT_GT(floor.r, 0.03f);
  EXPECT_FLOAT_EQ(floor.r, floor.g);
  EXPECT_FLOAT_EQ(floor.g, floor.b);
  // The red sphere sits in the middle.
  const Rgb centre = img.at(16, 10);
  EXPECT_GT(centre.r, 2 * centre.g);
}

TEST(LectureApi, LectureLambertSnippetAgreesWithTheRenderer) {
  // The slide's shadingLambert, written with the Vec3 methods it uses (dot, normalize).
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  s.addSceneObject(new Sphere(Vec3(0, 0, -3), 1, test::phong(Vec3(0.8, 0.4, 0.2), 0, 1, Vec3(0), 1)));
  s.addLightSource(Vec3(2, 1, 0));
  const Vec3 pos(0, 0, -2), normal(0, 0, 1), color_diffuse(0.8, 0.4, 0.2);
  Vec3 result_color = Vec3();
  for (int i = 0; i < s.getNumLightSources(); i++) {
    const Vec3 light_vector = (s.getLightSource(i) - pos).normalize();
    const double lambert = light_vector.dot(normal);
    if (lambert > 0.0) result_color = result_color + color_diffuse * lambert;
  }
  EXPECT_VEC_NEAR(test::pixel(s), result_color, 1e-14);
}

TEST(LectureApi, ValueTypeApiAndLocationsInErrors) {
  Scene s;
  Sphere& sphere = s.add(Sphere({0, 0, 0}, -1, Vec3(1)));
  sphere.loc = FileLoc{"scene.yaml", 12, 5};
  try {
    compile(s);
    FAIL() << "negative radius accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("scene.yaml:12:5:", 0), 0u) << e.what();
    EXPECT_EQ(e.loc().line, 12);
  }
}

TEST(LectureApi, InvalidMaterialsAndSettingsAreRejected) {
  const auto rejects = [](auto&& edit) {
    Scene s;
    Material m;
    edit(s, m);
    s.add(Sphere({0, 0, 0}, 1, m));
    EXPECT_THROW(compile(s), Error);
  };
  rejects([](Scene&, Material& m) { m.transparency = 1.5; });
  rejects([](Scene&, Material& m) { m.reflectivity = -0.1; });
  rejects([](Scene&, Material& m) { m.ior = 0; });
  rejects([](Scene&, Material& m) { m.color = {1, -1, 0}; });
  rejects([](Scene&, Material& m) { m.shininess = std::nan(""); });
  rejects([](Scene& s, Material&) { s.settings.width = 0; });
  rejects([](Scene& s, Material&) { s.settings.max_depth = 0; });
  rejects([](Scene& s, Material&) { s.settings.supersample = 0; });
  rejects([](Scene& s, Material&) { s.settings.min_weight = 2; });
  rejects([](Scene& s, Material&) { s.settings.medium_ior = -1; });
  rejects([](Scene& s, Material&) { s.add(directional_light({0, 0, 0})); });
  rejects([](Scene& s, Material&) { s.add(point_light({0, std::nan(""), 0})); });
  rejects([](Scene& s, Material&) { s.add(point_light({0, 1, 0}, {1, 1, 1}, -2)); });
}

}  // namespace
}  // namespace strahl::lecture_api_test
