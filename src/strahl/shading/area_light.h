#pragma once
// Area lights for soft shadows (Cook et al. 1984, distributed ray tracing): a rectangle, a disk
// or a sphere of constant emitted radiance L. A shading point estimates the irradiance
//   E = ∫_light L cos θ cos θ' / r² dA
// from n×n stratified (jittered) samples on the light. Rectangles and disks are sampled
// uniformly by area; spheres by the cone of directions they subtend (uniform in solid angle),
// which wastes no samples on the far side. Each sample acts like a point light of "intensity"
//   I = L · cos θ' / (π · r² · pdf_A)     (or L / (π · pdf_ω) for solid-angle sampling)
// in the Whitted shading of render/whitted.h, so a Lambert surface under a light filling its
// whole hemisphere with L = 1 is as bright as under a point light of intensity 1 at normal
// incidence (the 1/π of the Lambert BRDF). Rectangles and disks emit from one side only.
//
// Emitters are visible: a camera or mirror ray meeting one returns L (intersect_emitter). They
// cast no shadows of their own: shadow rays do not test light shapes.

#include <cmath>

#include "strahl/accel/packet.h"
#include "strahl/geometry/sphere.h"
#include "strahl/math/frame.h"
#include "strahl/math/trig.h"
#include "strahl/sampling/warp.h"
#include "strahl/shading/light.h"

namespace strahl {

// One sample on an area light as seen from a shading point.
struct AreaLightSample {
  Vec3 point;       // on the light
  Vec3 to_light;    // unit, from the shading point
  Real distance = 0;
  Vec3 intensity;   // I above; zero when the sample does not illuminate the point
  Real pdf = 0;     // density of `point`: per area (Rect, Disk) or of `to_light` per solid angle (Sphere)
};

STRAHL_HOST_DEVICE inline Real area_light_area(const Light& l) {
  switch (l.kind) {
    case LightKind::Rect: return length(cross(l.edge_u, l.edge_v));
    case LightKind::Disk: return kPi * l.radius * l.radius;
    case LightKind::Sphere: return 4 * kPi * l.radius * l.radius;
    default: return 0;
  }
}

// Radiance L of a light emitting total power Φ (one-sided Lambertian emitter: Φ = π·L·A).
STRAHL_HOST_DEVICE inline Real radiance_from_power(const Light& l, Real power) {
  const Real a = area_light_area(l);
  return a > 0 ? power / (kPi * a) : 0;
}

// Samples one light from one shading point p: what all of the point's samples share (the
// disk's frame, the rectangle's area, the cone the sphere subtends and its density) is computed
// once, by the constructor; sample(u) takes the unit-square point u. Hot: a soft shadow of n×n
// samples per shading point spent half its time on the shared part when it was redone per sample.
class AreaLightSampler {
 public:
  STRAHL_HOST_DEVICE AreaLightSampler(const Light& l, const Vec3& p) : l_(l), p_(p) {
    switch (l.kind) {
      case LightKind::Rect:
        area_ = length(cross(l.edge_u, l.edge_v));
        lit_ = true;
        break;
      case LightKind::Disk:
        frame_ = Frame::around(l.normal);
        area_ = kPi * l.radius * l.radius;
        lit_ = true;
        break;
      case LightKind::Sphere: {
        const Vec3 axis = l.position - p;
        const Real d2 = length_squared(axis);
        const Real r2 = l.radius * l.radius;
        if (d2 <= r2) break;  // inside the light: not lit by it
        const Real dist = std::sqrt(d2);
        const Real sin2_max = r2 / d2;
        cos_max_ = sqrt_clamped(1 - sin2_max);
        frame_ = Frame::around(axis / dist);
        axis_ = axis;
        pdf_ = uniform_cone_pdf(cos_max_);
        intensity_ = l.radiance * (1 / (kPi * pdf_));
        lit_ = true;
        break;
      }
      default: break;
    }
  }

