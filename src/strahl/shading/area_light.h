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

  // Samples u[0..n) into out[0..n), n ≤ N: sample(u[i]) for each, bit for bit, but with the
  // samples side by side in arrays the compiler vectorises.
  template <int N>
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void sample_lanes(const Vec2 (&u)[N], int n, AreaLightSample (&out)[N]) const {
    if (!lit_) {
      for (int i = 0; i < n; ++i) out[i] = AreaLightSample{};
      return;
    }
    Real ux[N], uy[N];
    for (int i = 0; i < N; ++i) {
      ux[i] = i < n ? u[i].x : Real(0.5);
      uy[i] = i < n ? u[i].y : Real(0.5);
    }
    if (l_.kind == LightKind::Sphere) {
      sphere_lanes(ux, uy, n, out);
      return;
    }
    // The point on the light: the rectangle's directly, the disk's by square_to_disk.
    Real px[N], py[N], pz[N];
    if (l_.kind == LightKind::Rect) {
      for (int i = 0; i < N; ++i) {
        px[i] = l_.position.x + l_.edge_u.x * ux[i] + l_.edge_v.x * uy[i];
        py[i] = l_.position.y + l_.edge_u.y * ux[i] + l_.edge_v.y * uy[i];
        pz[i] = l_.position.z + l_.edge_u.z * ux[i] + l_.edge_v.z * uy[i];
      }
    } else {
      for (int i = 0; i < N; ++i) {
        const Vec2 d = square_to_disk({ux[i], uy[i]});
        px[i] = l_.position.x + (frame_.u.x * d.x + frame_.v.x * d.y) * l_.radius;
        py[i] = l_.position.y + (frame_.u.y * d.x + frame_.v.y * d.y) * l_.radius;
        pz[i] = l_.position.z + (frame_.u.z * d.x + frame_.v.z * d.y) * l_.radius;
      }
    }
    // What sample() makes of the point: direction, distance, the cosine at the light, intensity.
    Real tx[N], ty[N], tz[N], distance[N], factor[N];
    bool seen[N], lit[N];
    for (int i = 0; i < N; ++i) {
      const Real dx = px[i] - p_.x, dy = py[i] - p_.y, dz = pz[i] - p_.z;
      const Real r2 = dx * dx + dy * dy + dz * dz;
      distance[i] = std::sqrt(r2);
      const Real inv = Real(1) / distance[i];
      seen[i] = distance[i] > 0;
      tx[i] = seen[i] ? dx * inv : Real(0);
      ty[i] = seen[i] ? dy * inv : Real(0);
      tz[i] = seen[i] ? dz * inv : Real(0);
      const Real cos_light = -(tx[i] * l_.normal.x + ty[i] * l_.normal.y + tz[i] * l_.normal.z);
      lit[i] = seen[i] && cos_light > 0;
      factor[i] = cos_light * area_ / (kPi * r2);
    }
    for (int i = 0; i < n; ++i) {
      AreaLightSample& s = out[i];
      s.point = Vec3(px[i], py[i], pz[i]);
      s.pdf = 1 / area_;
      s.distance = distance[i];
      s.to_light = Vec3(tx[i], ty[i], tz[i]);
      s.intensity = lit[i] ? l_.radiance * factor[i] : Vec3(0);
    }
  }

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
  template <int N>
  STRAHL_HOST_DEVICE STRAHL_FORCE_INLINE void sphere_lanes(const Real (&ux)[N], const Real (&uy)[N], int n,
                                                           AreaLightSample (&out)[N]) const {
    // square_to_uniform_cone, frame_.to_world and normalize, as sample() calls them.
    Real z[N], r[N], cos_phi[N], sin_phi[N];
    for (int i = 0; i < N; ++i) {
      z[i] = 1 - ux[i] * (1 - cos_max_);
      r[i] = sqrt_clamped(1 - z[i] * z[i]);
      const SinCos phi = sin_cos_pi(2 * uy[i]);  // φ = 2π·u.y
      cos_phi[i] = phi.cos;
      sin_phi[i] = phi.sin;
    }
    // The rays from p in those directions and where they meet the sphere: kernel::intersect's
    // answers, bit for bit, from its lane form (accel/packet.h).
    PacketRays<N> rays;
    Real t_min[N], t_max[N], t[N];
    for (int i = 0; i < N; ++i) {
      const Real lx = r[i] * cos_phi[i], ly = r[i] * sin_phi[i], lz = z[i];
      const Real wx = frame_.u.x * lx + frame_.v.x * ly + frame_.w.x * lz;
      const Real wy = frame_.u.y * lx + frame_.v.y * ly + frame_.w.y * lz;
      const Real wz = frame_.u.z * lx + frame_.v.z * ly + frame_.w.z * lz;
      const Real inv = Real(1) / std::sqrt(wx * wx + wy * wy + wz * wz);
      rays.ox[i] = p_.x, rays.oy[i] = p_.y, rays.oz[i] = p_.z, rays.time[i] = 0;
      rays.dx[i] = wx * inv, rays.dy[i] = wy * inv, rays.dz[i] = wz * inv;
      t_min[i] = 0, t_max[i] = kInfinity;
    }
    const kernel::Sphere sphere{l_.position, l_.radius, 0};
    if (!intersect_sphere_lanes<N>(sphere, rays, t_min, t_max, t))
      for (int i = 0; i < N; ++i) t[i] = kInfinity;
    // Grazing directions numerically missing the sphere take the tangent point's distance.
    for (int i = 0; i < N; ++i)
      if (t[i] == kInfinity) t[i] = axis_.x * rays.dx[i] + axis_.y * rays.dy[i] + axis_.z * rays.dz[i];
    for (int i = 0; i < n; ++i) {
      AreaLightSample& s = out[i];
      s.to_light = Vec3(rays.dx[i], rays.dy[i], rays.dz[i]);
      s.pdf = pdf_;
      s.distance = t[i];
      s.point = p_ + s.to_light * t[i];
      s.intensity = intensity_;
    }
  }

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
