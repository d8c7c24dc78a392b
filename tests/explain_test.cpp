// One camera sample explained (render/explain.h): the radiance and rays are the renderer's, bit
// for bit; the text follows the lecture's formulas on scenes whose answers are known.

#include <gtest/gtest.h>

#include <filesystem>

#include "strahl/render/explain.h"
#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/util/error.h"
#include "test_helpers.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Every example scene with reflections, refraction, area lights, glossy rays, the thin lens,
// motion, CSG and instances: for pixels across the image and the first and last sample of each,
// the explanation's radiance and ray counts are pixel_sample()'s (the renderer's own path).
TEST(Explain, RadianceAndRaysAreTheRenderersSample) {
  for (const char* file : {"lecture.yaml", "lecture-whitted.yaml", "refraction.yaml", "glossy.yaml", "soft-shadows.yaml",
                           "depth-of-field.yaml", "motion-blur.yaml", "csg.yaml", "instances-windmills.yaml",
                           "motion-tumble.yaml", "whitted-1979.yaml", "spotlights.yaml", "textures.yaml",
                           "uv-mesh.yaml"}) {
    Scene scene = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / file);
    scene.settings.width = 24;
    scene.settings.height = 14;
    const RenderScene rs = compile(scene);
    const SceneView s = rs.view();
    const int spp = effective_spp(rs.sampling.sampler, rs.sampling.spp);
    int checked = 0, multi = 0;
    for (int row = 0; row < 14; row += 3)
      for (int x = 1; x < 24; x += 4)
        for (const int index : {0, spp - 1}) {
          const PixelSequence p = pixel_sequence(s, make_pixel_sampler(rs.sampling), x, row);
          CameraSample cs;
          RayCounters rays;
          const Vec3 expected = pixel_sample(s, p, std::uint32_t(index), cs, rays);
          const PixelExplanation e = explain_pixel(rs, x, row, std::uint32_t(index));
          EXPECT_TRUE(e.radiance == expected) << file << " pixel " << x << "," << row << " sample " << index;
          EXPECT_EQ(e.rays.camera, rays.camera);
          EXPECT_EQ(e.rays.shadow, rays.shadow) << file << " pixel " << x << "," << row;
          EXPECT_EQ(e.rays.reflection, rays.reflection);
          EXPECT_EQ(e.rays.refraction, rays.refraction);
          EXPECT_TRUE(contains(e.text, "ray 1: camera ray, depth 1, weight 1\n")) << e.text;
          ++checked;
          multi += rays.reflection + rays.refraction > 0;
        }
    EXPECT_EQ(checked, 5 * 6 * 2) << file;
    if (std::string(file) == "soft-shadows.yaml") {  // area lights: their sum, not each sample
      const std::string t = explain_pixel(rs, 12, 10).text;
      EXPECT_TRUE(contains(t, "light 0 (rect, 4×4 samples): sampled with this sample's random numbers")) << t;
      EXPECT_TRUE(contains(t, "the area lights' samples add local − the terms above = (")) << t;
    }
    if (std::string(file) == "spotlights.yaml") {  // on the floor beside the mirror: lit by one spot
      const std::string t = explain_pixel(rs, 16, 12).text;
      EXPECT_TRUE(contains(t, "light 0 (spot at (-5, 6, 2) towards (")) << t;
      EXPECT_TRUE(contains(t, "angle 12°, falloff 20°, tightness 10")) << t;
      EXPECT_TRUE(contains(t, "outside its cone, adds 0")) << t;
      EXPECT_TRUE(contains(t, "(fade_distance 8, fade_power 2): ")) << t;
    }
    if (std::string(file) == "textures.yaml") {  // on the textured sphere
      const std::string t = explain_pixel(rs, 6, 6).text;
      EXPECT_TRUE(contains(t, "(from image texture 1)")) << t;
    }
    if (std::string(file) == "lecture-whitted.yaml") {
      EXPECT_GT(multi, 4);
    }
  }
}

