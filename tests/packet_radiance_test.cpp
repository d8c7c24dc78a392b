// The packet front end (render/packet_radiance.h: up to 8 or 16 samples of a pixel take their first
// step together) against the single-sample path it replaces in the tile renderer
// (pixel_sample: sample_radiance → trace): on every scene of scenes/ — spheres in one leaf, meshes
// in a BVH, solids, CSG, implicit surfaces, instances, moving shapes, area lights, glass and
// mirrors, thin lens — with every accelerator and sampler, each sample's radiance is the same bit
// for bit and so are the ray counts, for full packets and for packets with only some lanes active.

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "strahl/render/packet_radiance.h"
#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/tile_renderer.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::packet_radiance_test {
namespace {

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }
bool same_counts(const RayCounters& a, const RayCounters& b) {
  return a.camera == b.camera && a.shadow == b.shadow && a.reflection == b.reflection &&
         a.refraction == b.refraction && a.invalid_samples == b.invalid_samples && a.cut == b.cut;
}

struct Tally {
  std::uint64_t samples = 0, shadow = 0, secondary = 0, invalid = 0;
};

// Samples first … first + count − 1 of every pixel of `view` through packets of N and one by one.
template <int N>
void expect_packets_match(const SceneView& view, const PixelSampler& sampler, std::uint32_t first, int count,
                          const std::string& what, Tally& tally) {
  for (int row = 0; row < view.camera.ny; ++row) {
    for (int x = 0; x < view.camera.nx; ++x) {
      const PixelSequence p = pixel_sequence(view, sampler, x, row);
      CameraSample cs[N];
      Vec3 L[N];
      RayCounters packed;
      packet_radiance<N>(view, p, first, count, cs, L, packed);
      RayCounters single;
      for (int i = 0; i < count; ++i) {
        CameraSample c;
        const Vec3 l = pixel_sample(view, p, first + std::uint32_t(i), c, single);
        ASSERT_TRUE(same_bits(L[i], l)) << what << " N " << N << " pixel " << x << "," << row << " sample "
                                        << first + i << ": " << L[i].x << " " << L[i].y << " " << L[i].z
                                        << " vs " << l.x << " " << l.y << " " << l.z;
        ASSERT_EQ(std::memcmp(&cs[i], &c, sizeof(CameraSample)), 0) << what << " camera sample " << first + i;
      }
      ASSERT_TRUE(same_counts(packed, single)) << what << " N " << N << " pixel " << x << "," << row << ": shadow "
                                               << packed.shadow << " vs " << single.shadow;
      tally.samples += std::uint64_t(count);
      tally.shadow += single.shadow;
      tally.secondary += single.reflection + single.refraction;
      tally.invalid += single.invalid_samples;
    }
  }
}

struct Case {
  const char* file;
  SamplerKind sampler;
  int spp;
};

class PacketRadiance : public ::testing::TestWithParam<Case> {};

