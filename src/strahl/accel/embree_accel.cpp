#include "strahl/accel/embree_accel.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "strahl/accel/accel.h"
#include "strahl/accel/embree_range.h"

namespace strahl {

namespace {

// Geometry ids in every strahl Embree scene.
constexpr unsigned kTriangleGeometry = 0;
constexpr unsigned kSphereGeometry = 1;

// ---- the device: one per process, shared by every scene (each scene holds a reference) ----

// Net bytes Embree has allocated, from its memory monitor; build_embree reads the difference
// across a build. (Builds running at the same time in other threads would be counted too.)
std::atomic<long long> g_embree_bytes{0};

bool memory_monitor(void*, ssize_t bytes, bool) {
  g_embree_bytes.fetch_add(static_cast<long long>(bytes), std::memory_order_relaxed);
  return true;  // never refuse an allocation
}

// The last error Embree reported on this thread (Embree calls the error function on the thread
// that made the failing call).
thread_local std::string t_embree_error;

void error_function(void*, RTCError code, const char* message) {
  t_embree_error = std::string("Embree error ") + std::to_string(int(code)) + ": " + (message ? message : "");
}

struct SharedDevice {
  RTCDevice device = nullptr;
  SharedDevice() {
    device = rtcNewDevice(nullptr);
    if (device == nullptr)
      throw std::runtime_error("Embree: cannot create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) +
                               ")");
    rtcSetDeviceErrorFunction(device, error_function, nullptr);
    rtcSetDeviceMemoryMonitorFunction(device, memory_monitor, nullptr);
  }
  ~SharedDevice() { rtcReleaseDevice(device); }
  SharedDevice(const SharedDevice&) = delete;
  SharedDevice& operator=(const SharedDevice&) = delete;
};

RTCDevice shared_device() {
  static SharedDevice shared;  // created on first use, thread-safe
  return shared.device;
}

void check(RTCDevice device, const char* what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code == RTC_ERROR_NONE) return;
  std::string message = t_embree_error.empty() ? "Embree error " + std::to_string(int(code)) : t_embree_error;
  t_embree_error.clear();
  throw std::runtime_error(std::string(what) + ": " + message);
}

// ---- queries ----

// A ray Embree would refuse (an origin beyond ±1.8e18 fails its ray.valid()) or misjudge in float:
// the naive loop answers it instead (accel/embree_range.h). Hits on planes far out make such rays.
namespace {
bool beyond_float(const Ray& ray) { return !(max_abs_component(ray.origin) <= kEmbreeMaxCoordinate); }
AccelView naive(const AccelView& a) {
  AccelView v = a;
  v.kind = AccelKind::Naive;
  return v;
}
}  // namespace

// What the callbacks (sphere intersection, triangle filter) need besides the float ray Embree
// hands them: the original double ray, the primitives and the double interval. Embree passes
// &rtc to the callbacks, and rtc is the first member, so they can reach the rest.
struct QueryContext {
  RTCIntersectContext rtc;
  bool packet = false;  // false: this QueryContext; true: a PacketContext (below)
  const kernel::Sphere* spheres = nullptr;
  const kernel::Triangle* triangles = nullptr;
  const Ray* ray = nullptr;
  Real t_min = 0, t_max = kInfinity;  // the query's interval
  float check_below = 0;              // triangle hits nearer than this are checked in double
  Real sphere_t_min = 0;              // spheres: roots beyond this (for_each_crossing steps it)
  Real sphere_t = kInfinity;          // nearest sphere hit so far (intersect queries)
  std::uint32_t sphere = 0;
};
static_assert(std::is_standard_layout_v<QueryContext> && offsetof(QueryContext, rtc) == 0);

// The same for a packet (rtcIntersect8/16, rtcOccluded8/16): per lane. Embree may call the
// callbacks with another packet size than the one traced (single-ray mode inside a packet), so the
// callbacks find a ray's lane by its id, which is set to the lane.
struct PacketContext {
  RTCIntersectContext rtc;
  bool packet = true;
  const kernel::Sphere* spheres = nullptr;
  const kernel::Triangle* triangles = nullptr;
  const Ray* rays = nullptr;
  Real t_min[kEmbreeMaxPacket], t_max[kEmbreeMaxPacket];
  float check_below[kEmbreeMaxPacket];
  Real sphere_t[kEmbreeMaxPacket];
  std::uint32_t sphere[kEmbreeMaxPacket];
};
static_assert(std::is_standard_layout_v<PacketContext> && offsetof(PacketContext, rtc) == 0 &&
              offsetof(PacketContext, packet) == offsetof(QueryContext, packet));

bool is_packet(const RTCIntersectContext* c) { return reinterpret_cast<const QueryContext*>(c)->packet; }

void init_context(QueryContext& ctx, const AccelView& a, const Ray& ray, Real t_min, Real t_max) {
  rtcInitIntersectContext(&ctx.rtc);
  ctx.spheres = a.prims.spheres;
  ctx.triangles = a.prims.triangles;
  ctx.ray = &ray;
  ctx.t_min = ctx.sphere_t_min = t_min;
  ctx.t_max = t_max;
  ctx.check_below = float(kEmbreeCheckDistance * (1 + max_abs_component(ray.origin)));
}

void set_ray(RTCRay& r, const Ray& ray, Real t_near, Real t_far) {
  r.org_x = float(ray.origin.x);
  r.org_y = float(ray.origin.y);
  r.org_z = float(ray.origin.z);
  r.dir_x = float(ray.direction.x);
  r.dir_y = float(ray.direction.y);
  r.dir_z = float(ray.direction.z);
  r.tnear = float(t_near);
  r.tfar = float(t_far);  // ∞ stays ∞
  r.time = 0;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
}

RTCRayHit make_rayhit(const Ray& ray, Real t_near, Real t_far) {
  RTCRayHit rh;
  set_ray(rh.ray, ray, t_near, t_far);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rh.hit.u = rh.hit.v = 0;
  rh.hit.Ng_x = rh.hit.Ng_y = rh.hit.Ng_z = 0;
  return rh;
}

RTCScene scene_of(const AccelView& a) { return static_cast<RTCScene>(a.embree); }

// Embree's triangle hit recomputed in double, with kernel::intersect's own arithmetic (without its
// inside and range checks): where the ray meets the triangle's plane, and the barycentrics there.
// Float found the hit; rounding can put it a hair outside the triangle, which double then reports
// as slightly negative barycentrics rather than a miss.
kernel::TriangleHit refine(const kernel::Triangle& tri, const Ray& ray, const RTCRayHit& rh) {
  const kernel::TriangleHit h = kernel::plane_hit(tri, ray, kernel::ray_shear(ray.direction));
  if (!(h.t < kInfinity)) return {Real(rh.ray.tfar), Real(rh.hit.u), Real(rh.hit.v)};
  return h;
}

// ---- the spheres: a user geometry running strahl's own double-precision test ----

float round_down(Real x) {
  const float f = float(x);
  return Real(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(Real x) {
  const float f = float(x);
  return Real(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// Build time only: the user pointer is the PrimitiveSet's sphere array as it was during the build.
void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* spheres = static_cast<const kernel::Sphere*>(args->geometryUserPtr);
  const kernel::Sphere& s = spheres[args->primID];
  RTCBounds& b = *args->bounds_o;
  b.lower_x = round_down(s.center.x - s.radius);
  b.lower_y = round_down(s.center.y - s.radius);
  b.lower_z = round_down(s.center.z - s.radius);
  b.upper_x = round_up(s.center.x + s.radius);
  b.upper_y = round_up(s.center.y + s.radius);
  b.upper_z = round_up(s.center.z + s.radius);
}

// Packets: every valid lane of the RTCRayHitN, each with its own lane's double ray.
void sphere_intersect_packet(const RTCIntersectFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<PacketContext*>(args->context);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const unsigned lane = RTCRayN_id(ray, args->N, i);
    const kernel::Sphere& s = ctx->spheres[args->primID];
    const Real t_hi = ctx->sphere_t[lane] < ctx->t_max[lane] ? ctx->sphere_t[lane] : ctx->t_max[lane];
    const Real t = kernel::intersect(s, ctx->rays[lane], ctx->t_min[lane], t_hi);
    if (!(t < kInfinity)) continue;
    const float tf = float(t);
    if (tf > RTCRayN_tfar(ray, args->N, i)) continue;
    RTCRayN_tfar(ray, args->N, i) = tf;
    const Vec3 n = kernel::normal_at(s, ctx->rays[lane].at(t));
    RTCHitN_Ng_x(hit, args->N, i) = float(n.x);
    RTCHitN_Ng_y(hit, args->N, i) = float(n.y);
    RTCHitN_Ng_z(hit, args->N, i) = float(n.z);
    RTCHitN_u(hit, args->N, i) = RTCHitN_v(hit, args->N, i) = 0;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
    ctx->sphere_t[lane] = t;
    ctx->sphere[lane] = args->primID;
  }
}

// Single rays (rtcIntersect1 / rtcOccluded1): N is 1 and the ray is an RTCRayHit / RTCRay.
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (is_packet(args->context)) return sphere_intersect_packet(args);
  if (args->N != 1 || !args->valid[0]) return;
  auto* ctx = reinterpret_cast<QueryContext*>(args->context);
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const kernel::Sphere& s = ctx->spheres[args->primID];
  const Real t_hi = ctx->sphere_t < ctx->t_max ? ctx->sphere_t : ctx->t_max;
  const Real t = kernel::intersect(s, *ctx->ray, ctx->sphere_t_min, t_hi);
  if (!(t < kInfinity)) return;
  const float tf = float(t);
  if (tf > rh->ray.tfar) return;  // a triangle is nearer
  rh->ray.tfar = tf;
  const Vec3 n = kernel::normal_at(s, ctx->ray->at(t));
  rh->hit.Ng_x = float(n.x);
  rh->hit.Ng_y = float(n.y);
  rh->hit.Ng_z = float(n.z);
  rh->hit.u = rh->hit.v = 0;
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
  ctx->sphere_t = t;
  ctx->sphere = args->primID;
}

// Triangles: a hit near the ray's origin may be the surface the ray leaves, which the float ray
// (its origin rounded, losing strahl's tiny offset) can meet at a small t. Strahl's double test
// decides such hits: it rejects them when it sees no hit in (t_min, ∞).
void triangle_filter_packet(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const PacketContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const unsigned lane = RTCRayN_id(args->ray, args->N, i);
    if (RTCRayN_tfar(args->ray, args->N, i) >= ctx->check_below[lane]) continue;
    const std::uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    if (!(kernel::intersect(ctx->triangles[prim], ctx->rays[lane], ctx->t_min[lane], kInfinity).t < kInfinity))
      args->valid[i] = 0;
  }
}

void triangle_filter(const RTCFilterFunctionNArguments* args) {
  if (is_packet(args->context)) return triangle_filter_packet(args);
  if (args->N != 1 || !args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const QueryContext*>(args->context);
  const auto* r = reinterpret_cast<const RTCRay*>(args->ray);  // tfar: the candidate hit's distance
  if (r->tfar >= ctx->check_below) return;
  const auto* hit = reinterpret_cast<const RTCHit*>(args->hit);
  if (!(kernel::intersect(ctx->triangles[hit->primID], *ctx->ray, ctx->t_min, kInfinity).t < kInfinity))
    args->valid[0] = 0;
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  if (is_packet(args->context)) {
    const auto* ctx = reinterpret_cast<const PacketContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
      if (!args->valid[i]) continue;
      const unsigned lane = RTCRayN_id(args->ray, args->N, i);
      if (kernel::intersect(ctx->spheres[args->primID], ctx->rays[lane], ctx->t_min[lane], ctx->t_max[lane]) <
          kInfinity)
        RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
    return;
  }
  if (args->N != 1 || !args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const QueryContext*>(args->context);
  auto* r = reinterpret_cast<RTCRay*>(args->ray);
  if (kernel::intersect(ctx->spheres[args->primID], *ctx->ray, ctx->t_min, ctx->t_max) < kInfinity)
    r->tfar = -std::numeric_limits<float>::infinity();
}

}  // namespace

// ---- ownership ----

EmbreeAccel::~EmbreeAccel() { release(); }

void EmbreeAccel::release() noexcept {
  if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
  if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
  scene_ = device_ = nullptr;
}

EmbreeAccel::EmbreeAccel(const EmbreeAccel& other) : device_(other.device_), scene_(other.scene_) {
  if (device_) rtcRetainDevice(static_cast<RTCDevice>(device_));
  if (scene_) rtcRetainScene(static_cast<RTCScene>(scene_));
}

EmbreeAccel& EmbreeAccel::operator=(const EmbreeAccel& other) {
  if (this != &other) {
    EmbreeAccel copy(other);
    *this = std::move(copy);
  }
  return *this;
}

EmbreeAccel::EmbreeAccel(EmbreeAccel&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)), scene_(std::exchange(other.scene_, nullptr)) {}

EmbreeAccel& EmbreeAccel::operator=(EmbreeAccel&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, nullptr);
    scene_ = std::exchange(other.scene_, nullptr);
  }
  return *this;
}

