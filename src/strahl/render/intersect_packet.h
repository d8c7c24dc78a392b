#pragma once
// The scene queries of intersect_scene.h for a packet of N rays at once (lane i taking part when
// bit i of `active` is set): the nearest hit of camera rays and the transmittance of shadow rays.
// Lane for lane the answers are those of closest_hit() and transmittance(): planes and unbounded
// solids one lane after the other, the acceleration structure through its packet query
// (accel/packet.h: the BVH's packet traversal, the one-leaf sphere loop side by side), moving
// shapes and instances lane by lane. The only difference is the one packet.h names: a ray through
// an edge shared by two triangles at exactly the same t may report the other triangle.

#include "strahl/accel/packet.h"
#include "strahl/render/hit_lanes.h"
#include "strahl/render/intersect_scene.h"

namespace strahl {

// kernel::intersect(plane, ray, t_min[i], t_max[i]) for every lane's ray, into t[]: the same
// operations, the lanes side by side (a lane parallel to the plane divides by zero here, and its
// NaN or infinite quotient is replaced by kInfinity as the single test returns it).
template <int N>
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void intersect_plane_lanes(const kernel::Plane& p, const PacketRays<N>& r,
                                                                  const Real* t_min, const Real* t_max, Real* t) {
  const Real nx = p.normal.x, ny = p.normal.y, nz = p.normal.z;
  for (int i = 0; i < N; ++i) {
    const Real denom = nx * r.dx[i] + ny * r.dy[i] + nz * r.dz[i];
    const Real u = (p.distance - (nx * r.ox[i] + ny * r.oy[i] + nz * r.oz[i])) / denom;
    t[i] = ((denom != 0) & (u > t_min[i]) & (u < t_max[i])) ? u : kInfinity;
  }
}

// A packet's nearest hits (closest_hit_packet): in lane form where the packet loops over planes
// and one leaf of spheres found them, else a Hit per lane.
template <int N>
struct PacketHits {
  bool in_lanes = false;  // whether the hits are in `lanes` (every one a sphere, a plane or nothing)
  HitLanes<N> lanes;
  UninitializedLanes<Hit, N> hit;  // the lanes' hits when not in `lanes`

