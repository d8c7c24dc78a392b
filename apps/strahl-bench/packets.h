#pragma once
// Coherent packets: the primary rays of a tile of pixels (8 rays = 4×2 pixels, 16 = 4×4) and the
// shadow rays from those pixels' hits, traced together by a structure's packet query (strahl's
// BVH: wide_bvh_packet.h; Embree: rtcIntersect8/16, rtcOccluded8/16). The rays are the batches
// of rays.h, gathered into packets before any timing; lanes outside the image or whose pixel
// missed (shadow rays) are inactive.

#include <cstdint>
#include <vector>

#include "measure.h"
#include "rays.h"

namespace strahl::bench {

struct PacketBatch {
  int size = 8;                       // rays per packet: 8 or 16
  int tile_width = 4, tile_height = 2;
  std::vector<Ray> rays;              // size per packet (an inactive lane holds a copy of an active one)
  std::vector<Real> t_max;            // size per packet
  std::vector<std::uint32_t> active;  // per packet: the lanes that take part
  std::vector<std::uint32_t> ray;     // size per packet: the ray's index in its batch, or kNoRay
  std::size_t packets() const { return active.size(); }
  std::size_t ray_count = 0;          // active lanes in all
};

// The tiles of `size` = 8 (4×2) or 16 (4×4) pixels, left to right, top to bottom; `secondary`:
// the shadow rays of those pixels (rays.secondary_of_pixel) instead of the primary rays.
PacketBatch tile_packets(const BenchRays& rays, int size, bool secondary);

// The answers per ray of the batch (kMiss / 0 where not traced) and the exact hits (nearest).
struct PacketTrace {
  double seconds = 0;
  std::size_t rays = 0;
  std::vector<std::uint32_t> answers;  // per batch ray: nearest primitive or kMiss; occluded 1/0
  std::vector<kernel::TriangleHit> hits;  // per batch ray, nearest queries
  double mrays() const { return seconds > 0 ? double(rays) / seconds * 1e-6 : 0; }
};

PacketTrace trace_packets(const AccelView& view, const PacketBatch& packets, std::size_t batch_size, Query query,
                          int threads, const Repeat& repeat);

// The same rays one by one (nearest_hit / occluded), untimed: the reference for the packets.
PacketTrace trace_single(const AccelView& view, const RayBatch& batch, Query query, int threads);

// Rays whose packet answer is not the single-ray answer. exact: the same primitive, t, b1, b2 bit
// for bit, except `ties` (another primitive at exactly the same t: leaf order decides, see
// wide_bvh_packet.h); otherwise (float Embree) as differing() of measure.h.
struct PacketDiff {
  std::size_t differ = 0, ties = 0;
};
PacketDiff compare(const PacketTrace& packets, const PacketTrace& single, bool exact);

}  // namespace strahl::bench