// ---- build ----

EmbreeAccel build_embree(const PrimitiveSet& prims, AccelBuildStats* stats_out) {
  const auto start = std::chrono::steady_clock::now();
  const RTCDevice device = shared_device();
  const long long bytes_before = g_embree_bytes.load();
  t_embree_error.clear();
  rtcGetDeviceError(device);  // clear a stale error code

  EmbreeAccel out;
  rtcRetainDevice(device);
  out.device_ = device;
  const RTCScene scene = rtcNewScene(device);
  check(device, "Embree: rtcNewScene");
  out.scene_ = scene;
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_NONE);

  if (prims.triangle_count > 0) {
    const std::uint32_t n = prims.triangle_count;
    const RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), 3 * std::size_t(n)));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    if (vertices == nullptr || indices == nullptr) {
      rtcReleaseGeometry(geom);
      check(device, "Embree: triangle buffers");
      throw std::runtime_error("Embree: cannot allocate the triangle buffers");
    }
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, 4096), [&](const auto& r) {
      for (std::uint32_t i = r.begin(); i != r.end(); ++i) {
        const kernel::Triangle& t = prims.triangles[i];
        const Vec3 v[3] = {t.v0, t.v1, t.v2};
        float* out_v = vertices + 9 * std::size_t(i);
        for (int k = 0; k < 3; ++k) {
          out_v[3 * k + 0] = float(v[k].x);
          out_v[3 * k + 1] = float(v[k].y);
          out_v[3 * k + 2] = float(v[k].z);
          indices[3 * std::size_t(i) + std::size_t(k)] = 3 * i + unsigned(k);
        }
      }
    });
    rtcSetGeometryIntersectFilterFunction(geom, triangle_filter);
    rtcSetGeometryOccludedFilterFunction(geom, triangle_filter);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, kTriangleGeometry);
    rtcReleaseGeometry(geom);
    check(device, "Embree: triangle geometry");
  }

  if (prims.sphere_count > 0) {
    const RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, prims.sphere_count);
    rtcSetGeometryUserData(geom, const_cast<kernel::Sphere*>(prims.spheres));
    rtcSetGeometryBoundsFunction(geom, sphere_bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, sphere_intersect);
    rtcSetGeometryOccludedFunction(geom, sphere_occluded);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, kSphereGeometry);
    rtcReleaseGeometry(geom);
    check(device, "Embree: sphere geometry");
  }

  rtcCommitScene(scene);
  check(device, "Embree: rtcCommitScene");

  if (stats_out) {
    AccelBuildStats stats;
    stats.primitives = stats.primitive_references = prims.size();
    const long long bytes = g_embree_bytes.load() - bytes_before;
    stats.bytes = bytes > 0 ? std::size_t(bytes) : 0;
    // Embree does not report its node count or depth.
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    *stats_out = stats;
  }
  return out;
}