  // False where no sample can illuminate p (p inside a sphere light, or not an area light):
  // every sample's intensity is then zero.
  STRAHL_HOST_DEVICE bool lit() const { return lit_; }

  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE AreaLightSample sample(const Vec2& u) const {
    AreaLightSample s;
    if (!lit_) return s;
    if (l_.kind == LightKind::Sphere) {
      s.to_light = normalize(frame_.to_world(square_to_uniform_cone(u, cos_max_)));
      s.pdf = pdf_;
      // Where the direction meets the sphere (nearest root; grazing rays numerically missing it
      // take the tangent point's distance).
      const kernel::Sphere sphere{l_.position, l_.radius, 0};
      Real t = kernel::intersect(sphere, Ray{p_, s.to_light}, 0, kInfinity);
      if (t == kInfinity) t = dot(axis_, s.to_light);
      s.distance = t;
      s.point = p_ + s.to_light * t;
      s.intensity = intensity_;
      return s;
    }
    if (l_.kind == LightKind::Rect) {
      s.point = l_.position + l_.edge_u * u.x + l_.edge_v * u.y;
    } else {
      const Vec2 d = square_to_disk(u);
      s.point = l_.position + (frame_.u * d.x + frame_.v * d.y) * l_.radius;
    }
    s.pdf = 1 / area_;
    const Vec3 d = s.point - p_;
    const Real r2 = length_squared(d);
    s.distance = std::sqrt(r2);
    if (!(s.distance > 0)) return s;
    s.to_light = d / s.distance;
    const Real cos_light = -dot(s.to_light, l_.normal);
    if (cos_light <= 0) return s;  // the point sees the back of the light
    s.intensity = l_.radiance * (cos_light * area_ / (kPi * r2));
    return s;
  }

 private:
  const Light& l_;
  Vec3 p_;
  Frame frame_;         // Disk: around its normal; Sphere: around the axis from p to its centre
  Vec3 axis_;           // Sphere: from p to its centre
  Vec3 intensity_;      // Sphere: the same for every direction in the cone
  Real area_ = 0;       // Rect, Disk
  Real cos_max_ = 0;    // Sphere: the cone's half-angle
  Real pdf_ = 0;        // Sphere: per solid angle
  bool lit_ = false;
};

// An area light seen from N shading points at once, the lanes (p_x[i], p_y[i], p_z[i]): each
// lane's AreaLightSampler — its set-up and sample() — with the same arithmetic, bit for bit, but
// the lanes side by side in arrays the compiler vectorises. For the packet front end (a pixel's
// camera samples, each with its own shading point) and for one point's strata in groups.
template <int N>
class AreaLightLanes {
 public:
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE AreaLightLanes(const Light& l, const Real* p_x, const Real* p_y,
                                                        const Real* p_z)
      : l_(l) {
    for (int i = 0; i < N; ++i) px_[i] = p_x[i], py_[i] = p_y[i], pz_[i] = p_z[i];
    set_up();
  }
  // Every lane from the one point p.
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE AreaLightLanes(const Light& l, const Vec3& p) : l_(l) {
    for (int i = 0; i < N; ++i) px_[i] = p.x, py_[i] = p.y, pz_[i] = p.z;
    set_up();
  }

  // sample(u[i]) of lane i's AreaLightSampler for every lane, u[i] = (u_x[i], u_y[i]): the unit
  // direction (t_x, t_y, t_z) towards the sample, its distance and its intensity (i_r, i_g,
  // i_b), zero where the sample does not illuminate the point.
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void sample(const Real* u_x, const Real* u_y, Real* t_x, Real* t_y, Real* t_z,
                                                     Real* distance, Real* i_r, Real* i_g, Real* i_b) const {
    if (l_.kind == LightKind::Sphere) {
      sphere(u_x, u_y, t_x, t_y, t_z, distance, i_r, i_g, i_b);
      return;
    }
    if (l_.kind != LightKind::Rect && l_.kind != LightKind::Disk) {
      for (int i = 0; i < N; ++i) t_x[i] = t_y[i] = t_z[i] = distance[i] = i_r[i] = i_g[i] = i_b[i] = 0;
      return;
    }
    // The point on the light: the rectangle's directly, the disk's by square_to_disk.
    Real qx[N], qy[N], qz[N];
    if (l_.kind == LightKind::Rect) {
      for (int i = 0; i < N; ++i) {
        qx[i] = l_.position.x + l_.edge_u.x * u_x[i] + l_.edge_v.x * u_y[i];
        qy[i] = l_.position.y + l_.edge_u.y * u_x[i] + l_.edge_v.y * u_y[i];
        qz[i] = l_.position.z + l_.edge_u.z * u_x[i] + l_.edge_v.z * u_y[i];
      }
    } else {
      for (int i = 0; i < N; ++i) {
        const Vec2 d = square_to_disk({u_x[i], u_y[i]});
        qx[i] = l_.position.x + (disk_.u.x * d.x + disk_.v.x * d.y) * l_.radius;
        qy[i] = l_.position.y + (disk_.u.y * d.x + disk_.v.y * d.y) * l_.radius;
        qz[i] = l_.position.z + (disk_.u.z * d.x + disk_.v.z * d.y) * l_.radius;
      }
    }
    // What sample() makes of the point: direction, distance, the cosine at the light, intensity
    // — every value in every lane, then chosen by comparisons of Reals, so that the loop runs the
    // lanes side by side.
    const Vec3 normal = l_.normal, radiance = l_.radiance;
    const Real area = area_;
    Real dist[N], tx[N], ty[N], tz[N], ir[N], ig[N], ib[N];
    for (int i = 0; i < N; ++i) {
      const Real dx = qx[i] - px_[i], dy = qy[i] - py_[i], dz = qz[i] - pz_[i];
      const Real r2 = dx * dx + dy * dy + dz * dz;
      const Real d = std::sqrt(r2);
      const Real inv = Real(1) / d;
      const Real x = d > 0 ? dx * inv : Real(0), y = d > 0 ? dy * inv : Real(0), z = d > 0 ? dz * inv : Real(0);
      const Real cos_light = -(x * normal.x + y * normal.y + z * normal.z);
      const Real factor = cos_light * area / (kPi * r2);
      // (sample(): no light where d is not > 0, nor where cos_light <= 0: the back is seen)
      ir[i] = d > 0 ? (cos_light <= 0 ? Real(0) : radiance.x * factor) : Real(0);
      ig[i] = d > 0 ? (cos_light <= 0 ? Real(0) : radiance.y * factor) : Real(0);
      ib[i] = d > 0 ? (cos_light <= 0 ? Real(0) : radiance.z * factor) : Real(0);
      dist[i] = d, tx[i] = x, ty[i] = y, tz[i] = z;
    }
    for (int i = 0; i < N; ++i) {
      distance[i] = dist[i], t_x[i] = tx[i], t_y[i] = ty[i], t_z[i] = tz[i];
      i_r[i] = ir[i], i_g[i] = ig[i], i_b[i] = ib[i];
    }
  }