TEST_P(PacketRadiance, EverySampleEqualsTheSingleSamplePath) {
  const Case c = GetParam();
  Scene scene = load_scene(std::string(STRAHL_SOURCE_DIR) + "/scenes/" + c.file);
  scene.settings.width = 12;  // small, and with the scene's own aspect: the same view, coarse
  scene.settings.height = 7;
  scene.settings.integrator = IntegratorKind::Whitted;  // (the packet front end's; glow.yaml is path traced)
  Tally tally;
  for (AccelKind accel : {AccelKind::Bvh, AccelKind::KdTree, AccelKind::Octree, AccelKind::Naive}) {
    scene.settings.accel = accel;
    const RenderScene rs = compile(scene);
    const SceneView view = rs.view();
    ASSERT_TRUE(packet_radiance_supported(view)) << c.file;
    SamplingSettings sampling;
    sampling.sampler = c.sampler;
    sampling.spp = c.spp;
    sampling.seed = 7;
    const PixelSampler sampler = make_pixel_sampler(sampling);
    const std::string what = std::string(c.file) + " " + std::string(accel_name(accel));
    expect_packets_match<16>(view, sampler, 0, 16, what, tally);  // full
    expect_packets_match<16>(view, sampler, 16, 5, what, tally);  // the next round, some lanes
    expect_packets_match<8>(view, sampler, 0, 8, what, tally);
    expect_packets_match<8>(view, sampler, 3, 1, what, tally);    // one lane
  }
  EXPECT_EQ(tally.samples, 4u * 12u * 7u * (16u + 5u + 8u + 1u));
  EXPECT_GT(tally.shadow, 0u) << "no shadow ray in " << c.file;
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, PacketRadiance,
    ::testing::Values(Case{"lecture.yaml", SamplerKind::Grid, 16}, Case{"lecture-whitted.yaml", SamplerKind::Grid, 16},
                      Case{"lecture-distributed.yaml", SamplerKind::Stratified, 16},
                      Case{"whitted-1979.yaml", SamplerKind::Sobol, 16}, Case{"mesh.yaml", SamplerKind::Grid, 16},
                      Case{"shapes.yaml", SamplerKind::Random, 16}, Case{"shapes-pov.yaml", SamplerKind::Grid, 16},
                      Case{"csg.yaml", SamplerKind::Stratified, 16}, Case{"implicit.yaml", SamplerKind::Grid, 16},
                      Case{"instances.yaml", SamplerKind::Grid, 16}, Case{"motion-blur.yaml", SamplerKind::Stratified, 16},
                      Case{"depth-of-field.yaml", SamplerKind::Sobol, 16}, Case{"soft-shadows.yaml", SamplerKind::Grid, 16},
                      Case{"glossy.yaml", SamplerKind::Stratified, 16}, Case{"refraction.yaml", SamplerKind::Grid, 16},
                      Case{"spotlights.yaml", SamplerKind::Grid, 16}, Case{"textures.yaml", SamplerKind::Stratified, 16},
                      Case{"uv-mesh.yaml", SamplerKind::Grid, 4}, Case{"glow.yaml", SamplerKind::Grid, 4}),
    [](const ::testing::TestParamInfo<Case>& param) {
      std::string name = param.param.file;
      name = name.substr(0, name.find('.'));
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name;
    });

// The scenes above exercise what the packets do: mirror and glass rays after the first step.
TEST(PacketFrontEnd, WhittedSceneSpawnsSecondaryRays) {
  Scene scene = load_scene(std::string(STRAHL_SOURCE_DIR) + "/scenes/lecture-whitted.yaml");
  scene.settings.width = 12;
  scene.settings.height = 7;
  const RenderScene rs = compile(scene);
  SamplingSettings sampling;
  sampling.spp = 16;
  Tally tally;
  expect_packets_match<16>(rs.view(), make_pixel_sampler(sampling), 0, 16, "lecture-whitted", tally);
  EXPECT_GT(tally.secondary, 100u);
}

// A scene of the tests below, 16 grid samples per pixel: full packets of 16, and 5 lanes of 8.
void expect_scene_packets_match(const Scene& scene, const std::string& what, Tally& tally) {
  const RenderScene rs = compile(scene);
  ASSERT_TRUE(packet_radiance_supported(rs.view())) << what;
  SamplingSettings sampling;
  sampling.spp = 16;
  expect_packets_match<16>(rs.view(), make_pixel_sampler(sampling), 0, 16, what, tally);
  expect_packets_match<8>(rs.view(), make_pixel_sampler(sampling), 3, 5, what, tally);
}

