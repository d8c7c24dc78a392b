#pragma once
// Implicit surfaces f(x, y, z) = 0 (lecture 2.1: "Schnittpunktberechnung: finde f(e + t(s − e)) = 0")
// inside a bound, as a closed solid: the points of the bound where f < 0. Its surface is f = 0
// within the bound, plus the bound's own surface where f < 0 there (as POV-Ray's isosurface).
//
// The nearest root along the ray is found, per object, by one of three methods:
//   Lipschitz   POV-Ray's isosurface: with L = max_gradient an upper bound of |∇f|, an interval
//               [t0, t1] of the ray cannot hold a root when |f0| + |f1| > L·|d|·(t1 − t0); the
//               others are bisected, front to back, down to `accuracy` (a distance).
//   SphereTrace Hart 1996, for f a signed distance (|∇f| ≤ L): step by |f|/L, at least `accuracy`.
//   March       the lecture's iterative ray marching: fixed steps of `step` from the bound's
//               entry, the first sample on the other side of the surface ends the march.
// Each ends with a bracket [a, b] over which f changes side (f < 0 against f ≥ 0), bisected down
// to `accuracy` and then polished by the Illinois method until the root is known to ~1e-10 of
// the scene's scale, so that secondary rays leave from the right side of the surface.
//
// Lipschitz and sphere tracing note the steepest secant |Δf|/distance met between two samples
// (ImplicitStats::max_gradient): above L, roots may have been missed. Every query stops after
// kMaxImplicitEvaluations evaluations of f (counted in ImplicitStats::exhausted).

#include <cmath>
#include <cstdint>

#include "strahl/geometry/expression.h"
#include "strahl/math/ray.h"

namespace strahl::kernel {

enum class RootMethod : std::uint8_t { Lipschitz, SphereTrace, March };
enum class ImplicitBound : std::uint8_t { Box, Sphere };

// Evaluations of f one query may spend; the scene compiler keeps accuracy and step large enough
// (scene/validate.h) that no ordinary surface comes near it.
inline constexpr int kMaxImplicitEvaluations = 1 << 16;
// Pending interval ends of the Lipschitz bisection: 2^40 times the accuracy spans any bound the
// compiler accepts (it asks for bound diameter / accuracy ≤ 2^20).
inline constexpr int kMaxBisectionDepth = 40;
inline constexpr int kPolishSteps = 32;

struct Implicit {
  Expression f;
  ImplicitBound bound = ImplicitBound::Box;
  Vec3 lo{-1}, hi{1};            // Box
  Vec3 center{0};                // Sphere
  Real radius = 1;               // Sphere
  RootMethod method = RootMethod::Lipschitz;
  Real max_gradient = 1.1;       // L (Lipschitz, SphereTrace)
  Real accuracy = 1e-3;          // the bisection stops at brackets this long (a distance)
  Real step = 0;                 // March
  Real normal_step = 1e-6;       // h of the central differences of the normal
  std::uint32_t material = 0;
};

// What the root finding met, per object; the renderer keeps one per tile and merges them.
struct ImplicitStats {
  Real max_gradient = 0;        // steepest |Δf| per unit distance between two samples on a ray
  std::uint64_t exhausted = 0;  // queries that gave up after kMaxImplicitEvaluations