 private:
  // AreaLightSampler's constructor, lane by lane.
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void set_up() {
    if (l_.kind == LightKind::Rect) area_ = length(cross(l_.edge_u, l_.edge_v));
    if (l_.kind == LightKind::Disk) disk_ = Frame::around(l_.normal), area_ = kPi * l_.radius * l_.radius;
    if (l_.kind != LightKind::Sphere) {
      // (Unread, but set: the compiler cannot tell that the light's kind stays what it was.)
      for (int i = 0; i < N; ++i) {
        fux_[i] = fuy_[i] = fuz_[i] = fvx_[i] = fvy_[i] = fvz_[i] = fwx_[i] = fwy_[i] = fwz_[i] = 0;
        ax_[i] = ay_[i] = az_[i] = cos_max_[i] = scale_[i] = 0;
      }
      return;
    }
    const Real r2 = l_.radius * l_.radius;
    for (int i = 0; i < N; ++i) {
      const Real ax = l_.position.x - px_[i], ay = l_.position.y - py_[i], az = l_.position.z - pz_[i];
      const Real d2 = ax * ax + ay * ay + az * az;
      lit_[i] = !(d2 <= r2);  // (inside the light: not lit by it)
      const Real dist = std::sqrt(d2);
      const Real sin2_max = r2 / d2;
      cos_max_[i] = sqrt_clamped(1 - sin2_max);
      // Frame::around(axis / dist)
      const Real inv = Real(1) / dist;
      const Real nx = ax * inv, ny = ay * inv, nz = az * inv;
      const Real sign = nz >= 0 ? Real(1) : Real(-1);
      const Real a = Real(-1) / (sign + nz);
      const Real b = nx * ny * a;
      fux_[i] = 1 + sign * nx * nx * a, fuy_[i] = sign * b, fuz_[i] = -sign * nx;
      fvx_[i] = b, fvy_[i] = sign + ny * ny * a, fvz_[i] = -ny;
      fwx_[i] = nx, fwy_[i] = ny, fwz_[i] = nz;
      ax_[i] = ax, ay_[i] = ay, az_[i] = az;
      const Real pdf = uniform_cone_pdf(cos_max_[i]);
      scale_[i] = 1 / (kPi * pdf);
    }
  }