// ---- queries ----

NearestHit embree_nearest_hit(const AccelView& a, const Ray& ray, Real t_min, Real t_max) {
  if (beyond_float(ray)) return nearest_hit(naive(a), ray, t_min, t_max);
  NearestHit result;
  QueryContext ctx;
  init_context(ctx, a, ray, t_min, t_max);
  RTCRayHit rh = make_rayhit(ray, t_min, t_max);
  rtcIntersect1(scene_of(a), &ctx.rtc, &rh);
  if (rh.hit.geomID == kTriangleGeometry) {
    // The hit refined in double: the same t and barycentrics as strahl's own test, so that the
    // hit point lies on the triangle to double precision and spawn_ray's tiny offset suffices.
    const kernel::TriangleHit h = refine(a.prims.triangles[rh.hit.primID], ray, rh);
    if (h.t > t_min && h.t < t_max) {
      result.prim = a.prims.sphere_count + rh.hit.primID;
      result.hit = h;
    }
  } else if (rh.hit.geomID == kSphereGeometry) {
    result.prim = ctx.sphere;
    result.hit = {ctx.sphere_t, 0, 0};
  }
  return result;
}

bool embree_occluded(const AccelView& a, const Ray& ray, Real t_min, Real t_max) {
  if (beyond_float(ray)) return occluded(naive(a), ray, t_min, t_max);
  QueryContext ctx;
  init_context(ctx, a, ray, t_min, t_max);
  RTCRay r;
  set_ray(r, ray, t_min, t_max);
  rtcOccluded1(scene_of(a), &ctx.rtc, &r);
  return r.tfar < 0;  // Embree sets tfar to −∞ when it finds a hit
}