// The lanes shade side by side where a pixel's samples meet several materials: exponents that
// differ between the lanes, a fractional and a zero exponent (std::pow, lane by lane), black
// highlights, a checkerboard, a mirror beside a matte sphere (lanes that go on into trace()),
// three lights of two kinds — each sample as it would be alone, bit for bit.
Scene mixed_materials_scene() {
  Scene scene = lecture_scene();
  scene.settings.width = 24;  // coarse pixels: many straddle two objects
  scene.settings.height = 14;
  const auto with = [](Real shininess, Real specular) {
    Material m = material_with_color(Vec3(0.6, 0.3, 0.2));
    m.shininess = shininess;
    m.specular = Vec3(specular, specular * 0.8, specular * 0.5);  // (coloured: the channels must not mix)
    return m;
  };
  scene.addSceneObject(new Sphere(Vec3(0.3, 0.3, 0.4), 0.15, with(12.5, 0.5)));
  scene.addSceneObject(new Sphere(Vec3(0.1, 0.3, 0.4), 0.12, with(0, 0.4)));
  scene.addSceneObject(new Sphere(Vec3(-0.1, 0.3, 0.4), 0.12, with(7, 0)));
  scene.addSceneObject(new Sphere(Vec3(-0.3, 0.3, 0.4), 0.12, with(100000, 0.7)));
  Material checker = with(3, 0.3);
  checker.checker_size = 0.05;
  scene.addSceneObject(new Sphere(Vec3(0.5, 0.15, 0.5), 0.15, checker));
  Material mirror = with(100, 0.6);
  mirror.reflectivity = 0.5;
  scene.addSceneObject(new Sphere(Vec3(-0.5, 0.15, 0.5), 0.15, mirror));
  return scene;
}

TEST(PacketFrontEnd, LanesOfMixedMaterialsShadeAsAlone) {
  Scene scene = mixed_materials_scene();
  scene.add(point_light(Vec3(-1, 2, 2), Vec3(0.5, 0.4, 0.3)));
  scene.add(directional_light(normalize(Vec3(0.3, -1, -0.2)), Vec3(0.2, 0.3, 0.4)));
  Tally tally;
  expect_scene_packets_match(scene, "mixed materials", tally);
  EXPECT_GT(tally.secondary, 0u);
}

// Spotlights whose cone edges cross the spheres: lanes inside, on the step and outside (no
// shadow ray there) side by side, and a fading point light — each sample as it would be alone,
// the ray counts too.
TEST(PacketFrontEnd, SpotLitLanesOfMixedMaterialsShadeAsAlone) {
  Scene scene = mixed_materials_scene();
  scene.add(spot_light(Vec3(0, 1.5, 1.5), Vec3(0.1, 0.3, 0.4) - Vec3(0, 1.5, 1.5), 4, 9, 2, Vec3(1, 0.9, 0.8), 3));
  Light faded = point_light(Vec3(-1, 2, 2), Vec3(0.2, 0.2, 0.2));
  faded.fade_distance = 1.5;  // and a fade with distance
  faded.fade_power = 2;
  scene.add(faded);
  scene.add(spot_light(Vec3(1, 1, 2), Vec3(-1, -0.5, -1), 10, 5));  // a hard edge
  Tally tally;
  expect_scene_packets_match(scene, "mixed materials, spotlights", tally);
  EXPECT_GT(tally.shadow, 0u);
}

// The same lanes under area lights (add_area_light_lanes: each lane's strata from its own stream,
// a shading point per lane) between point lights, so that the terms add up in the lights' order:
// a sphere light of 2×2 strata, a rectangle of 3×3 that some points see from behind — each sample
// as it would be alone, bit for bit, the ray counts too. (soft-shadows.yaml above has a disk.)
TEST(PacketFrontEnd, AreaLitLanesOfMixedMaterialsShadeAsAlone) {
  Scene scene = mixed_materials_scene();
  scene.add(sphere_light(Vec3(1, 1.5, 1), 0.15, Vec3(40, 35, 30), 2));
  scene.add(point_light(Vec3(-1, 2, 2), Vec3(0.5, 0.4, 0.3)));
  scene.add(rect_light(Vec3(-0.5, 0.35, -0.2), Vec3(1, 0, 0), Vec3(0, 0, 0.4), Vec3(3, 2, 1), 3));
  Tally tally;
  expect_scene_packets_match(scene, "mixed materials, area lights", tally);
  EXPECT_GT(tally.secondary, 0u);
  EXPECT_GT(tally.shadow, 50000u);
}

