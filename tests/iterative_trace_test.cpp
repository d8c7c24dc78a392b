// The iterative integrator (render/whitted.h: one loop over an explicit stack of pending hits,
// the code the GPU runs too) against the recursive formulation it replaced, kept here as the
// reference: on random scenes of mirrors, clear, filtering, rough and nested glass, area and
// point lights, every max_depth, min_weight and ray budget, both give the same radiance bit for
// bit, the same ray counts (cuts included) and draw the same random numbers.

#include <gtest/gtest.h>

#include <cstring>

#include "strahl/render/pixel.h"
#include "test_helpers.h"
#include "test_random.h"

namespace strahl::iterative_trace_test {
namespace {

// Lecture 2.5's recursion, as render/whitted.h had it before it became a loop.
Vec3 recursive_trace(const SceneView& s, const Ray& ray, int depth, Real weight, const MediumStack& media,
                     RayCounters& counters, SampleStream& rng, std::uint32_t& budget) {
  const Hit hit = closest_hit(s, ray, 0, kInfinity);
  if (s.area_light_count > 0) {
    const int emitter = nearest_emitter(s, ray, hit.t);
    if (emitter >= 0) return s.lights[emitter].radiance;
  }
  if (!hit.found()) return s.settings.background;

  const SurfacePoint sp = surface_at(s, ray, hit);
  const Material& m = s.materials[sp.material];
  const bool front = dot(ray.direction, sp.geometric_normal) < 0;
  const Vec3 n = front ? sp.normal : -sp.normal;
  const Vec3 view = -ray.direction;

  Vec3 color = local_illumination(s, sp, n, view, counters, rng);
  if (depth >= s.settings.max_depth) return color;

  Real kr = m.reflectivity;
  Real kt = m.transparency;
  Vec3 refracted_dir;
  MediumStack next_media = media;
  if (kt > 0) {
    const Real n1 = front ? media.current() : m.ior;
    const Real n2 = front ? m.ior : media.outer();
    if (!refract(ray.direction, n, n1 / n2, refracted_dir)) {
      kr += kt;
      kt = 0;
    } else {
      if (m.fresnel) {
        const Real f = schlick(dot(view, n), n1, n2);
        kr += kt * f;
        kt *= 1 - f;
      }
      if (front) next_media.enter(m.ior); else next_media.leave();
    }
  }
  if (kr > 0 && kr * weight >= s.settings.min_weight && spend(budget, counters)) {
    ++counters.reflection;
    Vec3 dir = reflect(ray.direction, n);
    if (m.roughness > 0) dir = glossy_direction(dir, sp.geometric_normal, m.roughness, rng.next2());
    const Ray r = spawn_ray(sp, dir, ray.time);
    color += recursive_trace(s, r, depth + 1, weight * kr, media, counters, rng, budget) * kr;
  }
  if (kt > 0 && kt * weight >= s.settings.min_weight && spend(budget, counters)) {
    ++counters.refraction;
    if (m.roughness > 0) refracted_dir = glossy_direction(refracted_dir, sp.geometric_normal, m.roughness, rng.next2());
    const Ray r = spawn_ray(sp, refracted_dir, ray.time);
    const Vec3 tint = m.filter ? m.color : Vec3(1);
    color += recursive_trace(s, r, depth + 1, weight * kt, next_media, counters, rng, budget) * tint * kt;
  }
  return color;
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }
bool same_counts(const RayCounters& a, const RayCounters& b) {
  return a.camera == b.camera && a.shadow == b.shadow && a.reflection == b.reflection &&
         a.refraction == b.refraction && a.invalid_samples == b.invalid_samples && a.cut == b.cut;
}

Material random_material(test::Random& r) {
  Material m;
  m.color = {r.uniform(0.2, 1), r.uniform(0.2, 1), r.uniform(0.2, 1)};
  m.ambient = r.uniform(0, 0.2);
  m.diffuse = r.uniform(0, 0.8);
  m.specular = Vec3(r.uniform(0, 0.8));
  m.shininess = r.coin() ? 50 : r.uniform(1, 300);
  switch (r.below(4)) {
    case 0: break;                                        // opaque
    case 1: m.reflectivity = r.uniform(0.2, 1); break;    // mirror
    case 2: m.transparency = r.uniform(0.5, 1); break;    // glass
    default:                                              // both: a branching ray tree
      m.reflectivity = r.uniform(0.1, 0.6);
      m.transparency = r.uniform(0.1, 1 - m.reflectivity);
  }
  m.ior = r.coin() ? r.uniform(1.05, 2.5) : r.uniform(0.6, 1);
  m.fresnel = r.coin();
  m.filter = r.coin();
  if (r.below(3) == 0) m.roughness = r.uniform(0.01, 0.3);
  return m;
}

Scene random_scene(test::Random& r) {
  Scene s;
  s.camera.position = r.coin() ? Vec3(0, 0.5, 4) : Vec3(0, 0, 0);  // outside, or inside the shells
  s.camera.look_at = {r.uniform(-0.3, 0.3), r.uniform(-0.3, 0.3), -1};
  s.camera.fov_degrees = 60;
  s.settings.width = 12;
  s.settings.height = 9;
  s.settings.max_depth = std::array{1, 2, 3, 5, 8, 20, 64}[r.below(7)];
  s.settings.min_weight = std::array{0.0, 1e-4, 1e-3, 0.05}[r.below(4)];
  s.settings.ray_budget = std::array{0, 1, 3, 17, 200, int(kDefaultRayBudget)}[r.below(6)];
  s.settings.medium_ior = r.coin() ? 1 : 1.33;
  s.settings.background = {0.2, 0.3, 0.4};
  s.add(Plane({0, 1, 0}, -1, random_material(r)));
  for (int i = 0, n = 3 + r.below(6); i < n; ++i)
    s.add(Sphere(r.point(-1.5, 1.5) - Vec3(0, 0, 1.5), r.uniform(0.2, 0.8), random_material(r)));
  // Nested shells around the camera at the origin: more levels than the medium stack holds.
  for (int i = 0, n = r.below(11); i < n; ++i) s.add(Sphere({0, 0, 0}, 3 + 0.3 * i, random_material(r)));
  s.add(point_light({2, 3, 2}, Vec3(r.uniform(0.5, 1))));
  if (r.coin()) s.add(rect_light({-1, 2.5, -2}, {2, 0, 0}, {0, 0, 1}, Vec3(1.5), 1 + r.below(3)));
  if (r.coin()) s.add(sphere_light({1.5, 1.5, -1}, 0.3, Vec3(2), 2));
  return s;
}

TEST(IterativeTrace, EqualsTheRecursiveIntegratorBitForBit) {
  test::Random r(20261202);
  std::uint64_t secondary = 0, cut = 0, budgets_spent = 0;
  for (int scene = 0; scene < 60; ++scene) {
    const Scene description = random_scene(r);
    const RenderScene rs = compile(description);
    const SceneView view = rs.view();
    SamplingSettings sampling;
    sampling.sampler = SamplerKind::Stratified;
    sampling.spp = 4;
    const PixelSampler sampler = make_pixel_sampler(sampling);
    for (int row = 0; row < view.camera.ny; ++row) {
      for (int x = 0; x < view.camera.nx; ++x) {
        const PixelSequence p = pixel_sequence(view, sampler, x, row);
        for (std::uint32_t i = 0; i < 4; ++i) {
          const Ray ray = view.camera.generate_ray(p.sample(i));
          RayCounters ci, cr;
          SampleStream ri{p.stream, i}, rr{p.stream, i};
          const Vec3 iterative = trace(view, ray, ci, ri);
          std::uint32_t budget = view.settings.ray_budget;
          const Vec3 recursive =
              recursive_trace(view, ray, 1, Real(1), MediumStack(view.settings.medium_ior), cr, rr, budget);
          ASSERT_TRUE(same_bits(iterative, recursive))
              << "scene " << scene << " pixel " << x << "," << row << " sample " << i << ": " << iterative.x
              << " " << iterative.y << " " << iterative.z << " vs " << recursive.x << " " << recursive.y << " "
              << recursive.z;
          ASSERT_TRUE(same_counts(ci, cr)) << "scene " << scene << " pixel " << x << "," << row;
          ASSERT_EQ(ri.dimension, rr.dimension) << "random numbers drawn, scene " << scene;
          secondary += cr.reflection + cr.refraction;
          cut += cr.cut;
          budgets_spent += cr.reflection + cr.refraction == view.settings.ray_budget && cr.cut > 0;
        }
      }
    }
  }
  // The scenes exercise what they are meant to: deep trees, cuts, budgets spent to the last ray.
  EXPECT_GT(secondary, 100000u);
  EXPECT_GT(cut, 1000u);
  EXPECT_GT(budgets_spent, 100u);
}

// At max_depth 64 a chain of 63 mirror bounces fills the explicit stack to its last frame.
TEST(IterativeTrace, FillsTheStackAtMaxDepth64) {
  Scene s;
  test::one_ray_camera(s, {0, 0, 0}, {0, 0, -1});
  Material mirror = test::mirror(0.99, Vec3(0.01));
  mirror.ambient = 1;
  s.add(Plane({0, 0, 1}, -1, mirror));  // z = −1, facing +z
  s.add(Plane({0, 0, -1}, -1, mirror)); // z = +1, facing −z
  s.settings.max_depth = 64;
  s.settings.min_weight = 0;
  RayCounters counters;
  const Vec3 c = test::pixel(s, 0, 0, &counters);
  EXPECT_EQ(counters.reflection, 63u);
  // Σ_{k=0}^{63} 0.99^k · 0.01 (ambient k_a·C with C = 0.01, no lights): the geometric series.
  EXPECT_NEAR(c.x, 0.01 * (1 - std::pow(0.99, 64)) / (1 - 0.99), 1e-12);
}

// Undoing enter() and leave() in reverse order restores every earlier state exactly, also
// where enter() on a full stack replaced its innermost medium.
TEST(IterativeTrace, MediumStackUndoRestoresEveryState) {
  test::Random r(7);
  for (int trial = 0; trial < 200; ++trial) {
    MediumStack m(1.0 + r.uniform());
    MediumStack states[40] = {m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m,
                              m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m, m};
    MediumStack::Undo undo[40];
    const int steps = 1 + r.below(40);
    for (int i = 0; i < steps; ++i) {
      states[i] = m;
      undo[i] = r.below(3) != 0 ? m.enter(r.uniform(1, 3)) : m.leave();
    }
    for (int i = steps - 1; i >= 0; --i) {
      m.undo(undo[i]);
      ASSERT_EQ(m.size, states[i].size);
      ASSERT_EQ(std::memcmp(m.ior, states[i].ior, sizeof(m.ior)), 0) << "trial " << trial << " step " << i;
    }
  }
}

}  // namespace
}  // namespace strahl::iterative_trace_test
