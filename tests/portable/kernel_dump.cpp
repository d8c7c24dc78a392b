// Prints what the kernel code answers, bit for bit, on the cross-check scenes: every ray's nearest
// hit (primitive, t, barycentrics), occlusion and surface crossings through the wide BVH, every
// pixel of small renders of the scene files, and the film's wide-filter sums. Compiled twice (tests/CMakeLists.txt): as the
// CPU builds it (the AVX paths of accel/wide_bvh.h and accel/triangle_block.h where the host has
// AVX2) and with STRAHL_PORTABLE_KERNELS (their portable scalar paths, which the GPU runs). The
// test portable_kernels_match runs both and demands identical output.
//
// Only inline kernel code is called from here (nearest_hit, occluded, for_each_crossing,
// render_pixel), so each executable runs the path this file was compiled with: this object comes
// first on the link line, and its copies of those functions are the ones every caller gets.
//
//   strahl_kernel_dump_simd|strahl_kernel_dump_portable <source dir>  > dump.txt

#include <bit>
#include <cinttypes>
#include <cmath>
#include <limits>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/accel/packet.h"
#include "../shape_soup.h"
#include "strahl/render/film.h"
#include "strahl/render/film_sample.h"
#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"

namespace strahl {
namespace {

std::uint64_t bits(Real x) { return std::bit_cast<std::uint64_t>(x); }

using Soup = test::ShapeSoup;

// Awkward on purpose: duplicated, needle-thin and axis-aligned triangles on a lattice (shared
// edges and vertices, triangles in the planes a builder splits at), overlapping spheres.
Soup awkward_soup(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> lattice(-8, 8);
  Soup s;
  for (int i = 0; i < count; ++i) {
    const Vec3 p{u(rng) * 4, u(rng) * 4, u(rng) * 4};
    switch (i % 5) {
      case 0: s.triangle(p, p + Vec3{u(rng), u(rng), u(rng)} * 0.5, p + Vec3{u(rng), u(rng), u(rng)} * 0.5); break;
      case 1: {  // axis-aligned, on lattice coordinates
        const Real z = lattice(rng) * 0.5, x = lattice(rng) * 0.5, y = lattice(rng) * 0.5;
        s.triangle({x, y, z}, {x + 0.5, y, z}, {x, y + 0.5, z});
        s.triangle({x + 0.5, y + 0.5, z}, {x, y + 0.5, z}, {x + 0.5, y, z});  // shares the diagonal
        break;
      }
      case 2: s.triangle(p, p + Vec3{1e-7, 0, 0}, p + Vec3{u(rng), u(rng), u(rng)}); break;  // needle
      case 3: s.triangles.push_back(s.triangles.back()); break;                              // duplicate
      case 4:
        if (i % 15 == 4) s.spheres.push_back({p, 0.05 + 0.3 * (u(rng) + 1), 0});
        break;
    }
  }
  return s;
}

// Rays from everywhere: random, axis-parallel with ±0 components, at vertices and edge
// midpoints, starting inside the soup.
std::vector<Ray> awkward_rays(const Soup& s, std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Ray r;
    r.origin = Vec3{u(rng), u(rng), u(rng)} * (i % 2 ? 6.0 : 3.0);
    Vec3 d{u(rng), u(rng), u(rng)};
    switch (i % 6) {
      case 1: d = {i % 4 == 1 ? 0.0 : -0.0, i % 3 ? 1.0 : -1.0, 0.0}; break;
      case 2: d = {0.0, -0.0, i % 4 == 2 ? 1.0 : -1.0}; break;
      case 3:
        if (!s.triangles.empty()) {
          const kernel::Triangle& t = s.triangles[std::size_t(i) % s.triangles.size()];
          d = (i % 12 == 3 ? t.v0 : (t.v0 + t.v1) * 0.5) - r.origin;
        }
        break;
      default: break;
    }
    if (length(d) == 0) d = {1, 0, 0};
    r.direction = normalize(d);
    rays.push_back(r);
  }
  return rays;
}

// The packet queries (accel/packet.h) on consecutive runs of N rays, every third lane off.
template <int N>
void dump_packets(const AccelView& a, const std::vector<Ray>& rays) {
  std::printf("# packets of %d\n", N);
  for (std::size_t first = 0; first + N <= rays.size(); first += N) {
    const std::uint32_t active = ((1u << N) - 1) & ~(first % 3 == 0 ? 0x4924u : 0u);
    Real t_min[N], t_max[N];
    for (int i = 0; i < N; ++i) {
      t_min[i] = 1e-9;
      t_max[i] = i % 4 == 3 ? 2.0 : kInfinity;
    }
    NearestHit out[N];
    nearest_hit_packet<N>(a, active, rays.data() + first, t_min, t_max, out);
    const std::uint32_t occ = occluded_packet<N>(a, active, rays.data() + first, t_min, t_max);
    for (int i = 0; i < N; ++i)
      if ((active >> i) & 1u)
        std::printf("p%d %zu %u %016" PRIx64 " %016" PRIx64 " %016" PRIx64 " o%u\n", N, first + std::size_t(i),
                    out[i].hit.t < kInfinity ? out[i].prim : ~0u, bits(out[i].hit.t), bits(out[i].hit.b1),
                    bits(out[i].hit.b2), (occ >> i) & 1u);
  }
}

void dump_queries(const char* name, const AccelView& a, const std::vector<Ray>& rays) {
  std::printf("# %s: %u primitives, %zu rays%s\n", name, a.prims.size(), rays.size(),
              a.sphere_quads != nullptr ? ", one leaf of sphere quads" : "");
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i];
    const NearestHit h = nearest_hit(a, ray, 1e-9, kInfinity);
    std::printf("%zu %u %016" PRIx64 " %016" PRIx64 " %016" PRIx64, i, h.hit.t < kInfinity ? h.prim : ~0u,
                bits(h.hit.t), bits(h.hit.b1), bits(h.hit.b2));
    const Real t_far = h.hit.t < kInfinity ? h.hit.t * 1.5 : 20.0;
    std::printf(" o%d", occluded(a, ray, 1e-9, t_far) ? 1 : 0);
    auto cross = [&](std::uint32_t prim, int n) {
      std::printf(" %u:%d", prim, n);
      return false;
    };
    for_each_crossing(a, ray, 1e-9, t_far, cross);
    std::printf("\n");
  }
  dump_packets<8>(a, rays);
  dump_packets<16>(a, rays);
}

