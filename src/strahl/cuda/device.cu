// The CUDA back end's device side: the scene's arrays in device memory, and the kernel that runs
// the existing kernel functions (camera, samplers, the BVH traversal's portable path, shapes,
// materials, the Whitted/distributed integrator, the film's per-sample arithmetic) one thread
// per pixel. Everything the kernel computes comes from the same headers the CPU compiles; this
// file adds only the launch, the uploads and the copies.

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <unordered_map>

#include "strahl/cuda/cuda_backend.h"
#include "strahl/cuda/device.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "kernel_variants.h"

namespace strahl::cuda_detail {


// The scene's arrays are uploaded (Device::upload) and mapped to their device copies
// (Impl::device_view) member by member: a kernel reading an array not uploaded would read host
// memory. So a new member of SceneView, AccelView or PrimitiveSet stops the build here until it
// is uploaded and mapped below — then update these sizes.
// Instance groups are RenderScenes of their own: their arrays are uploaded and mapped the same way
// (copy_scene_arrays, map_accel), and their views (InstanceGroupView) with device pointers.
static_assert(sizeof(SceneView) - sizeof(AccelView) == 624 && sizeof(PrimitiveSet) == 144 &&
#if defined(STRAHL_HAVE_EMBREE)
                  sizeof(AccelView) == 408,
#else
                  sizeof(AccelView) == 400,
#endif
              "SceneView changed: upload and map its new arrays in cuda/device.cu, then update these sizes");
static_assert(sizeof(InstanceGroupView) - sizeof(AccelView) == 16,
              "InstanceGroupView changed: map its new arrays in copy_instances, then update this size");

namespace {

constexpr int kBlock = 128;

// The render kernel's variants: __launch_bounds__(kBlock, m) for each m of
// STRAHL_CUDA_KERNEL_MIN_BLOCKS (kernel_variants.h, generated from CMake's option of that name,
// default 1): ptxas fits the registers so that m blocks of kBlock threads share one multiprocessor
// (1: up to 255 registers; 3: 168; 4: 128). The first is the one strahl renders with; the others
// are for measuring (strahl-gpu-bench --kernels; tools/gpu-check.sh builds 1, 3 and 4).

struct KernelArgs {
  PassArgs pass;                 // device pointers (cuda/flat_pass.h)
  unsigned long long* counters;  // kPassCounters (counter_array)
};

__device__ inline unsigned long long warp_sum(unsigned long long v) {
  for (int offset = 16; offset > 0; offset >>= 1) v += __shfl_down_sync(0xffffffffu, v, offset);
  return v;
}

template <int MinBlocks>
__global__ void __launch_bounds__(kBlock, MinBlocks) render_kernel(const KernelArgs a) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  RayCounters c;
  if (i < a.pass.n)
    render_flat_pixel(a.pass, i, c, [](std::int64_t* q, std::int64_t v) {
      atomicAdd(reinterpret_cast<unsigned long long*>(q), static_cast<unsigned long long>(v));
    });
  // Every thread of the block reaches this point (no early return above).
  unsigned long long v[kPassCounters];
  counter_array(c, v);
  for (int k = 0; k < kPassCounters; ++k) {
    const unsigned long long s = warp_sum(v[k]);
    if ((threadIdx.x & 31) == 0 && s != 0) atomicAdd(&a.counters[k], s);
  }
}

using RenderKernel = void (*)(KernelArgs);
template <int... MinBlocks>
struct KernelList {
  static constexpr RenderKernel kernels[] = {render_kernel<MinBlocks>...};
  static constexpr int min_blocks[] = {MinBlocks...};
};
using RenderKernels = KernelList<STRAHL_CUDA_KERNEL_MIN_BLOCKS>;
constexpr int kKernelCount = int(sizeof(RenderKernels::min_blocks) / sizeof(int));

// Primary rays: the nearest hit of one camera ray through each pixel's centre.
__global__ void __launch_bounds__(kBlock) primary_kernel(const SceneView view, std::uint32_t* out) {
  const int nx = view.camera.nx, ny = view.camera.ny;
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= std::uint32_t(nx) * std::uint32_t(ny)) return;
  const int x = int(i % std::uint32_t(nx)), y = int(i / std::uint32_t(nx));
  const Ray ray = view.camera.generate_ray(Real(x) + Real(0.5), Real(y) + Real(0.5));
  const Hit h = closest_hit(view, ray, 0, kInfinity);
  out[i] = h.found() ? (std::uint32_t(h.kind) << 28) ^ h.index : ~0u;
}