// ---- packets ----

namespace {

template <int N>
struct alignas(64) EmbreePacket {
  RTCRayHitNt<N> rh;
  alignas(64) int valid[N];
};

// Fills the packet's lanes (inactive ones get a harmless ray and valid = 0) and the context.
template <int N>
std::uint32_t fill_packet(EmbreePacket<N>& p, PacketContext& ctx, const AccelView& a, std::uint32_t active,
                          const Ray* rays, const Real* t_min, const Real* t_max) {
  rtcInitIntersectContext(&ctx.rtc);
  ctx.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  ctx.spheres = a.prims.spheres;
  ctx.triangles = a.prims.triangles;
  ctx.rays = rays;
  for (int i = 0; i < N; ++i) {
    const bool on = (active >> i) & 1u;
    const Ray& ray = on ? rays[i] : rays[0];
    p.valid[i] = on ? -1 : 0;
    p.rh.ray.org_x[i] = on ? float(ray.origin.x) : 0;
    p.rh.ray.org_y[i] = on ? float(ray.origin.y) : 0;
    p.rh.ray.org_z[i] = on ? float(ray.origin.z) : 0;
    p.rh.ray.dir_x[i] = on ? float(ray.direction.x) : 0;
    p.rh.ray.dir_y[i] = on ? float(ray.direction.y) : 0;
    p.rh.ray.dir_z[i] = on ? float(ray.direction.z) : 1;
    p.rh.ray.tnear[i] = on ? float(t_min[i]) : 0;
    p.rh.ray.tfar[i] = on ? float(t_max[i]) : 0;
    p.rh.ray.time[i] = 0;
    p.rh.ray.mask[i] = ~0u;
    p.rh.ray.id[i] = unsigned(i);
    p.rh.ray.flags[i] = 0;
    p.rh.hit.geomID[i] = p.rh.hit.primID[i] = p.rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    ctx.t_min[i] = on ? t_min[i] : 0;
    ctx.t_max[i] = on ? t_max[i] : 0;
    ctx.check_below[i] = on ? float(kEmbreeCheckDistance * (1 + max_abs_component(ray.origin))) : 0;
    ctx.sphere_t[i] = kInfinity;
    ctx.sphere[i] = 0;
  }
  return active;
}

template <int N>
void nearest_packet(const AccelView& a, std::uint32_t active, const Ray* rays, const Real* t_min, const Real* t_max,
                    NearestHit* out) {
  EmbreePacket<N> p;
  PacketContext ctx;
  fill_packet(p, ctx, a, active, rays, t_min, t_max);
  if constexpr (N == 8)
    rtcIntersect8(p.valid, scene_of(a), &ctx.rtc, reinterpret_cast<RTCRayHit8*>(&p.rh));
  else
    rtcIntersect16(p.valid, scene_of(a), &ctx.rtc, reinterpret_cast<RTCRayHit16*>(&p.rh));
  for (int i = 0; i < N; ++i) {
    if (!p.valid[i]) continue;
    NearestHit result;
    if (p.rh.hit.geomID[i] == kTriangleGeometry) {
      const std::uint32_t prim = p.rh.hit.primID[i];
      const kernel::TriangleHit h = kernel::plane_hit(a.prims.triangles[prim], rays[i], kernel::ray_shear(rays[i].direction));
      const kernel::TriangleHit refined =
          h.t < kInfinity ? h : kernel::TriangleHit{Real(p.rh.ray.tfar[i]), Real(p.rh.hit.u[i]), Real(p.rh.hit.v[i])};
      if (refined.t > t_min[i] && refined.t < t_max[i]) {
        result.prim = a.prims.sphere_count + prim;
        result.hit = refined;
      }
    } else if (p.rh.hit.geomID[i] == kSphereGeometry) {
      result.prim = ctx.sphere[i];
      result.hit = {ctx.sphere_t[i], 0, 0};
    }
    out[i] = result;
  }
}

template <int N>
void occluded_packet(const AccelView& a, std::uint32_t active, const Ray* rays, const Real* t_min, const Real* t_max,
                     bool* out) {
  EmbreePacket<N> p;
  PacketContext ctx;
  fill_packet(p, ctx, a, active, rays, t_min, t_max);
  if constexpr (N == 8)
    rtcOccluded8(p.valid, scene_of(a), &ctx.rtc, reinterpret_cast<RTCRay8*>(&p.rh.ray));
  else
    rtcOccluded16(p.valid, scene_of(a), &ctx.rtc, reinterpret_cast<RTCRay16*>(&p.rh.ray));
  for (int i = 0; i < N; ++i)
    if (p.valid[i]) out[i] = p.rh.ray.tfar[i] < 0;
}

// Lanes Embree would refuse or misjudge (beyond_float) are answered one by one; returns the rest.
std::uint32_t packet_lanes(int n, std::uint32_t active, const Ray* rays) {
  if (n != 8 && n != 16) throw std::invalid_argument("Embree packets are 8 or 16 rays, not " + std::to_string(n));
  active &= (1u << n) - 1;
  for (int i = 0; i < n; ++i)
    if (((active >> i) & 1u) && beyond_float(rays[i])) active &= ~(1u << i);
  return active;
}

}  // namespace