// A mirror floor under a mirror sphere, a glass sphere, a matte one, a checkered mirror and a
// rough one, a coloured background: most packets' lanes meet a perfect mirror first, and their
// reflected rays meet the floor, the spheres (another mirror, glass: on alone in trace() at
// depth 2), the sky or nothing.
Scene mirror_floor_scene(Real floor_reflectivity) {
  Scene scene;
  test::set_camera(scene, Vec3(0, 1.5, 3), Vec3(0, 0.2, 0), Vec3(0, 1, 0), -1, 1, -0.6, 0.6, 1.5, 20, 12);
  Material floor = test::phong(Vec3(0.3, 0.4, 0.5), 0.1, 0.5, Vec3(0.6, 0.5, 0.4), 50);
  floor.reflectivity = floor_reflectivity;
  scene.add(Plane(Vec3(0, 1, 0), 0, floor));
  Material mirror = test::phong(Vec3(0.8, 0.2, 0.2), 0, 0, Vec3(0.6), 100);
  mirror.reflectivity = 1;
  scene.add(Sphere(Vec3(-0.6, 0.4, 0), 0.4, mirror));
  Material glass = test::clear_glass(1.5);
  glass.reflectivity = 0.1;
  glass.specular = Vec3(0.6);
  glass.shininess = 100;
  scene.add(Sphere(Vec3(0.6, 0.35, 0.3), 0.35, glass));
  scene.add(Sphere(Vec3(0, 0.3, -0.8), 0.3, test::phong(Vec3(0.2, 0.8, 0.3), 0.1, 0.7, Vec3(0.5), 20)));
  Material checker = mirror;
  checker.reflectivity = 0.7;
  checker.checker_size = 0.1;
  checker.diffuse = 0.5;
  scene.add(Sphere(Vec3(0.2, 0.2, 0.9), 0.2, checker));
  Material rough = mirror;
  rough.roughness = 0.2;
  scene.add(Sphere(Vec3(-0.4, 0.15, 1.0), 0.15, rough));
  scene.add(point_light(Vec3(1, 2, 1), Vec3(1, 0.9, 0.8)));
  scene.add(directional_light(normalize(Vec3(-0.3, -1, -0.2)), Vec3(0.2, 0.3, 0.4)));
  scene.settings.background = Vec3(0.1, 0.2, 0.3);
  return scene;
}

// The lanes on mirrors and glass follow their ray trees together (packet_tree) — each sample as
// it would be alone, bit for bit, and the ray counts equal: with the recursion depth, the ray
// budget and min_weight cutting the reflected and refracted rays (or not) at every depth, and
// with materials the packets leave to trace() (rough).
TEST(PacketFrontEnd, MirrorLanesTakeTheirReflectedRaysTogether) {
  {  // The precondition: a packet of camera rays onto the mirror floor is all mirror lanes.
    const RenderScene rs = compile(mirror_floor_scene(1));
    const SceneView view = rs.view();
    PacketRays<16> r;
    for (int i = 0; i < 16; ++i) {
      const Vec3 d = normalize(Vec3(Real(i % 4) * 0.01 + 0.1, 0, Real(i / 4) * 0.01 + 1.9) - Vec3(0, 1.5, 3));
      r.ox[i] = 0, r.oy[i] = 1.5, r.oz[i] = 3, r.dx[i] = d.x, r.dy[i] = d.y, r.dz[i] = d.z, r.time[i] = 0;
    }
    r.unit = true;
    PacketStep<16> step;
    RayCounters counters;
    packet_step<16>(view, 0xffffu, r, step, counters);
    EXPECT_EQ(step.lit, 0xffffu);
    EXPECT_EQ(step.local, 0u);
    EXPECT_EQ(step.spawn, 0xffffu);
    EXPECT_EQ(counters.shadow, 32u);
  }
  struct Variant {
    const char* what;
    Real floor_reflectivity;
    int max_depth, ray_budget;
    Real min_weight;
  };
  const int budget = int(kDefaultRayBudget);
  for (const Variant v : {Variant{"defaults", 1, 8, budget, 1e-3}, Variant{"partial floor", 0.6, 8, budget, 1e-3},
                          Variant{"depth 2", 1, 2, budget, 1e-3}, Variant{"depth 3", 0.6, 3, budget, 1e-3},
                          Variant{"depth 1", 1, 1, budget, 1e-3}, Variant{"budget 0", 1, 8, 0, 1e-3},
                          Variant{"budget 1", 1, 8, 1, 1e-3}, Variant{"budget 2", 0.6, 8, 2, 1e-3},
                          Variant{"min_weight above the floor", 0.6, 8, budget, 0.65},
                          Variant{"min_weight 1", 1, 8, budget, 1}}) {
    Scene scene = mirror_floor_scene(v.floor_reflectivity);
    scene.settings.max_depth = v.max_depth;
    scene.settings.ray_budget = v.ray_budget;
    scene.settings.min_weight = v.min_weight;
    Tally tally;
    expect_scene_packets_match(scene, v.what, tally);
    // The same with a mirror triangle and a moving sphere: the BVH's packet traversal and the
    // moving shapes' lane-by-lane queries for the reflected rays.
    Material mirror = test::phong(Vec3(0.2), 0, 0.1, Vec3(0.5), 80);
    mirror.reflectivity = 0.9;
    scene.add(Triangle(Vec3(-1.2, 0, -1), Vec3(1.2, 0, -1.4), Vec3(0, 1.2, -1.2), mirror));
    Sphere moving(Vec3(0.9, 0.2, 1.2), 0.2, test::phong(Vec3(0.9, 0.9, 0.2), 0.1, 0.7, Vec3(0.4), 30));
    moving.motion = Motion::linear(Vec3(0, 0.3, 0));
    scene.add(moving);
    expect_scene_packets_match(scene, std::string(v.what) + " + triangle, moving sphere", tally);
    if (v.max_depth > 1 && v.ray_budget > 0 && v.floor_reflectivity >= v.min_weight) {  // the floor reflects
      EXPECT_GT(tally.secondary, tally.samples / 4) << v.what;
    }
  }
}