std::string cuda_message(cudaError_t e) { return std::string(cudaGetErrorName(e)) + ": " + cudaGetErrorString(e); }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A device buffer that frees itself.
struct Buffer {
  void* ptr = nullptr;
  std::size_t bytes = 0;
  Buffer() = default;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() {
    if (ptr) cudaFree(ptr);
  }
  // Grows to at least `n` bytes (contents lost).
  cudaError_t reserve(std::size_t n) {
    if (n <= bytes) return cudaSuccess;
    if (ptr) cudaFree(ptr);
    ptr = nullptr;
    bytes = 0;
    const cudaError_t e = cudaMalloc(&ptr, std::max<std::size_t>(n, 256));
    if (e == cudaSuccess) bytes = std::max<std::size_t>(n, 256);
    return e;
  }
};

}  // namespace

struct Device::Impl {
  int device = 0;
  cudaStream_t stream = nullptr, control = nullptr;
  cudaEvent_t begin = nullptr, end = nullptr;
  std::vector<std::unique_ptr<Buffer>> scene;    // the uploaded arrays
  std::unordered_map<const void*, void*> mapped;  // host array → its device copy
  std::size_t scene_bytes = 0;
  Buffer pixels, local, stats, taken, tiles, fixed, flag, counters, primary;
  SceneView uploaded;  // the uploaded scene's view (device pointers)

  ~Impl() {
    if (begin) cudaEventDestroy(begin);
    if (end) cudaEventDestroy(end);
    if (stream) cudaStreamDestroy(stream);
    if (control) cudaStreamDestroy(control);
  }

  template <class T, class Allocator>
  cudaError_t copy_array(const std::vector<T, Allocator>& host) {
    if (host.empty()) {
      if (host.data() != nullptr) mapped[host.data()] = nullptr;  // reserved, never filled
      return cudaSuccess;
    }
    auto b = std::make_unique<Buffer>();
    cudaError_t e = b->reserve(host.size() * sizeof(T));
    if (e != cudaSuccess) return e;
    e = cudaMemcpy(b->ptr, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice);
    if (e != cudaSuccess) return e;
    mapped[host.data()] = b->ptr;
    scene_bytes += b->bytes;
    scene.push_back(std::move(b));
    return cudaSuccess;
  }

  // The device pointer of a host array uploaded earlier; false when `p` was not uploaded.
  template <class T>
  bool map(const T*& p) const {
    if (p == nullptr) return true;
    const auto it = mapped.find(static_cast<const void*>(p));
    if (it == mapped.end()) return false;
    p = static_cast<const T*>(it->second);
    return true;
  }

  bool map_mutable(kernel::ImplicitTally*& p) const {
    const kernel::ImplicitTally* q = p;
    if (!map(q)) return false;
    p = const_cast<kernel::ImplicitTally*>(q);  // a device buffer of its own (the kernel's atomics)
    return true;
  }