  STRAHL_HOST_DEVICE void merge(const ImplicitStats& o) {
    if (o.max_gradient > max_gradient) max_gradient = o.max_gradient;
    exhausted += o.exhausted;
  }
};

// Inside the solid: f < 0. NaN and f = 0 count as outside.
STRAHL_HOST_DEVICE inline bool inside_value(Real f) { return f < 0; }

STRAHL_HOST_DEVICE inline bool in_bound(const Implicit& s, const Vec3& p) {
  if (s.bound == ImplicitBound::Sphere) return length_squared(p - s.center) <= s.radius * s.radius;
  return p.x >= s.lo.x && p.x <= s.hi.x && p.y >= s.lo.y && p.y <= s.hi.y && p.z >= s.lo.z && p.z <= s.hi.z;
}

// The inside test of the solid (CSG, media): within the bound and f < 0.
STRAHL_HOST_DEVICE inline bool inside(const Implicit& s, const Vec3& p) {
  return in_bound(s, p) && inside_value(evaluate(s.f, p));
}

// The ray's parameter range [ta, tb] inside the bound (unclipped); false when it misses.
STRAHL_HOST_DEVICE inline bool bound_range(const Implicit& s, const Ray& ray, Real& ta, Real& tb) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  if (s.bound == ImplicitBound::Sphere) {
    const Vec3 f = o - s.center;
    const Real a = dot(d, d);
    const Real mid = -dot(f, d) / a;       // nearest approach to the centre
    const Vec3 l = f + d * mid;
    const Real disc = s.radius * s.radius - dot(l, l);
    if (!(disc >= 0)) return false;
    const Real half = std::sqrt(disc / a);
    ta = mid - half;
    tb = mid + half;
    return true;
  }
  ta = -kInfinity;
  tb = kInfinity;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (o[k] < s.lo[k] || o[k] > s.hi[k]) return false;
      continue;
    }
    const Real inv = Real(1) / d[k];
    Real t0 = (s.lo[k] - o[k]) * inv, t1 = (s.hi[k] - o[k]) * inv;
    if (t0 > t1) { const Real tmp = t0; t0 = t1; t1 = tmp; }
    ta = t0 > ta ? t0 : ta;
    tb = t1 < tb ? t1 : tb;
  }
  return ta <= tb;
}

// Outward normal of the bound at a point on it (the box face nearest to p).
STRAHL_HOST_DEVICE inline Vec3 bound_normal(const Implicit& s, const Vec3& p) {
  if (s.bound == ImplicitBound::Sphere) return normalize(p - s.center);
  int axis = 0;
  Real best = kInfinity, sign = 1;
  for (int k = 0; k < 3; ++k) {
    const Real dl = std::fabs(p[k] - s.lo[k]), dh = std::fabs(p[k] - s.hi[k]);
    if (dl < best) { best = dl; axis = k; sign = -1; }
    if (dh < best) { best = dh; axis = k; sign = 1; }
  }
  return axis == 0 ? Vec3(sign, 0, 0) : axis == 1 ? Vec3(0, sign, 0) : Vec3(0, 0, sign);
}

// Outward unit normal: the bound's where the hit is on it, else ∇f by central differences.
STRAHL_HOST_DEVICE inline Vec3 normal_at(const Implicit& s, const Vec3& p, bool on_bound) {
  if (on_bound) return bound_normal(s, p);
  const Real h = s.normal_step;
  const Vec3 g{evaluate(s.f, {p.x + h, p.y, p.z}) - evaluate(s.f, {p.x - h, p.y, p.z}),
               evaluate(s.f, {p.x, p.y + h, p.z}) - evaluate(s.f, {p.x, p.y - h, p.z}),
               evaluate(s.f, {p.x, p.y, p.z + h}) - evaluate(s.f, {p.x, p.y, p.z - h})};
  const Real l = length(g);
  if (!(l > 0) || !(l < kInfinity)) return bound_normal(s, p);  // flat or undefined f: any normal will do
  return g / l;
}

// ---- root finding along one ray ----

struct RaySample {
  Real t = 0, f = 0;
};

// [a, b] with a.t < b.t over which f changes side.
struct Bracket {
  RaySample a, b;
};

struct ImplicitQuery {
  const Implicit& s;
  const Ray& ray;
  ImplicitStats& stats;
  Real speed = length(ray.direction);  // distance per unit of t
  Real limit = kInfinity;              // no bracket is looked for beyond this t
  int evaluations = 0;
  bool any = false;                    // any crossing before `limit` will do (shadow rays)

  STRAHL_HOST_DEVICE RaySample sample(Real t) {
    ++evaluations;
    return {t, evaluate(s.f, ray.at(t))};
  }
  STRAHL_HOST_DEVICE bool out_of_budget() {
    if (evaluations < kMaxImplicitEvaluations) return false;
    if (evaluations++ == kMaxImplicitEvaluations) ++stats.exhausted;  // counted once per query
    return true;
  }
  // The secant slope between two samples, for the max_gradient check (divides only when it is
  // steeper than any met so far).
  STRAHL_HOST_DEVICE void slope(const RaySample& a, const RaySample& b) {
    const Real df = std::fabs(b.f - a.f), dt = speed * (b.t - a.t);
    if (!(df > stats.max_gradient * dt)) return;
    const Real g = df / dt;
    if (g > stats.max_gradient) stats.max_gradient = g;
  }
};