// Glass in packets: a glass sphere in front of the camera holding another (nested media), with
// Fresnel or without, filtering or clear, in a denser medium than air or not, thick enough for
// total internal reflection, beside a mirror; the budget and the depth cutting the trees
// anywhere — each sample as alone, bit for bit.
TEST(PacketFrontEnd, GlassLanesFollowTheirRayTreesTogether) {
  for (const bool fresnel : {false, true}) {
    for (const bool filter : {false, true}) {
      for (const Real medium : {Real(1), Real(1.2)}) {
        for (const int budget : {int(kDefaultRayBudget), 3, 7}) {
          for (const int depth : {8, 3, 12}) {
            Scene scene = mirror_floor_scene(0.5);
            Material glass = test::clear_glass(1.8);
            glass.reflectivity = 0.1;
            glass.fresnel = fresnel;
            glass.filter = filter;
            glass.color = Vec3(0.7, 0.8, 1.0);
            glass.specular = Vec3(0.5);
            glass.shininess = 60;
            glass.diffuse = 0.1;
            scene.add(Sphere(Vec3(0, 0.9, 1.6), 0.5, glass));
            Material inner = glass;
            inner.ior = 1.3;
            scene.add(Sphere(Vec3(0.05, 0.9, 1.6), 0.2, inner));
            scene.settings.medium_ior = medium;
            scene.settings.ray_budget = budget;
            scene.settings.max_depth = depth;
            scene.settings.width = 12;
            scene.settings.height = 8;
            const std::string what = "glass fresnel " + std::to_string(fresnel) + " filter " + std::to_string(filter) +
                                     " medium " + std::to_string(medium) + " budget " + std::to_string(budget) +
                                     " depth " + std::to_string(depth);
            Tally tally;
            expect_scene_packets_match(scene, what, tally);
            ASSERT_GT(tally.secondary, tally.samples) << what;
          }
        }
      }
    }
  }
}

