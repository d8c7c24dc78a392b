#include "rays.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace strahl::bench {

namespace {

// SplitMix64: a small, good 64-bit mixer; enough for one pixel's two numbers.
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Real uniform(std::uint64_t& state) { return Real(splitmix64(state) >> 11) * 0x1.0p-53; }

// A direction about the unit normal n with density cos θ / π (Malley: a uniform disc point
// lifted onto the hemisphere), in the branchless orthonormal basis of Duff et al. (2017).
Vec3 cosine_direction(const Vec3& n, Real u1, Real u2) {
  const Real sign = std::copysign(Real(1), n.z);
  const Real a = -1 / (sign + n.z);
  const Real b = n.x * n.y * a;
  const Vec3 t(1 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const Vec3 s(b, sign + n.y * n.y * a, -n.y);
  const Real r = std::sqrt(u1), phi = 2 * kPi * u2;
  const Real z = std::sqrt(std::fmax(Real(0), 1 - u1));
  return normalize(t * (r * std::cos(phi)) + s * (r * std::sin(phi)) + n * z);
}

}  // namespace

BenchRays make_rays(const BenchScene& scene, const AccelView& reference, std::uint64_t seed) {
  const Camera& cam = scene.camera;
  const std::size_t width = std::size_t(cam.nx), height = std::size_t(cam.ny), pixels = width * height;
  BenchRays out;
  out.width = cam.nx;
  out.height = cam.ny;
  out.primary.rays.resize(pixels);
  out.secondary_of_pixel.assign(pixels, kNoRay);
  std::vector<Ray> incoherent(pixels), shadow(pixels);
  std::vector<Real> shadow_t(pixels);
  std::vector<std::uint8_t> hit(pixels);
  const PrimitiveSet& prims = reference.prims;

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, height), [&](const auto& rows) {
    for (std::size_t row = rows.begin(); row != rows.end(); ++row) {
      for (std::size_t x = 0; x < width; ++x) {
        const std::size_t pixel = row * width + x;
        const Ray ray = cam.generate_ray(Real(x) + Real(0.5), Real(height - 1 - row) + Real(0.5));
        out.primary.rays[pixel] = ray;
        const NearestHit h = nearest_hit(reference, ray, 0, kInfinity);
        hit[pixel] = h.hit.t < kInfinity;
        if (!hit[pixel]) continue;
        const Vec3 p = ray.at(h.hit.t);
        Vec3 n = prims.is_sphere(h.prim) ? kernel::normal_at(prims.spheres[h.prim], p)
                                         : kernel::geometric_normal(prims.triangles[h.prim - prims.sphere_count]);
        if (dot(n, ray.direction) > 0) n = -n;  // the side the ray arrived from
        std::uint64_t state = seed ^ (std::uint64_t(pixel) * 0xD1B54A32D192ED03ull);
        const Real u1 = uniform(state), u2 = uniform(state);
        incoherent[pixel] = spawn_ray(p, n, cosine_direction(n, u1, u2));
        const Vec3 to_light = scene.light - p;
        const Real distance = length(to_light);
        shadow[pixel] = spawn_ray(p, n, to_light / distance);
        shadow_t[pixel] = distance;
      }
    }
  });
  for (std::size_t i = 0; i < pixels; ++i) {
    if (!hit[i]) continue;
    out.secondary_of_pixel[i] = std::uint32_t(out.shadow.rays.size());
    out.incoherent.rays.push_back(incoherent[i]);
    out.shadow.rays.push_back(shadow[i]);
    out.shadow.t_max.push_back(shadow_t[i]);
  }
  return out;
}

}  // namespace strahl::bench