STRAHL_HOST_DEVICE inline bool changes_side(const RaySample& a, const RaySample& b) {
  return inside_value(a.f) != inside_value(b.f);
}

// Lipschitz bisection, front to back: the stack holds the right ends of the intervals still to
// look at; the current interval runs from `a` to the top.
STRAHL_HOST_DEVICE inline bool lipschitz_bracket(ImplicitQuery& q, RaySample a, const RaySample& b, Bracket& out) {
  const Real L = q.s.max_gradient * q.speed;  // per unit of t
  const Real inv_L = Real(1) / L;
  const Real shortest = q.s.accuracy / q.speed;
  RaySample stack[kMaxBisectionDepth];
  int n = 0;
  stack[n++] = b;
  RaySample prev;  // the sample `a` was before it moved on (once moved)
  bool moved = false;
  while (n > 0 && a.t < q.limit) {
    const RaySample e = stack[n - 1];
    q.slope(a, e);
    const bool change = changes_side(a, e);
    const Real len = e.t - a.t;
    if (!change && std::fabs(a.f) + std::fabs(e.f) > L * len) {  // no root can fit in between
      prev = a;
      moved = true;
      a = e;
      --n;
      continue;
    }
    if (change && q.any && e.t < q.limit) {  // a crossing before the limit: enough for a shadow ray
      out = {a, e};
      return true;
    }
    // No root lies within |f(a)|/L of a nor within |f(e)|/L of e: every root is in [lo, hi] (plain
    // bisection of [a, e] where L does not hold or f is not finite). Roots closer together than
    // `accuracy` cannot be told apart: the interval is done once [lo, hi] is that short (with a
    // change of side, refine() finds one of its roots; they all lie within `accuracy`).
    Real mid = a.t + Real(0.5) * len, open = len;
    const Real fa = std::fabs(a.f);
    const Real lo = a.t + fa * inv_L, hi = e.t - std::fabs(e.f) * inv_L;
    if (lo < hi) {
      open = hi - lo;
      // With a change of side the split goes near lo, where the first root can be soonest: most
      // of the time its left part changes side too and the interval shrinks to the first root
      // in fewer samples than by halves (measured on scenes/shapes-pov.yaml's isosurface).
      mid = lo + (change ? Real(0.1) : Real(0.5)) * (hi - lo);
      if (!change) {
        if (fa * inv_L < shortest) {
          // f(a) ~ 0 (a ray leaving the surface): a split 2·accuracy away, not halves down to a.
          const Real c = a.t + 2 * shortest;
          if (c < mid) mid = c;
        } else if (moved && fa > std::fabs(prev.f)) {
          // |f| rose from the sample before a at a slope s: were it to go on so, [a, c] with
          // c = a + 1.95·|f(a)|/(L − s) would be ruled out whole by c's own sample (at 2: just).
          // Steps grow geometrically away from a surface, where halving would come back down.
          const Real s = (fa - std::fabs(prev.f)) / (a.t - prev.t);
          if (s < L) {
            const Real c = a.t + Real(1.95) * fa / (L - s);
            if (c < mid) mid = c;
          }
        }
      }
    }
    if (open <= shortest || n == kMaxBisectionDepth || !(mid > a.t && mid < e.t) || q.out_of_budget()) {
      if (change) {
        out = {a, e};
        return true;
      }
      if (q.out_of_budget()) return false;
      prev = a;
      moved = true;
      a = e;  // no root seen at this resolution
      --n;
      continue;
    }
    stack[n++] = q.sample(mid);
  }
  return false;
}

// Sphere tracing: f bounds the distance to the surface, so a step of |f|/L cannot pass a root.
STRAHL_HOST_DEVICE inline bool sphere_trace_bracket(ImplicitQuery& q, RaySample a, const RaySample& b, Bracket& out) {
  const Real L = q.s.max_gradient * q.speed;
  const Real shortest = q.s.accuracy / q.speed;
  while (a.t < q.limit && !q.out_of_budget()) {
    Real step = std::fabs(a.f) / L;
    if (!(step >= shortest)) step = shortest;  // NaN too
    const Real t = a.t + step;
    const RaySample c = t < b.t ? q.sample(t) : b;
    q.slope(a, c);
    if (changes_side(a, c)) {
      out = {a, c};
      return true;
    }
    if (!(t < b.t)) return false;
    a = c;
  }
  return false;
}