  // Every array of a compiled scene: the scene itself, or one of its instance groups.
  cudaError_t copy_scene_arrays(const RenderScene& rs) {
    cudaError_t e = cudaSuccess;
    const auto ok = [&](cudaError_t r) { return (e = r) == cudaSuccess; };
    (void)(ok(copy_array(rs.spheres)) && ok(copy_array(rs.planes)) && ok(copy_array(rs.triangles)) &&
           ok(copy_array(rs.vertex_normals)) && ok(copy_array(rs.vertex_texcoords)) && ok(copy_array(rs.accel.sphere_quads)) &&
           ok(copy_array(rs.accel.bvh.nodes)) && ok(copy_array(rs.accel.bvh.leaves)) &&
           ok(copy_array(rs.accel.kdtree.nodes)) && ok(copy_array(rs.accel.kdtree.leaves)) &&
           ok(copy_array(rs.accel.kdtree.blocks)) && ok(copy_array(rs.accel.octree.nodes)) &&
           ok(copy_array(rs.accel.octree.centers)) && ok(copy_array(rs.accel.octree.leaves)) &&
           ok(copy_array(rs.accel.octree.blocks)) && ok(copy_array(rs.moving_spheres)) &&
           ok(copy_array(rs.moving_triangles)) && ok(copy_array(rs.moving_solids)) && ok(copy_array(rs.moving_instances)) && ok(copy_array(rs.moving_bvh.trees.nodes)) &&
           ok(copy_array(rs.moving_bvh.trees.prims)) && ok(copy_array(rs.materials)) && ok(copy_array(rs.textures)) &&
           ok(copy_array(rs.texels)) && ok(copy_array(rs.lights)) &&
           ok(copy_array(rs.solids)) && ok(copy_array(rs.boxes)) && ok(copy_array(rs.cones)) &&
           ok(copy_array(rs.disks)) && ok(copy_array(rs.tori)) && ok(copy_array(rs.quadrics)) &&
           ok(copy_array(rs.implicits)) && ok(copy_array(rs.implicit_tallies)) &&
           ok(copy_array(rs.solid_spheres)) && ok(copy_array(rs.csgs)) && ok(copy_array(rs.csg_code)) &&
           ok(copy_array(rs.csg_leaves)) && ok(copy_array(rs.placed)));
    return e;
  }

  // The instances (render/instance_queries.h): every group's arrays, the instances' records, their
  // BVH, and the groups' views with device pointers, which SceneView::groups then maps to.
  cudaError_t copy_instances(const RenderScene& rs) {
    if (rs.groups.empty()) {  // (a group placed nowhere is uploaded all the same: SceneView::groups points to it)
      if (rs.groups.views() != nullptr) mapped[rs.groups.views()] = nullptr;  // reserved, never filled
      return cudaSuccess;
    }
    cudaError_t e = cudaSuccess;
    for (const RenderScene& g : rs.groups)
      if ((e = copy_scene_arrays(g)) != cudaSuccess) return e;
    if ((e = copy_array(rs.instances)) != cudaSuccess || (e = copy_array(rs.instance_bvh.nodes)) != cudaSuccess ||
        (e = copy_array(rs.instance_bvh.prims)) != cudaSuccess)
      return e;
    std::vector<InstanceGroupView> views(rs.groups.views(), rs.groups.views() + rs.groups.size());
    for (InstanceGroupView& v : views)
      if (!map_accel(v.accel) || !map(v.vertex_normals) || !map(v.vertex_texcoords)) return cudaErrorInvalidValue;
    auto b = std::make_unique<Buffer>();
    if ((e = b->reserve(views.size() * sizeof(InstanceGroupView))) != cudaSuccess ||
        (e = cudaMemcpy(b->ptr, views.data(), views.size() * sizeof(InstanceGroupView), cudaMemcpyHostToDevice)) !=
            cudaSuccess)
      return e;
    mapped[rs.groups.views()] = b->ptr;
    scene_bytes += b->bytes;
    scene.push_back(std::move(b));
    return cudaSuccess;
  }

  // A structure's arrays and its primitives' with device pointers.
  bool map_accel(AccelView& a) const {
    return map(a.prims.spheres) && map(a.sphere_quads) && map(a.prims.triangles) && map(a.bvh.nodes) &&
           map(a.bvh.leaves) && map(a.prims.solids) && map(a.prims.shapes.boxes) && map(a.prims.shapes.cones) &&
           map(a.prims.shapes.disks) && map(a.prims.shapes.tori) && map(a.prims.shapes.quadrics) &&
           map(a.prims.shapes.implicits) && map_mutable(a.prims.shapes.tallies) && map(a.prims.shapes.spheres) &&
           map(a.prims.shapes.csgs) && map(a.prims.shapes.csg_code) && map(a.prims.shapes.csg_leaves) &&
           map(a.prims.shapes.placed) && map(a.kdtree.nodes) && map(a.kdtree.leaves) && map(a.kdtree.blocks) &&
           map(a.octree.nodes) && map(a.octree.centers) && map(a.octree.leaves) && map(a.octree.blocks);
  }