// At one sample per pixel (the grid's, through the pixel centre) the image is the explained
// radiance, pixel by pixel.
TEST(Explain, TheImageAtOneSampleIsTheExplainedRadiance) {
  Scene scene = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  scene.settings.width = 16;
  scene.settings.height = 9;
  const Image image = test::render_image(scene, 2, 8);
  const RenderScene rs = compile(scene);
  for (int row = 0; row < 9; ++row)
    for (int x = 0; x < 16; ++x) {
      const Vec3 r = explain_pixel(rs, x, row).radiance;
      const Rgb& c = image.at(x, row);
      EXPECT_EQ(c.r, float(r.x));
      EXPECT_EQ(c.g, float(r.y));
      EXPECT_EQ(c.b, float(r.z));
    }
}

// A unit sphere at the origin seen from (0, 0, 5) with the light at the eye: the centre pixel's
// ray runs down −z, hits at t = 4, p = N = (0, 0, 1), N·L = N·H = 1, and the local colour is
// k_a·C + k_d·C + k_s.
Scene lit_sphere(const Material& m) {
  Scene s;
  test::set_camera(s, Vec3(0, 0, 5), Vec3(0, 0, 0), Vec3(0, 1, 0), -0.5, 0.5, -0.5, 0.5, 1, 21, 21);
  s.addSceneObject(new Sphere(Vec3(0, 0, 0), 1, m));
  s.addLightSource(Vec3(0, 0, 5));
  return s;
}

TEST(Explain, TheLecturesFormulasOnALitSphere) {
  const Material m = test::phong(Vec3(0.8, 0.4, 0.2), 0.1, 0.7, Vec3(0.5), 20);
  const RenderScene rs = compile(lit_sphere(m));
  const PixelExplanation e = explain_pixel(rs, 10, 10);
  const std::string& t = e.text;
  EXPECT_TRUE(contains(t, "film position (x, y) = (10.5, 10.5)")) << t;
  EXPECT_TRUE(contains(t, "s_u = l + (r − l)·x/n_x = 0, s_v = b + (t − b)·y/n_y = 0\n")) << t;
  EXPECT_TRUE(contains(t, "direction = normalize(s_u·u + s_v·v − d·w) = (0, 0, -1)\n")) << t;
  EXPECT_TRUE(contains(t, "hits a sphere (object id 0) at t = 4\n")) << t;
  EXPECT_TRUE(contains(t, "p = (0, 0, 1), N = (0, 0, 1) (the ray arrives at the outside)")) << t;
  EXPECT_TRUE(contains(t, "L = (0, 0, 1), N·L = 1\n")) << t;
  EXPECT_TRUE(contains(t, "the shadow ray reaches it; N·H = 1:")) << t;
  EXPECT_TRUE(contains(t, "ambient (1 − T)·k_a·C·ambient_light = (0.08, 0.04, 0.02)\n")) << t;
  EXPECT_TRUE(contains(t, "local = ambient + lights = ")) << t;
  EXPECT_VEC_NEAR(e.radiance, Vec3(0.8, 0.4, 0.2) * 0.8 + Vec3(0.5), 1e-12);
  EXPECT_EQ(e.rays.shadow, 1u);
  // Off to the side of the sphere the ray meets nothing.
  EXPECT_TRUE(contains(explain_pixel(rs, 0, 0).text, "hits nothing: the background (0, 0, 0)\n"));
  // The light behind the surface; a blocker in the shadow ray's way.
  Scene behind = lit_sphere(m);
  behind.addLightSource(Vec3(0, 0, -5));
  behind.addLightSource(Vec3(0, 3, 3));
  behind.addSceneObject(new Sphere(Vec3(0, 1.5, 2), 0.2, m));  // halfway from p to that light
  const std::string b = explain_pixel(compile(behind), 10, 10).text;
  EXPECT_TRUE(contains(b, "N·L = -1: behind the surface, adds 0\n")) << b;
  EXPECT_TRUE(contains(b, "the shadow ray is blocked: adds 0\n")) << b;
}