// The lecture's ray marching: samples at a fixed spacing from the start; the first one found on
// the other side of the surface ends it.
STRAHL_HOST_DEVICE inline bool march_bracket(ImplicitQuery& q, RaySample a, const RaySample& b, Bracket& out) {
  const Real start = a.t, dt = q.s.step / q.speed;
  for (int k = 1; a.t < q.limit && !q.out_of_budget(); ++k) {
    const Real t = start + Real(k) * dt;
    const RaySample c = t < b.t ? q.sample(t) : b;
    if (changes_side(a, c)) {
      out = {a, c};
      return true;
    }
    if (!(t < b.t)) return false;
    a = c;
  }
  return false;
}

STRAHL_HOST_DEVICE inline bool find_bracket(ImplicitQuery& q, const RaySample& a, const RaySample& b, Bracket& out) {
  switch (q.s.method) {
    case RootMethod::SphereTrace: return sphere_trace_bracket(q, a, b, out);
    case RootMethod::March: return march_bracket(q, a, b, out);
    case RootMethod::Lipschitz: break;
  }
  return lipschitz_bracket(q, a, b, out);
}

// Bisection of the bracket down to `accuracy`.
STRAHL_HOST_DEVICE inline void bisect(ImplicitQuery& q, Bracket& br) {
  const Real shortest = q.s.accuracy / q.speed;
  while (br.b.t - br.a.t > shortest) {
    const Real mid = br.a.t + Real(0.5) * (br.b.t - br.a.t);
    if (!(mid > br.a.t && mid < br.b.t)) return;
    const RaySample m = q.sample(mid);
    (changes_side(br.a, m) ? br.b : br.a) = m;
  }
}

// The root in a bracket: Illinois steps (regula falsi that halves the value kept at an end
// chosen twice in a row) until the bracket is within ~1e-10 of the scene's scale, then bisection
// to `accuracy` should they not have got there; returns the interpolated root, and leaves the
// bracket around it. Brackets of sphere tracing and marching are bisected to `accuracy` first
// (they may hold several roots further apart; a Lipschitz bracket's roots all lie within
// `accuracy`). A secant step landing within half the tolerance of an end goes that far in: at a
// root found all but exactly, the next sample closes the bracket instead of halving it.
STRAHL_HOST_DEVICE inline Real refine(ImplicitQuery& q, Bracket& br) {
  if (q.s.method != RootMethod::Lipschitz) bisect(q, br);
  const Real scale = Real(1) + max_abs_component(q.ray.at(br.b.t));
  const Real tolerance = Real(1e-10) * scale / q.speed;
  Real fa = br.a.f, fb = br.b.f;
  int kept = 0;  // +1: a kept last time, −1: b
  for (int i = 0; i < kPolishSteps && br.b.t - br.a.t > tolerance; ++i) {
    Real t = br.b.t - fb * (br.b.t - br.a.t) / (fb - fa);
    if (t == t) {  // NaN: bisection below
      const Real nudge = Real(0.5) * tolerance;
      if (!(t > br.a.t + nudge)) t = br.a.t + nudge;
      else if (!(t < br.b.t - nudge)) t = br.b.t - nudge;
    }
    if (!(t > br.a.t && t < br.b.t)) t = br.a.t + Real(0.5) * (br.b.t - br.a.t);
    if (!(t > br.a.t && t < br.b.t)) break;
    const RaySample m = q.sample(t);
    if (changes_side(br.a, m)) {
      br.b = m;
      fb = m.f;
      if (kept == 1) fa *= Real(0.5);
      kept = 1;
    } else {
      br.a = m;
      fa = m.f;
      if (kept == -1) fb *= Real(0.5);
      kept = -1;
    }
  }
  bisect(q, br);
  const Real t = br.b.t - br.b.f * (br.b.t - br.a.t) / (br.b.f - br.a.f);
  return t >= br.a.t && t <= br.b.t ? t : br.a.t + Real(0.5) * (br.b.t - br.a.t);
}