  // `host` (a job's view of the uploaded scene: its camera may differ) with device pointers.
  bool device_view(const SceneView& host, SceneView& out) const {
    out = host;
    return map(out.spheres) && map(out.planes) && map(out.triangles) && map(out.vertex_normals) && map(out.vertex_texcoords) &&
           map_accel(out.accel) && map(out.moving_spheres) && map(out.moving_triangles) && map(out.moving_solids) && map(out.moving_instances) &&
           map(out.moving_bvh.trees.nodes) && map(out.moving_bvh.trees.leaves) && map(out.materials) && map(out.textures.images) &&
           map(out.textures.texels) && map(out.lights) &&
           map(out.solids) && map(out.instances) && map(out.instance_bvh.nodes) && map(out.instance_bvh.leaves) &&
           map(out.groups);
  }
};

Device::~Device() = default;

std::unique_ptr<Device> Device::open(std::string& error) {
  int count = 0;
  cudaError_t e = cudaGetDeviceCount(&count);
  if (e == cudaErrorInsufficientDriver || e == cudaErrorNoDevice || e == cudaErrorInitializationError ||
      e == cudaErrorNotSupported || e == cudaErrorOperatingSystem || e == cudaErrorSystemDriverMismatch ||
      e == cudaErrorCompatNotSupportedOnDevice) {
    error = e == cudaErrorNoDevice ? "no CUDA device found (" + cuda_message(e) + ")"
                                   : "no usable CUDA driver (" + cuda_message(e) + ")";
    return nullptr;
  }
  if (e != cudaSuccess) {
    error = "CUDA is not usable (" + cuda_message(e) + ")";
    return nullptr;
  }
  if (count == 0) {
    error = "no CUDA device found";
    return nullptr;
  }
  std::unique_ptr<Device> d(new Device());
  d->impl_ = std::make_unique<Impl>();
  cudaDeviceProp prop{};
  if ((e = cudaGetDeviceProperties(&prop, 0)) != cudaSuccess || (e = cudaSetDevice(0)) != cudaSuccess) {
    error = "cannot use CUDA device 0 (" + cuda_message(e) + ")";
    return nullptr;
  }
  d->info_.name = prop.name;
  d->info_.major = prop.major;
  d->info_.minor = prop.minor;
  d->info_.multiprocessors = prop.multiProcessorCount;
  d->info_.memory_total = prop.totalGlobalMem;
  // Does this build hold code for the chip (sm_90 machine code, compute_90 PTX)? And what did
  // each variant of the render kernel become there.
  for (int k = 0; k < kKernelCount; ++k) {
    cudaFuncAttributes attr{};
    CudaKernel ki;
    ki.min_blocks = RenderKernels::min_blocks[k];
    ki.block = kBlock;
    if ((e = cudaFuncGetAttributes(&attr, RenderKernels::kernels[k])) != cudaSuccess ||
        (e = cudaOccupancyMaxActiveBlocksPerMultiprocessor(&ki.blocks_per_sm, RenderKernels::kernels[k], kBlock, 0)) !=
            cudaSuccess) {
      error = std::string("this strahl's CUDA kernels do not run on ") + prop.name + " (compute capability " +
              std::to_string(prop.major) + "." + std::to_string(prop.minor) + "; " + cuda_message(e) + ")";
      return nullptr;
    }
    ki.registers = attr.numRegs;
    ki.local_bytes = attr.localSizeBytes;
    d->info_.kernels.push_back(ki);
  }
  Impl& m = *d->impl_;
  if ((e = cudaStreamCreateWithFlags(&m.stream, cudaStreamNonBlocking)) != cudaSuccess ||
      (e = cudaStreamCreateWithFlags(&m.control, cudaStreamNonBlocking)) != cudaSuccess ||
      (e = cudaEventCreate(&m.begin)) != cudaSuccess || (e = cudaEventCreate(&m.end)) != cudaSuccess ||
      (e = m.flag.reserve(sizeof(int))) != cudaSuccess || (e = m.counters.reserve(kPassCounters * sizeof(unsigned long long))) != cudaSuccess) {
    error = "CUDA set-up failed on " + std::string(prop.name) + " (" + cuda_message(e) + ")";
    return nullptr;
  }
  return d;
}