// The tree: a mirror's reflected ray, glass's reflected and refracted rays with their weights,
// total internal reflection where a ray inside glass meets the wall too obliquely, and max_depth.
TEST(Explain, TheRayTreeNamesEachRayAndWhyItEnds) {
  Material reflecting_glass = test::clear_glass(1.5);
  reflecting_glass.reflectivity = 0.1;
  Scene glass = lit_sphere(reflecting_glass);
  const PixelExplanation g = explain_pixel(compile(glass), 10, 10);
  EXPECT_TRUE(contains(g.text, "ray 1.R: reflected ray, depth 2")) << g.text;
  EXPECT_TRUE(contains(g.text, "ray 1.T: refracted ray, depth 2")) << g.text;
  EXPECT_TRUE(contains(g.text, "(the ray arrives from inside: N turned towards it)")) << g.text;
  EXPECT_TRUE(contains(g.text, "refraction n_1 = 1 → n_2 = 1.5: cos θ_1 = −d·N = 1, sin θ_2 = (n_1/n_2)·sin θ_1 = 0\n"))
      << g.text;
  EXPECT_TRUE(contains(g.text, "refraction n_1 = 1.5 → n_2 = 1: cos θ_1 = −d·N = 1,")) << g.text;
  EXPECT_TRUE(contains(g.text, "ray 1 brings ")) << g.text;

  // From inside a glass sphere (centre (0.9, 0, 0), radius 1) the ray down −z meets the wall at
  // cos θ = 0.436 (θ ≈ 64°, beyond the critical angle asin(1/1.5) ≈ 41.8°).
  Scene inside;
  test::set_camera(inside, Vec3(0, 0, 0), Vec3(0, 0, -1), Vec3(0, 1, 0), -0.5, 0.5, -0.5, 0.5, 1, 21, 21);
  inside.addSceneObject(new Sphere(Vec3(0.9, 0, 0), 1, test::clear_glass(1.5)));
  inside.addLightSource(Vec3(0, 5, 0));
  const std::string tir = explain_pixel(compile(inside), 10, 10).text;
  EXPECT_TRUE(contains(tir, "refraction n_1 = 1.5 → n_2 = 1: cos θ_1 = −d·N = 0.43589, sin θ_2 = (n_1/n_2)·sin θ_1 = "
                            "1.35 > 1\n")) << tir;
  EXPECT_TRUE(contains(tir, "(total internal reflection: T moved to k_r)")) << tir;
  EXPECT_FALSE(contains(tir, "ray 1.T:")) << tir;

  Scene mirror = lit_sphere(test::mirror(1));
  mirror.settings.max_depth = 1;
  const std::string shallow = explain_pixel(compile(mirror), 10, 10).text;
  EXPECT_TRUE(contains(shallow, "= local (max_depth 1 reached: no further rays)")) << shallow;
  EXPECT_FALSE(contains(shallow, "ray 1.R")) << shallow;
}

// What a ray hits inside an instance is named by its group; the compiler's own groups (a group's
// moving shape, a turning mesh) by what they hold.
TEST(Explain, NamesTheShapesInInstances) {
  const std::string camera = "camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 40, shutter: [0, 1]}\n"
                             "render: {width: 21, height: 21}\nlights: [{type: point, position: [0, 0, 5]}]\n";
  const auto centre = [&](const std::string& rest) {
    return explain_pixel(compile(parse_scene(camera + rest, "t.yaml", ".")), 10, 10).text;
  };
  const std::string placed = centre(
      "groups:\n  ball: [{type: box, corners: [[-2, -2, -2], [-1, -1, -1]]}, {type: sphere, center: [0, 0, 0], "
      "radius: 1}]\nobjects: [{type: instance, of: ball}]\n");
  EXPECT_TRUE(contains(placed, "hits a sphere of group 'ball', in instance record 0 (object id 1) at t = 4\n")) << placed;
  const std::string moving = centre(
      "groups:\n  ball: [{type: sphere, center: [0, 0, 0], radius: 1, motion: {velocity: [0, 0, 0.1]}}]\n"
      "objects: [{type: instance, of: ball}]\n");
  EXPECT_TRUE(contains(moving, "hits a sphere moving in its group, in moving instance record 0")) << moving;
  const std::string turning = centre(
      "objects: [{type: triangle, vertices: [[-1, -1, 0], [1, -1, 0], [0, 1, 0]], motion: {spin: {axis: [0, 0, 1], "
      "angle: 10}}}]\n");
  EXPECT_TRUE(contains(turning, "hits a triangle that turns, in moving instance record 0 (object id 0) at t = 5\n"))
      << turning;
}

TEST(Explain, APixelOutsideTheImageIsAnError) {
  const RenderScene rs = compile(lit_sphere(Material{}));
  EXPECT_THROW(explain_pixel(rs, 21, 0), Error);
  EXPECT_THROW(explain_pixel(rs, 0, -1), Error);
}

}  // namespace
}  // namespace strahl
