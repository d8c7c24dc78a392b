#pragma once
// surface_at() (render/surface_point.h) for a packet of camera rays whose hits are spheres and
// planes (the lecture's shapes), the lanes side by side: the same operations on the same values,
// so every lane's point, normal, texture coordinate and offset equal surface_at's bit for bit.
// Only the shape's parameters are fetched lane by lane; the arithmetic runs across the lanes.

#include "strahl/accel/packet.h"
#include "strahl/render/hit_lanes.h"
#include "strahl/render/surface_point.h"

namespace strahl {

template <int N>
struct SurfaceLanes {
  Real px[N], py[N], pz[N];  // the hit point
  Real gx[N], gy[N], gz[N];  // the geometric normal (here also the shading normal)
  Real ux[N], uy[N], uz[N];  // the texture coordinate
  Real offset[N];
  std::uint32_t material[N];

  // Lane i's surface point, as surface_at() writes it.
  STRAHL_HOST_DEVICE void get(int i, Real time, SurfacePoint& sp) const {
    sp.p = Vec3(px[i], py[i], pz[i]);
    sp.time = time;
    sp.geometric_normal = sp.normal = Vec3(gx[i], gy[i], gz[i]);
    sp.texcoord = Vec3(ux[i], uy[i], uz[i]);
    sp.material = material[i];
    sp.offset = offset[i];
  }
};

// max_abs_component(Vec3(x, y, z)), written out for lanes.
STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE Real max_abs_of(Real x, Real y, Real z) {
  const Real a = std::fabs(x), b = std::fabs(y), c = std::fabs(z);
  const Real ab = a > b ? a : b;  // (a > b ? (a > c ? a : c) : (b > c ? b : c), as two selects)
  return ab > c ? ab : c;
}

// What surface_at() reads of the shape hit: a sphere's centre c and 1/radius, or a plane's normal
// and frame (sphere = 1 or 0 selects between them; point = 1 where the texture coordinate is the
// point itself: spheres and planes with an image); the magnitude passed to ray_offset; the
// material. All zero for no hit.
struct ShapeParams {
  Real sphere = 0, point = 0, cx = 0, cy = 0, cz = 0, inv_r = 0, nx = 0, ny = 0, nz = 0, tx = 0, ty = 0, tz = 0, bx = 0, by = 0,
       bz = 0, magnitude = 0;
  std::uint32_t material = 0;
};
STRAHL_HOST_DEVICE inline ShapeParams shape_params(const SceneView& s, const Hit& hit) {
  ShapeParams q;
  if (hit.kind == ShapeKind::Sphere) {
    const kernel::Sphere& k = s.spheres[hit.index];
    q.sphere = q.point = 1;
    q.cx = k.center.x, q.cy = k.center.y, q.cz = k.center.z;
    q.inv_r = Real(1) / k.radius;  // (normal_at: (p − c) / R, vec3.h's division)
    q.magnitude = max_abs_component(k.center) + k.radius;
    q.material = k.material;
  } else if (hit.kind == ShapeKind::Plane) {
    const kernel::Plane& k = s.planes[hit.index];
    q.nx = k.normal.x, q.ny = k.normal.y, q.nz = k.normal.z;
    q.tx = k.tangent.x, q.ty = k.tangent.y, q.tz = k.tangent.z;
    q.bx = k.bitangent.x, q.by = k.bitangent.y, q.bz = k.bitangent.z;
    q.magnitude = std::fabs(k.distance);
    q.material = k.material;
    q.point = s.materials[k.material].texture != kNoTexture ? 1 : 0;
  }
  return q;
}

// The surface points of the active lanes' hits into `out`, and `lit` the lanes that hit (inactive
// and missing lanes' values are zeros).
template <int N>
STRAHL_HOST_DEVICE inline void surface_lanes(const SceneView& s, std::uint32_t active, const PacketRays<N>& r,
                                             const HitLanes<N>& hits, SurfaceLanes<N>& __restrict out,
                                             std::uint32_t& lit) {
  // The shapes' parameters per lane (ShapeParams, side by side) and the hits' t (0 where none).
  Real t[N], sphere[N], point[N], cx[N], cy[N], cz[N], inv_r[N], nx[N], ny[N], nz[N], tx[N], ty[N], tz[N], bx[N], by[N],
      bz[N], magnitude[N];
  lit = hits.found() & active;
  const int first = active != 0 ? wide_bvh_detail::lowest_bit(active) : 0;
  // Do all active lanes hit the same shape (as a pixel's samples mostly do)?
  std::uint32_t differ = 0;
  for (int i = 0; i < N; ++i)
    differ |= std::uint32_t((hits.sphere[i] != hits.sphere[first]) | (hits.plane[i] != hits.plane[first])) << i;
  const auto put = [&](int i, const ShapeParams& q) {
    sphere[i] = q.sphere, point[i] = q.point, cx[i] = q.cx, cy[i] = q.cy, cz[i] = q.cz, inv_r[i] = q.inv_r;
    nx[i] = q.nx, ny[i] = q.ny, nz[i] = q.nz, tx[i] = q.tx, ty[i] = q.ty, tz[i] = q.tz;
    bx[i] = q.bx, by[i] = q.by, bz[i] = q.bz, magnitude[i] = q.magnitude, out.material[i] = q.material;
  };
  if ((differ & active) == 0) {  // its parameters fetched once, in every lane
    const ShapeParams q = shape_params(s, hits.hit(first));
    for (int i = 0; i < N; ++i) put(i, q);
  } else {
    for (int i = 0; i < N; ++i) put(i, ((active >> i) & 1u) ? shape_params(s, hits.hit(i)) : ShapeParams{});
  }
  for (int i = 0; i < N; ++i) t[i] = hits.t[i] < kInfinity ? hits.t[i] : Real(0);  // (lanes not lit: zeros below)
  for (int i = 0; i < N; ++i) {
    // ray.at(t), normal_at or the plane's normal, the texture coordinate, ray_offset.
    const Real px = r.ox[i] + r.dx[i] * t[i], py = r.oy[i] + r.dy[i] * t[i], pz = r.oz[i] + r.dz[i] * t[i];
    const bool on_sphere = sphere[i] != 0;
    out.px[i] = px, out.py[i] = py, out.pz[i] = pz;
    out.gx[i] = on_sphere ? (px - cx[i]) * inv_r[i] : nx[i];
    out.gy[i] = on_sphere ? (py - cy[i]) * inv_r[i] : ny[i];
    out.gz[i] = on_sphere ? (pz - cz[i]) * inv_r[i] : nz[i];
    const bool at_point = point[i] != 0;
    out.ux[i] = at_point ? px : px * tx[i] + py * ty[i] + pz * tz[i];
    out.uy[i] = at_point ? py : px * bx[i] + py * by[i] + pz * bz[i];
    out.uz[i] = at_point ? pz : Real(0);
    const Real p_max = max_abs_of(px, py, pz);
    out.offset[i] = kRayEpsilon * larger_of(p_max, magnitude[i]) +
                    kRayPathEpsilon * (max_abs_of(r.ox[i], r.oy[i], r.oz[i]) + t[i]);
  }
  for (std::uint32_t m = ~lit & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    out.px[i] = out.py[i] = out.pz[i] = out.gx[i] = out.gy[i] = out.gz[i] = out.offset[i] = 0;
    out.ux[i] = out.uy[i] = out.uz[i] = 0;
    out.material[i] = 0;
  }
}

}  // namespace strahl