  // square_to_uniform_cone, the frame's to_world and normalize, as AreaLightSampler::sample()
  // calls them, then where the direction meets the sphere.
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void sphere(const Real* u_x, const Real* u_y, Real* t_x, Real* t_y, Real* t_z,
                                                     Real* distance, Real* i_r, Real* i_g, Real* i_b) const {
    PacketRays<N> rays;
    Real t_min[N], t_max[N], t[N];
    for (int i = 0; i < N; ++i) {
      const Real z = 1 - u_x[i] * (1 - cos_max_[i]);
      const Real r = sqrt_clamped(1 - z * z);
      const SinCos phi = sin_cos_pi(2 * u_y[i]);  // φ = 2π·u.y
      const Real lx = r * phi.cos, ly = r * phi.sin, lz = z;
      const Real wx = fux_[i] * lx + fvx_[i] * ly + fwx_[i] * lz;
      const Real wy = fuy_[i] * lx + fvy_[i] * ly + fwy_[i] * lz;
      const Real wz = fuz_[i] * lx + fvz_[i] * ly + fwz_[i] * lz;
      const Real inv = Real(1) / std::sqrt(wx * wx + wy * wy + wz * wz);
      rays.ox[i] = px_[i], rays.oy[i] = py_[i], rays.oz[i] = pz_[i], rays.time[i] = 0;
      rays.dx[i] = wx * inv, rays.dy[i] = wy * inv, rays.dz[i] = wz * inv;
      t_min[i] = 0, t_max[i] = kInfinity;
    }
    // kernel::intersect's answers, bit for bit, from its lane form (accel/packet.h).
    const kernel::Sphere sphere{l_.position, l_.radius, 0};
    if (!intersect_sphere_lanes<N>(sphere, rays, t_min, t_max, t))
      for (int i = 0; i < N; ++i) t[i] = kInfinity;
    for (int i = 0; i < N; ++i) {
      // Grazing directions numerically missing the sphere take the tangent point's distance.
      const Real tangent = ax_[i] * rays.dx[i] + ay_[i] * rays.dy[i] + az_[i] * rays.dz[i];
      const bool lit = lit_[i];
      t_x[i] = lit ? rays.dx[i] : Real(0), t_y[i] = lit ? rays.dy[i] : Real(0), t_z[i] = lit ? rays.dz[i] : Real(0);
      distance[i] = lit ? (t[i] == kInfinity ? tangent : t[i]) : Real(0);
      i_r[i] = lit ? l_.radiance.x * scale_[i] : Real(0);
      i_g[i] = lit ? l_.radiance.y * scale_[i] : Real(0);
      i_b[i] = lit ? l_.radiance.z * scale_[i] : Real(0);
    }
  }

  const Light& l_;
  Real px_[N], py_[N], pz_[N];
  // Sphere, per lane: the cone's frame (around the axis), the axis from p to the centre, the
  // cone's half-angle, I / L (the intensity's factor), whether the light is seen.
  Real fux_[N], fuy_[N], fuz_[N], fvx_[N], fvy_[N], fvz_[N], fwx_[N], fwy_[N], fwz_[N];
  Real ax_[N], ay_[N], az_[N], cos_max_[N], scale_[N];
  bool lit_[N] = {};
  Frame disk_;     // Disk: around its normal
  Real area_ = 0;  // Rect, Disk
};

// One sample of light l for shading point p with the unit-square point u.
STRAHL_HOST_DEVICE inline AreaLightSample sample_area_light(const Light& l, const Vec3& p, const Vec2& u) {
  return AreaLightSampler(l, p).sample(u);
}

// The stratum (i, j) of an n×n grid, jittered by `jitter`.
STRAHL_HOST_DEVICE inline Vec2 stratified(int i, int j, int n, const Vec2& jitter) {
  return {(i + jitter.x) / n, (j + jitter.y) / n};
}

// Distance along the ray to the light's emitting surface in (t_min, t_max), or kInfinity.
// Rectangles and disks are seen from their emitting side only.
STRAHL_HOST_DEVICE inline Real intersect_emitter(const Light& l, const Ray& ray, Real t_min, Real t_max) {
  switch (l.kind) {
    case LightKind::Rect:
    case LightKind::Disk: {
      const Real denom = dot(ray.direction, l.normal);
      if (denom >= 0) return kInfinity;  // parallel, or arriving at the back
      const Real t = dot(l.position - ray.origin, l.normal) / denom;
      if (!(t > t_min && t < t_max)) return kInfinity;
      const Vec3 q = ray.at(t) - l.position;
      if (l.kind == LightKind::Disk) return length_squared(q) <= l.radius * l.radius ? t : kInfinity;
      const Real uu = length_squared(l.edge_u), vv = length_squared(l.edge_v);
      const Real a = dot(q, l.edge_u), b = dot(q, l.edge_v);
      // Edges are perpendicular (the loader checks), so the coordinates are independent.
      return (a >= 0 && a <= uu && b >= 0 && b <= vv) ? t : kInfinity;
    }
    case LightKind::Sphere: return kernel::intersect(kernel::Sphere{l.position, l.radius, 0}, ray, t_min, t_max);
    default: return kInfinity;
  }
}

}  // namespace strahl
