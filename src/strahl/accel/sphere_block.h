#pragma once
// Spheres eight at a time, for scenes whose bounded primitives are a handful of spheres tested one
// by one (the lecture's five: the BVH is a single leaf, or the naive loop). A ray's discriminant
// (the half-chord² of kernel::intersect) is computed for eight spheres in one pass of straight-line
// arithmetic, which the compiler turns into SIMD; the spheres whose discriminant is negative —
// most of them, for most rays — then cost a lane each instead of a call each. The spheres left are
// tested by kernel::intersect / kernel::crossings themselves, in id order, so every answer is the
// one-by-one loop's, bit for bit: a lane's discriminant is computed with exactly the operations
// of kernel::intersect (no contraction: -ffp-contract=off, nvcc --fmad=false), and a sphere whose
// discriminant is negative or NaN has no root there either.

#include <cstdint>
#include <vector>

#include "strahl/geometry/sphere.h"

namespace strahl {

inline constexpr int kSphereBlockWidth = 8;

// Structure of arrays: centres and radius² of eight spheres; unused lanes have radius² = −1.
struct SphereBlock {
  Real cx[kSphereBlockWidth], cy[kSphereBlockWidth], cz[kSphereBlockWidth], r2[kSphereBlockWidth];
};

// Bit k set: the ray's line passes within sphere k's radius (discriminant ≥ 0).
STRAHL_HOST_DEVICE inline unsigned sphere_block_candidates(const SphereBlock& b, const Ray& ray) {
  const Vec3 o = ray.origin, d = ray.direction;
  Real disc[kSphereBlockWidth];
  for (int k = 0; k < kSphereBlockWidth; ++k) {
    // kernel::intersect's f = o − c, b = −dot(f, d), l = f + d·b, r² − dot(l, l).
    const Real fx = o.x - b.cx[k], fy = o.y - b.cy[k], fz = o.z - b.cz[k];
    const Real t = -(fx * d.x + fy * d.y + fz * d.z);
    const Real lx = fx + d.x * t, ly = fy + d.y * t, lz = fz + d.z * t;
    disc[k] = b.r2[k] - (lx * lx + ly * ly + lz * lz);
  }
  unsigned mask = 0;
  for (int k = 0; k < kSphereBlockWidth; ++k) mask |= unsigned(disc[k] >= 0) << k;
  return mask;
}

// The blocks of spheres 0 … count − 1 (host).
inline std::vector<SphereBlock> build_sphere_blocks(const kernel::Sphere* spheres, std::uint32_t count) {
  std::vector<SphereBlock> blocks((count + kSphereBlockWidth - 1) / kSphereBlockWidth);
  for (SphereBlock& b : blocks)
    for (int k = 0; k < kSphereBlockWidth; ++k) b.cx[k] = b.cy[k] = b.cz[k] = 0, b.r2[k] = -1;
  for (std::uint32_t i = 0; i < count; ++i) {
    SphereBlock& b = blocks[i / kSphereBlockWidth];
    const int k = int(i % kSphereBlockWidth);
    b.cx[k] = spheres[i].center.x;
    b.cy[k] = spheres[i].center.y;
    b.cz[k] = spheres[i].center.z;
    b.r2[k] = spheres[i].radius * spheres[i].radius;
  }
  return blocks;
}

}  // namespace strahl