// Lanes shaded side by side (no mirror, no glass) whose radiance overflows — two lights of 1e308,
// each finite, whose terms add up to infinity where both light the surface — become black and are
// counted, as guard_sample() does for the single sample, in packets of good and bad lanes.
TEST(PacketFrontEnd, OverflowingLanesAreGuardedAsAlone) {
  Scene scene;
  test::set_camera(scene, Vec3(0, 0, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), -1, 1, -1, 1, 2, 20, 20);
  scene.add(Sphere(Vec3(0, 0, 0), 1, test::phong(Vec3(1), 0, 1, Vec3(1), 10)));
  scene.add(Sphere(Vec3(0.8, 0.8, 0.5), 0.3, test::phong(Vec3(0.5), 0, 1, Vec3(0), 10)));
  scene.add(point_light(Vec3(2, 2, 4), Vec3(1), 1e308));
  scene.add(point_light(Vec3(-2, 2, 4), Vec3(1), 1e308));
  Tally tally;
  expect_scene_packets_match(scene, "overflow", tally);
  EXPECT_GT(tally.invalid, 0u);
  EXPECT_LT(tally.invalid, tally.samples / 2) << "most samples are finite: the packets mix good and bad lanes";
  EXPECT_EQ(tally.secondary, 0u) << "every lane is shaded side by side";
}

// Lanes from neighbouring pixels (packet_radiance_of, what the tile renderer uses for pixels with
// one sample each): every row in runs of N pixels, lane j taking sample j % 3 of its pixel — each
// sample's radiance bit for bit pixel_sample()'s, the ray counts equal.
template <int N>
void expect_neighbours_match(const SceneView& view, const PixelSampler& sampler, const std::string& what) {
  for (int row = 0; row < view.camera.ny; ++row) {
    for (int x0 = 0; x0 < view.camera.nx; x0 += N) {
      const int count = view.camera.nx - x0 < N ? view.camera.nx - x0 : N;
      CameraSample cs[N];
      std::uint64_t key[N];
      std::uint32_t index[N];
      Vec3 L[N];
      for (int j = 0; j < count; ++j) {
        const PixelSequence p = pixel_sequence(view, sampler, x0 + j, row);
        index[j] = std::uint32_t(j % 3);
        cs[j] = p.sample(index[j]);
        key[j] = p.stream;
      }
      RayCounters packed, single;
      FilmLanes<N> film;
      film.set(cs, count);
      packet_radiance_of<N>(view, cs, film, key, index, count, L, packed);
      for (int j = 0; j < count; ++j) {
        CameraSample c;
        const Vec3 l = pixel_sample(view, pixel_sequence(view, sampler, x0 + j, row), index[j], c, single);
        ASSERT_TRUE(same_bits(L[j], l)) << what << " N " << N << " pixel " << x0 + j << "," << row;
      }
      ASSERT_TRUE(same_counts(packed, single)) << what << " N " << N << " row " << row;
    }
  }
}

TEST(PacketFrontEnd, LanesOfNeighbouringPixelsEqualTheSingleSamplePath) {
  for (const char* file : {"lecture-whitted.yaml", "mesh.yaml", "depth-of-field.yaml", "soft-shadows.yaml"}) {
    Scene scene = load_scene(std::string(STRAHL_SOURCE_DIR) + "/scenes/" + file);
    scene.settings.width = 40;
    scene.settings.height = 23;
    const RenderScene rs = compile(scene);
    ASSERT_TRUE(packet_radiance_supported(rs.view())) << file;
    SamplingSettings sampling;
    sampling.sampler = SamplerKind::Stratified;
    sampling.spp = 4;
    const PixelSampler sampler = make_pixel_sampler(sampling);
    expect_neighbours_match<16>(rs.view(), sampler, file);
    expect_neighbours_match<8>(rs.view(), sampler, file);
  }
}