int embree_native_packet_width() {
  const RTCDevice device = shared_device();
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 16;
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 8;
  return 1;
}

void embree_nearest_hit_packet(const AccelView& a, int n, std::uint32_t active, const Ray* rays, const Real* t_min,
                               const Real* t_max, NearestHit* out) {
  const std::uint32_t lanes = packet_lanes(n, active, rays);
  for (int i = 0; i < n; ++i)
    if (((active & ~lanes) >> i) & 1u) out[i] = nearest_hit(naive(a), rays[i], t_min[i], t_max[i]);
  if (lanes == 0) return;
  if (n == 8)
    nearest_packet<8>(a, lanes, rays, t_min, t_max, out);
  else
    nearest_packet<16>(a, lanes, rays, t_min, t_max, out);
}

void embree_occluded_packet(const AccelView& a, int n, std::uint32_t active, const Ray* rays, const Real* t_min,
                            const Real* t_max, bool* out) {
  const std::uint32_t lanes = packet_lanes(n, active, rays);
  for (int i = 0; i < n; ++i)
    if (((active & ~lanes) >> i) & 1u) out[i] = occluded(naive(a), rays[i], t_min[i], t_max[i]);
  if (lanes == 0) return;
  if (n == 8)
    occluded_packet<8>(a, lanes, rays, t_min, t_max, out);
  else
    occluded_packet<16>(a, lanes, rays, t_min, t_max, out);
}