bool Device::upload(const RenderScene& rs, std::string& error) {
  Impl& m = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  const SceneView host = rs.view();
  if (!gpu_traverses(host.accel.kind)) {
    error = std::string("--device cuda does not traverse ") + std::string(accel_name(host.accel.kind)) +
            "'s structure (use --accel bvh)";
    return false;
  }
  cudaError_t e = cudaSuccess;
  const auto ok = [&](cudaError_t r) { return (e = r) == cudaSuccess; };
  if (!(ok(m.copy_scene_arrays(rs)) && ok(m.copy_instances(rs)))) {
    error = (e == cudaErrorMemoryAllocation ? "out of GPU memory uploading the scene (" : "scene upload failed (") +
            cuda_message(e) + ")";
    return false;
  }
  if (!m.device_view(host, m.uploaded)) {
    error = "internal: the scene has an array the CUDA back end does not upload";
    return false;
  }
  // Each thread's stack: what the kernels' frames need (no recursion: render/whitted.h keeps the
  // pending rays in a fixed array, so ptxas knows the whole frame). The driver would grow the
  // stack at the first launch anyway; reserving it here reports a shortage at the upload, and
  // reserves no more than the kernel uses (the driver reserves it for every resident thread).
  std::size_t stack = 1024;  // CUDA's default
  for (const CudaKernel& k : info_.kernels) stack = std::max(stack, k.local_bytes);
  if (!ok(cudaDeviceSetLimit(cudaLimitStackSize, stack))) {
    error = "cannot reserve the GPU stack (" + std::to_string(stack) + " bytes per thread; " + cuda_message(e) + ")";
    return false;
  }
  upload_seconds_ = seconds_since(t0);
  return true;
}

bool Device::use_kernel(int index) {
  if (index < 0 || index >= int(info_.kernels.size())) return false;
  kernel_ = index;
  return true;
}

bool Device::holds(const SceneView& view) const {
  SceneView out;
  return gpu_traverses(view.accel.kind) && impl_->device_view(view, out);
}