void dump_render(const std::string& path, int width, int height, AccelKind kind = AccelKind::Bvh, int spp = 0) {
  Scene scene = load_scene(path);
  if (spp > 0) scene.settings.sampling.spp = spp;
  scene.settings.width = width;
  scene.settings.height = height;
  scene.settings.accel = kind;
  const RenderScene rs = compile(scene);
  const SceneView view = rs.view();
  std::printf("# render %s: %dx%d, %d spp, %s, %s\n", path.substr(path.rfind('/') + 1).c_str(), width, height,
              effective_spp(rs.sampling.sampler, rs.sampling.spp), std::string(accel_name(kind)).c_str(),
              view.accel.one_leaf ? "one leaf" : "tree");
  RayCounters counters;
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) {
      const Vec3 c = render_pixel(view, x, row, rs.sampling, counters);
      std::printf("%d %d %016" PRIx64 " %016" PRIx64 " %016" PRIx64 "\n", x, row, bits(c.x), bits(c.y), bits(c.z));
    }
  std::printf("# rays %" PRIu64 "\n", counters.total());
}

// The film's wide-filter arithmetic (render/film_sample.h: film_to_fixed4 in AVX or scalar, as the
// GPU runs it): every filter at several radii, random samples near and at the image's edges with
// radiance in and far beyond the fixed-point clamp, negative, zero and NaN; every pixel's sums.
void dump_film() {
  constexpr int width = 24, height = 16;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (const FilterKind kind : {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian, FilterKind::Mitchell})
    for (const Real radius : {Real(0.5), Real(1), Real(1.5), Real(2.7), Real(4)}) {
      const FilmParams f = FilmLayout(width, height, Filter{kind, radius}, false).params();
      std::vector<std::int64_t> fixed(std::size_t(width) * height * 4, 0);
      for (int i = 0; i < 3000; ++i) {
        const int x = int(u(rng) * width), row = int(u(rng) * height);
        CameraSample cs;
        cs.film_x = x + u(rng);
        cs.film_y = (height - 1 - row) + u(rng);
        const double big = i % 50 == 0 ? 1e7 : 1.0;
        Vec3 L{(u(rng) - 0.1) * big, u(rng), i % 7 == 0 ? 0.0 : u(rng) * 3};
        if (i == 1234) L.y = std::numeric_limits<double>::quiet_NaN();
        // Added modulo 2^64: the NaN sample's INT64_MIN would overflow a signed sum (the renderer
        // never passes a NaN to the film: bad samples are black, tests/invalid_sample_test.cpp).
        film_add_wide(f, x, row, cs, L, fixed.data(), 0, 0, width, [](std::int64_t* p, std::int64_t v) {
          *p = std::int64_t(std::uint64_t(*p) + std::uint64_t(v));
        });
      }
      std::printf("# film %s r %g\n", std::string(filter_name(kind)).c_str(), radius);
      for (std::size_t p = 0; p < fixed.size(); p += 4)
        std::printf("%zu %" PRId64 " %" PRId64 " %" PRId64 " %" PRId64 "\n", p / 4, fixed[p], fixed[p + 1], fixed[p + 2],
                    fixed[p + 3]);
    }
}

}  // namespace
}  // namespace strahl