  STRAHL_HOST_DEVICE Hit at(int i) const { return in_lanes ? lanes.hit(i) : hit.at[i]; }
};

// closest_hit(s, r.ray(i), 0, kInfinity) for each active lane, into out (every lane is set; the
// inactive lanes' hits are those of their rays).
template <int N>
STRAHL_HOST_DEVICE inline void closest_hit_packet(const SceneView& s, std::uint32_t active, const PacketRays<N>& r,
                                                  PacketHits<N>& out) {
  // The planes, the lanes side by side (the plane's index kept as a Real beside t, so that the
  // lanes' update is one width; −1: none).
  Real t_min[N], t_max[N], t[N], plane[N];
  for (int i = 0; i < N; ++i) t_min[i] = 0, t_max[i] = kInfinity, plane[i] = -1;
  for (std::uint32_t k = 0; k < s.plane_count; ++k) {
    intersect_plane_lanes<N>(s.planes[k], r, t_min, t_max, t);
    for (int i = 0; i < N; ++i) {
      const bool nearer = t[i] < t_max[i];
      t_max[i] = nearer ? t[i] : t_max[i];
      plane[i] = nearer ? Real(k) : plane[i];
    }
  }
  if (is_sphere_leaf(s.accel) && s.solid_count == s.bounded_solid_count &&
      s.moving_count() == 0 && s.instance_count == 0) {
    // Planes and one leaf of spheres (the lecture's scenes): the spheres side by side too, the
    // hits left in lane form (a plane behind the sphere hit is no hit of the plane).
    HitLanes<N>& h = out.lanes;
    sphere_leaf_nearest_lanes<N>(s.accel.prims, active, r, t_min, t_max, h.sphere);
    for (int i = 0; i < N; ++i) {
      h.t[i] = t_max[i];  // (kInfinity where nothing was hit)
      h.plane[i] = h.sphere[i] >= 0 ? Real(-1) : plane[i];
    }
    out.in_lanes = true;
    return;
  }
  out.in_lanes = false;
  Hit* const hits = out.hit.at;
  UninitializedLanes<Ray, N> ray_slots;  // the rays one by one, for the queries below
  Ray* const rays = ray_slots.at;
  for (int i = 0; i < N; ++i) rays[i] = r.ray(i);
  for (int i = 0; i < N; ++i) {
    hits[i] = Hit{};
    if (plane[i] >= 0) {
      hits[i].t = t_max[i];
      hits[i].kind = ShapeKind::Plane;
      hits[i].index = std::uint32_t(plane[i]);
    }
  }
  for (std::uint32_t k = s.bounded_solid_count; k < s.solid_count; ++k) {
    for (std::uint32_t m = active; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      const kernel::SolidCrossing c = kernel::intersect(s.accel.prims.shapes, s.solids[k], rays[i], 0, hits[i].t);
      if (c.t < hits[i].t) { hits[i].t = c.t; hits[i].kind = ShapeKind::Solid; hits[i].index = k; hits[i].b1 = c.part; }
    }
  }
  for (int i = 0; i < N; ++i) t_max[i] = hits[i].t;
  NearestHit nearest[N];
  if (is_sphere_leaf(s.accel))
    sphere_leaf_nearest_packet<N>(s.accel.prims, active, r, t_min, t_max, nearest);
  else
    nearest_hit_packet<N>(s.accel, active, rays, t_min, t_max, nearest);
  for (std::uint32_t m = active; m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    Hit& hit = hits[i];
    if (nearest[i].hit.t < hit.t) {
      const std::uint32_t prim = nearest[i].prim;
      hit.t = nearest[i].hit.t;
      if (s.accel.prims.is_sphere(prim)) {
        hit.kind = ShapeKind::Sphere;
        hit.index = prim;
      } else if (s.accel.prims.is_solid(prim)) {
        hit.kind = ShapeKind::Solid;
        hit.index = prim - s.accel.prims.first_solid();
        hit.b1 = nearest[i].hit.b1;
      } else {
        hit.kind = ShapeKind::Triangle;
        hit.index = prim - s.accel.prims.sphere_count;
        hit.b1 = nearest[i].hit.b1;
        hit.b2 = nearest[i].hit.b2;
      }
    }
    if (s.moving_count() > 0) closest_moving_hit(s, rays[i], 0, hit);
    if (s.instance_count > 0) closest_instance_hit(s, rays[i], 0, hit);
    if (!hit.found()) hit.t = kInfinity;
  }
}

// transmittance(s, r.ray(i), distance[i]) for each active lane, into (tx[i], ty[i], tz[i]); the
// other lanes get 0 or 1 (every lane is written).
template <int N>
STRAHL_HOST_DEVICE inline void transmittance_packet(const SceneView& s, std::uint32_t active, const PacketRays<N>& r,
                                                    const Real* distance, Real* __restrict tx, Real* __restrict ty,
                                                    Real* __restrict tz) {
  const bool moving = s.moving_count() > 0;
  Real t_min[N], t[N];
  for (int i = 0; i < N; ++i) t_min[i] = 0;
  if (!s.opaque && !moving && s.instance_count == 0 && is_sphere_leaf(s.accel)) {
    // Crossings to count and attenuate by, in transmittance()'s order — planes, unbounded solids,
    // then the spheres of the one leaf in index order (for_each_crossing's naive loop) — with
    // the lanes side by side at each plane and sphere.
    std::uint32_t open = active;  // lanes whose light is not blocked yet
    for (int i = 0; i < N; ++i) tx[i] = ty[i] = tz[i] = 1;
    const auto cross = [&](int i, const Material& material, int n) {
      for (int c = 0; c < n; ++c) {
        Vec3 tr(tx[i], ty[i], tz[i]);
        if (!attenuate(material, tr)) {
          open &= ~(1u << i);
          return;
        }
        tx[i] = tr.x, ty[i] = tr.y, tz[i] = tr.z;
      }
    };
    for (std::uint32_t k = 0; k < s.plane_count; ++k) {
      intersect_plane_lanes<N>(s.planes[k], r, t_min, distance, t);
      std::uint32_t crossing = 0;
      for (int i = 0; i < N; ++i) crossing |= std::uint32_t(t[i] < kInfinity) << i;
      for (std::uint32_t m = crossing & open; m != 0; m &= m - 1)
        cross(wide_bvh_detail::lowest_bit(m), s.materials[s.planes[k].material], 1);
    }
    for (std::uint32_t k = s.bounded_solid_count; k < s.solid_count; ++k)
      for (std::uint32_t m = open; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        cross(i, s.materials[s.solids[k].material], kernel::crossings(s.accel.prims.shapes, s.solids[k], r.ray(i), 0, distance[i]));
      }
    const PacketCone cone = s.accel.prims.sphere_count > 1 ? packet_cone<N>(r, open, t_min) : PacketCone{};
    for (std::uint32_t k = 0; k < s.accel.prims.sphere_count && open != 0; ++k) {
      if (!cone_may_meet(cone, s.accel.prims.spheres[k])) continue;
      std::uint32_t first = 0, second = 0;  // lanes whose first, second root is a crossing
      if (!sphere_crossings_lanes<N>(s.accel.prims.spheres[k], r, t_min, distance, first, second)) continue;
      const Material& material = s.materials[s.accel.prims.spheres[k].material];
      for (std::uint32_t m = (first | second) & open; m != 0; m &= m - 1) {
        const int i = wide_bvh_detail::lowest_bit(m);
        cross(i, material, int((first >> i) & 1u) + int((second >> i) & 1u));
      }
    }
    for (std::uint32_t m = active & ~open; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      tx[i] = ty[i] = tz[i] = 0;
    }
    return;
  }
  if (!s.opaque) {
    // Crossings to count and attenuate by: the single-ray query, lane by lane.
    for (int i = 0; i < N; ++i) tx[i] = ty[i] = tz[i] = 0;
    for (std::uint32_t m = active; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      const Vec3 tr = transmittance(s, r.ray(i), distance[i]);
      tx[i] = tr.x, ty[i] = tr.y, tz[i] = tr.z;
    }
    return;
  }
  // Nothing transparent: any surface in between blocks the light (transmittance()'s any-hit case).
  std::uint32_t blocked = 0;
  for (std::uint32_t k = 0; k < s.plane_count; ++k) {
    intersect_plane_lanes<N>(s.planes[k], r, t_min, distance, t);
    for (int i = 0; i < N; ++i) blocked |= std::uint32_t(t[i] < kInfinity) << i;
  }
  for (std::uint32_t k = s.bounded_solid_count; k < s.solid_count; ++k)
    for (std::uint32_t m = active & ~blocked; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      if (kernel::crossings(s.accel.prims.shapes, s.solids[k], r.ray(i), 0, distance[i]) > 0) blocked |= 1u << i;
    }
  if (is_sphere_leaf(s.accel)) {
    blocked |= sphere_leaf_occluded_packet<N>(s.accel.prims, active & ~blocked, r, t_min, distance);
  } else {
    UninitializedLanes<Ray, N> ray_slots;  // (every lane assigned)
    for (int i = 0; i < N; ++i) ray_slots.at[i] = r.ray(i);
    blocked |= occluded_packet<N>(s.accel, active & ~blocked, ray_slots.at, t_min, distance);
  }
  if (s.instance_count > 0)
    for (std::uint32_t m = active & ~blocked; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      if (instance_occluded(s, r.ray(i), 0, distance[i])) blocked |= 1u << i;
    }
  if (moving)  // each lane at its own time: one by one
    for (std::uint32_t m = active & ~blocked; m != 0; m &= m - 1) {
      const int i = wide_bvh_detail::lowest_bit(m);
      if (moving_occluded(s, r.ray(i), distance[i])) blocked |= 1u << i;
    }
  for (int i = 0; i < N; ++i) tx[i] = ty[i] = tz[i] = ((blocked >> i) & 1u) ? Real(0) : Real(1);
}

}  // namespace strahl