bool Device::run(const SceneView& view, const PixelSampler& sampler, const FilmParams& film, PassData& pass,
                 const std::function<bool()>& stop, RayCounters& counters, std::string& error) {
  Impl& m = *impl_;
  KernelArgs a{};
  if (!m.device_view(view, a.pass.view)) {
    error = "internal: the job's scene is not the one uploaded to the GPU";
    return false;
  }
  const std::size_t n = pass.pixels.size();
  pass.taken.assign(n, 0);
  if (n == 0) return true;
  cudaError_t e = cudaSuccess;
  const auto ok = [&](cudaError_t r) { return (e = r) == cudaSuccess; };
  const auto up = [&](Buffer& b, const auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    return ok(b.reserve(v.size() * sizeof(T))) &&
           (v.empty() || ok(cudaMemcpyAsync(b.ptr, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice, m.stream)));
  };
  const auto down = [&](auto& v, const Buffer& b) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    return v.empty() || ok(cudaMemcpyAsync(v.data(), b.ptr, v.size() * sizeof(T), cudaMemcpyDeviceToHost, m.stream));
  };
  const int zero = 0, one = 1;
  unsigned long long sums[kPassCounters] = {};
  if (!(up(m.pixels, pass.pixels) && up(m.local, pass.local) && up(m.stats, pass.stats) && up(m.tiles, pass.tiles) &&
        up(m.fixed, pass.fixed) && ok(m.taken.reserve(n * sizeof(std::uint32_t))) &&
        ok(cudaMemcpyAsync(m.flag.ptr, &zero, sizeof zero, cudaMemcpyHostToDevice, m.stream)) &&
        ok(cudaMemsetAsync(m.counters.ptr, 0, sizeof sums, m.stream)))) {
    error = (e == cudaErrorMemoryAllocation ? "out of GPU memory for the pass (" : "GPU upload failed (") +
            cuda_message(e) + ")";
    return false;
  }
  a.pass.sampler = sampler;
  a.pass.film = film;
  a.pass.pixels = static_cast<const PassPixel*>(m.pixels.ptr);
  a.pass.local = static_cast<double*>(m.local.ptr);
  a.pass.stats = static_cast<PixelStats*>(m.stats.ptr);
  a.pass.taken = static_cast<std::uint32_t*>(m.taken.ptr);
  a.pass.tiles = static_cast<const PassTile*>(m.tiles.ptr);
  a.pass.fixed = static_cast<std::int64_t*>(m.fixed.ptr);
  a.pass.n = std::uint32_t(n);
  a.pass.stop = static_cast<const volatile int*>(m.flag.ptr);
  a.counters = static_cast<unsigned long long*>(m.counters.ptr);
  const unsigned blocks = unsigned((n + kBlock - 1) / kBlock);
  cudaEventRecord(m.begin, m.stream);
  RenderKernels::kernels[kernel_]<<<blocks, kBlock, 0, m.stream>>>(a);
  if (!ok(cudaGetLastError())) {
    error = "kernel launch failed (" + cuda_message(e) + ")";
    return false;
  }
  cudaEventRecord(m.end, m.stream);
  // Poll the stop request while the kernel runs: the flag reaches the kernel through the control
  // stream, and each thread reads it before every sample.
  bool stopped = false;
  while ((e = cudaEventQuery(m.end)) == cudaErrorNotReady) {
    if (!stopped && stop && stop()) {
      stopped = true;
      cudaMemcpyAsync(m.flag.ptr, &one, sizeof one, cudaMemcpyHostToDevice, m.control);
      cudaStreamSynchronize(m.control);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (e != cudaSuccess) {
    error = "the GPU kernel failed (" + cuda_message(e) + ")";
    return false;
  }
  float ms = 0;
  cudaEventElapsedTime(&ms, m.begin, m.end);
  last_kernel_seconds_ = double(ms) / 1000;
  kernel_seconds_ += last_kernel_seconds_;
  ++launches_;
  if (!(down(pass.local, m.local) && down(pass.stats, m.stats) && down(pass.taken, m.taken) &&
        down(pass.fixed, m.fixed) &&
        ok(cudaMemcpyAsync(sums, m.counters.ptr, sizeof sums, cudaMemcpyDeviceToHost, m.stream)) &&
        ok(cudaStreamSynchronize(m.stream)))) {
    error = "copying the pass back from the GPU failed (" + cuda_message(e) + ")";
    return false;
  }
  add_counter_array(counters, sums);
  return true;
}

double Device::primary_benchmark(const SceneView& view, int frames, std::string& error) {
  Impl& m = *impl_;
  SceneView dv;
  if (!m.device_view(view, dv)) {
    error = "internal: the benchmark's scene is not the one uploaded to the GPU";
    return -1;
  }
  const std::size_t n = std::size_t(view.camera.nx) * std::size_t(view.camera.ny);
  cudaError_t e = m.primary.reserve(n * sizeof(std::uint32_t));
  if (e != cudaSuccess) {
    error = "out of GPU memory (" + cuda_message(e) + ")";
    return -1;
  }
  const unsigned blocks = unsigned((n + kBlock - 1) / kBlock);
  std::vector<float> times;
  for (int f = -1; f < frames; ++f) {  // frame −1: warm-up
    cudaEventRecord(m.begin, m.stream);
    primary_kernel<<<blocks, kBlock, 0, m.stream>>>(dv, static_cast<std::uint32_t*>(m.primary.ptr));
    cudaEventRecord(m.end, m.stream);
    if ((e = cudaEventSynchronize(m.end)) != cudaSuccess || (e = cudaGetLastError()) != cudaSuccess) {
      error = "the primary-ray kernel failed (" + cuda_message(e) + ")";
      return -1;
    }
    float ms = 0;
    cudaEventElapsedTime(&ms, m.begin, m.end);
    if (f >= 0) times.push_back(ms);
  }
  if (times.empty()) return 0;
  std::sort(times.begin(), times.end());
  return double(times[times.size() / 2]) / 1000;
}

std::size_t Device::memory_in_use() const {
  std::size_t free = 0, total = 0;
  if (cudaMemGetInfo(&free, &total) != cudaSuccess) return 0;
  return total - free;
}

std::size_t Device::memory_used() const {
  const Impl& m = *impl_;
  return m.scene_bytes + m.pixels.bytes + m.local.bytes + m.stats.bytes + m.taken.bytes + m.tiles.bytes +
         m.fixed.bytes + m.flag.bytes + m.counters.bytes + m.primary.bytes;
}

}  // namespace strahl::cuda_detail