int main(int argc, char** argv) {
  using namespace strahl;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <strahl source dir>\n", argv[0]);
    return 1;
  }
#if defined(STRAHL_WIDE_BVH_AVX) && defined(STRAHL_TRIANGLE_BLOCK_AVX) && defined(STRAHL_SPHERE_QUAD_AVX) && \
    defined(STRAHL_FILM_AVX)
  std::fprintf(stderr, "kernel path: avx\n");
#elif !defined(STRAHL_WIDE_BVH_AVX) && !defined(STRAHL_TRIANGLE_BLOCK_AVX) && !defined(STRAHL_SPHERE_QUAD_AVX) && \
    !defined(STRAHL_FILM_AVX)
  std::fprintf(stderr, "kernel path: portable\n");
#else
  std::fprintf(stderr, "kernel path: mixed\n");
#endif
  const std::string dir = argv[1];
  try {
    for (const auto& [seed, count] : {std::pair<std::uint64_t, int>{1, 40}, {2, 600}, {3, 6000}}) {
      const Soup soup = awkward_soup(seed, count);
      const Accel accel = build_accel(AccelKind::Bvh, soup.set());
      const std::string name = "soup " + std::to_string(seed);
      dump_queries(name.c_str(), accel.view(soup.set()), awkward_rays(soup, seed + 100, 3000));
    }
    // The kd-tree and the octree (the GPU walks them too): their leaves' triangle blocks.
    for (const AccelKind kind : {AccelKind::KdTree, AccelKind::Octree}) {
      const Soup soup = awkward_soup(2, 600);
      const Accel accel = build_accel(kind, soup.set());
      const std::string name = "soup 2, " + std::string(accel_name(kind));
      dump_queries(name.c_str(), accel.view(soup.set()), awkward_rays(soup, 102, 3000));
    }
    // Spheres only, few enough for one leaf (the sphere quads of geometry/sphere_quad.h):
    // overlapping, nested and touching, rays from inside them too.
    for (const int count : {3, 4, 7}) {
      Soup spheres;
      std::mt19937_64 rng{std::uint64_t(count)};
      std::uniform_real_distribution<double> u(-1, 1);
      for (int i = 0; i < count; ++i)
        spheres.spheres.push_back({Vec3{u(rng), u(rng), u(rng)} * 2.0, 0.4 + 0.6 * (u(rng) + 1), 0});
      spheres.spheres.push_back({spheres.spheres[0].center, spheres.spheres[0].radius * 0.5, 0});  // nested
      const Accel accel = build_accel(AccelKind::Bvh, spheres.set());
      const std::string name = "spheres " + std::to_string(count + 1);
      dump_queries(name.c_str(), accel.view(spheres.set()), awkward_rays(spheres, std::uint64_t(count) + 200, 2000));
    }
    for (const char* scene : {"lecture.yaml", "lecture-whitted.yaml", "lecture-distributed.yaml", "mesh.yaml",
                              "glossy.yaml", "motion-blur.yaml", "soft-shadows.yaml"})
      dump_render(dir + "/scenes/" + scene, 40, 30);
    for (const AccelKind kind : {AccelKind::KdTree, AccelKind::Octree}) dump_render(dir + "/scenes/mesh.yaml", 40, 30, kind);
    dump_render(dir + "/scenes/instances.yaml", 40, 30);  // the two-level hierarchy the GPU walks too
    // The path tracer (render/path_tracer.h), whose area light samples go one by one on the GPU.
    dump_render(dir + "/scenes/cornell-box-path.yaml", 40, 30, AccelKind::Bvh, 16);
    dump_render(dir + "/scenes/glow.yaml", 40, 30, AccelKind::Bvh, 4);  // emitting materials
    dump_film();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