struct ImplicitCrossing {
  Real t = kInfinity;
  bool on_bound = false;  // the bound's surface (where f < 0 on it), not f = 0
  bool entering = false;  // from outside the solid to inside
};

// Every crossing of the solid's surface in (t_min, t_max), front to back: calls
// visit(const ImplicitCrossing&), which returns true to stop.
template <class Visit>
STRAHL_HOST_DEVICE inline void for_each_implicit_crossing(const Implicit& s, const Ray& ray, Real t_min, Real t_max,
                                                          ImplicitStats& stats, Visit&& visit) {
  Real ta = 0, tb = 0;
  if (!bound_range(s, ray, ta, tb) || !(tb > t_min) || !(ta < t_max)) return;
  ImplicitQuery q{s, ray, stats};
  RaySample a;
  if (ta > t_min) {
    a = q.sample(ta);
    if (inside_value(a.f) && visit(ImplicitCrossing{ta, true, true})) return;
  } else {
    a = q.sample(t_min);
  }
  // The search always runs to the bound's exit, stopping once past t_max: the samples, and so
  // the roots found, do not depend on t_max (every acceleration structure, whatever nearer hit
  // it has found already, gets the same root, bit for bit).
  const RaySample b = q.sample(tb);
  q.limit = t_max;
  Bracket br;
  while (a.t < b.t && a.t < t_max && find_bracket(q, a, b, br)) {
    const Real t = refine(q, br);
    if (!(t < t_max)) return;
    if (t > t_min && visit(ImplicitCrossing{t, false, inside_value(br.b.f)})) return;
    a = br.b;  // beyond the root
  }
  if (tb < t_max && inside_value(b.f)) visit(ImplicitCrossing{tb, true, false});
}

// The nearest crossing in (t_min, t_max); t = kInfinity when there is none.
STRAHL_HOST_DEVICE inline ImplicitCrossing intersect(const Implicit& s, const Ray& ray, Real t_min, Real t_max,
                                                     ImplicitStats& stats) {
  ImplicitCrossing first;
  for_each_implicit_crossing(s, ray, t_min, t_max, stats, [&](const ImplicitCrossing& c) {
    first = c;
    return true;
  });
  return first;
}

// Is there any crossing in (t_min, t_max)? (shadow rays) The same search as
// for_each_implicit_crossing(), which ends at the first change of side seen wholly before t_max:
// that holds a crossing, whichever it is, so it is neither narrowed down to the first root nor
// refined. The answer is intersect()'s (t < kInfinity) in far fewer evaluations of f.
STRAHL_HOST_DEVICE inline bool any_crossing(const Implicit& s, const Ray& ray, Real t_min, Real t_max,
                                            ImplicitStats& stats) {
  Real ta = 0, tb = 0;
  if (!bound_range(s, ray, ta, tb) || !(tb > t_min) || !(ta < t_max)) return false;
  ImplicitQuery q{s, ray, stats};
  RaySample a;
  if (ta > t_min) {
    a = q.sample(ta);
    if (inside_value(a.f)) return true;  // the bound's surface, at ta in (t_min, t_max)
  } else {
    a = q.sample(t_min);
  }
  const RaySample b = q.sample(tb);
  q.limit = t_max;
  q.any = true;
  Bracket br;
  while (a.t < b.t && a.t < t_max && find_bracket(q, a, b, br)) {
    if (br.b.t < t_max) return true;  // a root in (br.a.t, br.b.t], and br.a.t >= t_min
    const Real t = refine(q, br);      // the bracket reaches past t_max: where is its root?
    if (!(t < t_max)) return false;
    if (t > t_min) return true;
    a = br.b;
  }
  return tb < t_max && inside_value(b.f);
}

// How many times (t_min, t_max) crosses the surface (shadow rays through transparent solids).
STRAHL_HOST_DEVICE inline int crossings(const Implicit& s, const Ray& ray, Real t_min, Real t_max,
                                        ImplicitStats& stats) {
  int n = 0;
  for_each_implicit_crossing(s, ray, t_min, t_max, stats, [&](const ImplicitCrossing&) {
    ++n;
    return false;
  });
  return n;
}

}  // namespace strahl::kernel