void embree_for_each_crossing(const AccelView& a, const Ray& ray, Real t_min, Real t_max, EmbreeCrossFn cross,
                              void* state) {
  if (beyond_float(ray)) {
    auto visit = [&](std::uint32_t prim, int n) { return cross(state, prim, n); };
    return for_each_crossing(naive(a), ray, t_min, t_max, visit);
  }
  // Each round finds the nearest crossing past the previous one: triangles past the float t
  // just reported (the next float up), spheres past the double root just reported.
  QueryContext ctx;
  init_context(ctx, a, ray, t_min, t_max);
  Real triangle_lo = t_min;
  for (;;) {
    ctx.sphere_t = kInfinity;
    RTCRayHit rh = make_rayhit(ray, triangle_lo, t_max);
    rtcIntersect1(scene_of(a), &ctx.rtc, &rh);
    std::uint32_t prim;
    if (rh.hit.geomID == kTriangleGeometry) {
      if (!(Real(rh.ray.tfar) < t_max)) return;
      // Embree's AVX2 kernels can report a hit a float ulp below tnear: the crossing reported
      // in the previous round once more. Step past it without counting it again (else the
      // loop would never end).
      const bool repeat = Real(rh.ray.tfar) < triangle_lo;
      triangle_lo = std::nextafter(repeat ? float(triangle_lo) : rh.ray.tfar, std::numeric_limits<float>::infinity());
      if (repeat) continue;
      prim = a.prims.sphere_count + rh.hit.primID;
    } else if (rh.hit.geomID == kSphereGeometry) {
      prim = ctx.sphere;
      ctx.sphere_t_min = ctx.sphere_t;
    } else {
      return;
    }
    if (cross(state, prim, 1)) return;
  }
}

}  // namespace strahl