// The tile renderer (fewer than 16 samples per pixel: packets gathered across pixels, a pixel's
// samples running on from one packet into the next; 16 or more: whole packets of a pixel's own,
// the rest gathered; the Sobol and strata film, lens and shutter samples computed lane by lane in
// both) against
// pixel_sample() one sample at a time into the same film layout: the same sums, statistics and
// counts, bit for bit. per_pixel 0: every pixel its own number of samples, 0 … 20.
TEST(TileRenderer, EveryPathEqualsPixelSamplesOneByOne) {
  for (const char* file : {"lecture-whitted.yaml", "depth-of-field.yaml", "motion-blur.yaml"}) {  // (lens; shutter)
    Scene scene = load_scene(std::string(STRAHL_SOURCE_DIR) + "/scenes/" + file);
    scene.settings.width = 37;
    scene.settings.height = 21;
    const RenderScene rs = compile(scene);
    const SceneView view = rs.view();
    for (const SamplerKind kind : {SamplerKind::Adaptive, SamplerKind::Sobol, SamplerKind::Stratified, SamplerKind::Grid})
      for (const int spp : {1, 4, 16})  // (grid and stratified: strata sides 1, 2, 4)
      for (const std::uint32_t per_pixel : {1u, 3u, 16u, 0u}) {
        SamplingSettings sampling;
        sampling.sampler = kind;
        sampling.spp = spp;
        sampling.seed = 5;
        const PixelSampler sampler = make_pixel_sampler(sampling);
        const FilmLayout layout(view.camera.nx, view.camera.ny, Filter{}, kind == SamplerKind::Adaptive);
        TileWork tiled, alone;
        tiled.rect = alone.rect = TileRect{0, 0, view.camera.nx, view.camera.ny};
        const std::size_t n = tiled.rect.pixels();
        for (TileWork* w : {&tiled, &alone}) {
          layout.prepare(*w);
          w->first.resize(n);
          w->count.resize(n);
          for (int row = 0; row < view.camera.ny; ++row)
            for (int x = 0; x < view.camera.nx; ++x) {
              const std::size_t i = w->rect.index(x, row);
              w->first[i] = std::uint32_t(x + 2 * row) % 7;        // rows of samples of differing numbers
              w->count[i] = (x * row) % 5 == 1 ? 0u : per_pixel;  // and gaps in them
              if (per_pixel == 0) w->count[i] = std::uint32_t(3 * x + 5 * row) % 21;
            }
        }
        const StopToken stop;
        render_tile(view, sampler, layout, stop, tiled);
        for (int row = 0; row < view.camera.ny; ++row)
          for (int x = 0; x < view.camera.nx; ++x) {
            const std::size_t i = alone.rect.index(x, row);
            const PixelSequence p = pixel_sequence(view, sampler, x, row);
            for (std::uint32_t k = alone.first[i]; k < alone.first[i] + alone.count[i]; ++k) {
              CameraSample cs;
              const Vec3 L = pixel_sample(view, p, k, cs, alone.counters);
              layout.add_sample(alone, x, row, cs, L);
              ++alone.taken[i];
            }
          }
        const std::string what =
            std::string(file) + " " + sampler_name(kind) + " spp " + std::to_string(spp) + " " + std::to_string(per_pixel);
        EXPECT_EQ(tiled.taken, alone.taken) << what;
        ASSERT_EQ(tiled.local.size(), alone.local.size()) << what;
        EXPECT_EQ(std::memcmp(tiled.local.data(), alone.local.data(), tiled.local.size() * sizeof(double)), 0) << what;
        ASSERT_EQ(tiled.stats.size(), alone.stats.size()) << what;
        for (std::size_t i = 0; i < tiled.stats.size(); ++i) {
          ASSERT_EQ(tiled.stats[i].n, alone.stats[i].n) << what << " pixel " << i;
          ASSERT_EQ(tiled.stats[i].sum, alone.stats[i].sum) << what << " pixel " << i;
          ASSERT_EQ(tiled.stats[i].sum_sq, alone.stats[i].sum_sq) << what << " pixel " << i;
        }
        EXPECT_TRUE(same_counts(tiled.counters, alone.counters)) << what;
      }
  }
}

// More lights than a FirstHit has room for: the tile renderer keeps the single-sample path.
TEST(PacketFrontEnd, ScenesWithManyLightsAreNotPacked) {
  Scene scene = lecture_scene();
  for (int i = 0; i < kMaxPacketLights; ++i) scene.addLightSource(Vec3(i, 2, 1));
  EXPECT_FALSE(packet_radiance_supported(compile(scene).view()));
}

}  // namespace
}  // namespace strahl::packet_radiance_test
