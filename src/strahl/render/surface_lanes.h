#pragma once
// surface_at() (render/surface_point.h) for a packet of camera rays whose hits are spheres and
// planes (the lecture's shapes), the lanes side by side: the same operations on the same values,
// so every lane's point, normal, texture coordinate and offset equal surface_at's bit for bit.
// Only the shape's parameters are fetched lane by lane; the arithmetic runs across the lanes.

#include "strahl/accel/packet.h"
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
  return a > b ? (a > c ? a : c) : (b > c ? b : c);
}

// The surface points of the active lanes' hits into `out`, when every active lane hit a sphere,
// a plane or nothing: true, and `lit` the lanes that hit (inactive and missing lanes' values are
// zeros). False, with `out` and `lit` unspecified, when some lane hit another kind of shape.
template <int N>
STRAHL_HOST_DEVICE inline bool surface_lanes(const SceneView& s, std::uint32_t active, const PacketRays<N>& r,
                                             const Hit* hits, SurfaceLanes<N>& out, std::uint32_t& lit) {
  // Per lane, the shape's parameters: a sphere's centre c and 1/radius, or a plane's normal and
  // frame (sphere = 1 or 0 selects); the magnitude passed to ray_offset. All zero to begin with
  // (one block of stores) and in the lanes that hit nothing.
  struct {
    Real t[N], sphere[N], cx[N], cy[N], cz[N], inv_r[N], nx[N], ny[N], nz[N], tx[N], ty[N], tz[N], bx[N], by[N],
        bz[N], magnitude[N];
  } g = {};
  Real *const t = g.t, *const sphere = g.sphere, *const cx = g.cx, *const cy = g.cy, *const cz = g.cz,
       *const inv_r = g.inv_r, *const nx = g.nx, *const ny = g.ny, *const nz = g.nz, *const tx = g.tx,
       *const ty = g.ty, *const tz = g.tz, *const bx = g.bx, *const by = g.by, *const bz = g.bz,
       *const magnitude = g.magnitude;
  lit = 0;
  for (int i = 0; i < N; ++i) out.material[i] = 0;
  for (std::uint32_t m = active; m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    const Hit& hit = hits[i];
    if (hit.kind == ShapeKind::Sphere) {
      const kernel::Sphere& k = s.spheres[hit.index];
      sphere[i] = 1;
      cx[i] = k.center.x, cy[i] = k.center.y, cz[i] = k.center.z;
      inv_r[i] = Real(1) / k.radius;  // (normal_at: (p − c) / R, vec3.h's division)
      magnitude[i] = max_abs_component(k.center) + k.radius;
      out.material[i] = k.material;
    } else if (hit.kind == ShapeKind::Plane) {
      const kernel::Plane& k = s.planes[hit.index];
      nx[i] = k.normal.x, ny[i] = k.normal.y, nz[i] = k.normal.z;
      tx[i] = k.tangent.x, ty[i] = k.tangent.y, tz[i] = k.tangent.z;
      bx[i] = k.bitangent.x, by[i] = k.bitangent.y, bz[i] = k.bitangent.z;
      magnitude[i] = std::fabs(k.distance);
      out.material[i] = k.material;
    } else if (hit.kind != ShapeKind::None) {
      return false;
    } else {
      continue;
    }
    t[i] = hit.t;
    lit |= 1u << i;
  }
  for (int i = 0; i < N; ++i) {
    // ray.at(t), normal_at or the plane's normal, the texture coordinate, ray_offset.
    const Real px = r.ox[i] + r.dx[i] * t[i], py = r.oy[i] + r.dy[i] * t[i], pz = r.oz[i] + r.dz[i] * t[i];
    const bool on_sphere = sphere[i] != 0;
    out.px[i] = px, out.py[i] = py, out.pz[i] = pz;
    out.gx[i] = on_sphere ? (px - cx[i]) * inv_r[i] : nx[i];
    out.gy[i] = on_sphere ? (py - cy[i]) * inv_r[i] : ny[i];
    out.gz[i] = on_sphere ? (pz - cz[i]) * inv_r[i] : nz[i];
    out.ux[i] = on_sphere ? px : px * tx[i] + py * ty[i] + pz * tz[i];
    out.uy[i] = on_sphere ? py : px * bx[i] + py * by[i] + pz * bz[i];
    out.uz[i] = on_sphere ? pz : Real(0);
    const Real p_max = max_abs_of(px, py, pz);
    out.offset[i] = kRayEpsilon * larger_of(p_max, magnitude[i]) +
                    kRayPathEpsilon * (max_abs_of(r.ox[i], r.oy[i], r.oz[i]) + t[i]);
  }
  for (std::uint32_t m = ~lit & ((1u << (N - 1) << 1) - 1); m != 0; m &= m - 1) {
    const int i = wide_bvh_detail::lowest_bit(m);
    out.px[i] = out.py[i] = out.pz[i] = out.gx[i] = out.gy[i] = out.gz[i] = out.offset[i] = 0;
    out.ux[i] = out.uy[i] = out.uz[i] = 0;
  }
  return true;
}

}  // namespace strahl
