#include "report.h"

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "console.h"
#include "packets.h"

namespace strahl::bench {

namespace {

constexpr const char* kBatchNames[kBatches] = {"primary", "incoherent", "shadow"};
constexpr Query kBatchQuery[kBatches] = {Query::Nearest, Query::Nearest, Query::Occluded};

const RayBatch& batch_of(const BenchRays& rays, int b) {
  return b == 0 ? rays.primary : (b == 1 ? rays.incoherent : rays.shadow);
}

// 1234567 → "1,234,567".
std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string bytes_text(std::size_t bytes) {
  if (bytes < (1u << 20)) return fmt::format("{:.1f} KiB", double(bytes) / 1024);
  return fmt::format("{:.1f} MiB", double(bytes) / (1 << 20));
}

// A text table: the first column left-aligned, the others right-aligned.
class Table {
 public:
  explicit Table(std::vector<std::string> header) { rows_.push_back(std::move(header)); }
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  void print() const {
    std::vector<std::size_t> width;
    for (const auto& row : rows_) {
      if (width.size() < row.size()) width.resize(row.size(), 0);
      for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    }
    for (const auto& row : rows_) {
      std::string line = " ";
      for (std::size_t c = 0; c < row.size(); ++c)
        line += c == 0 ? fmt::format(" {:<{}}", row[c], width[c]) : fmt::format("  {:>{}}", row[c], width[c]);
      while (!line.empty() && line.back() == ' ') line.pop_back();
      strahl::console::out("{}\n", line);
    }
  }

 private:
  std::vector<std::vector<std::string>> rows_;
};

bool has(const Plan& plan, AccelKind kind) {
  return std::find(plan.kinds.begin(), plan.kinds.end(), kind) != plan.kinds.end();
}

// Every k-th ray for the naive loop, so that it spends about plan.naive_budget primitive tests.
std::size_t naive_stride(const Plan& plan, std::size_t prims, std::size_t rays) {
  const double tests = double(prims) * double(rays);
  return tests <= plan.naive_budget ? 1 : std::size_t(std::ceil(tests / plan.naive_budget));
}

// Packets of 8 and 16 rays for strahl's BVH and Embree, interleaved (bvh, embree, bvh, ...), on
// the scene's own primary and shadow rays; each checked against the structure's single rays.
void measure_packets(const PrimitiveSet& prims, const BenchRays& rays, const Plan& plan, SceneResult& result) {
  std::vector<AccelKind> kinds;
  for (AccelKind k : plan.kinds) {
    if (k == AccelKind::Bvh) kinds.push_back(k);
#if defined(STRAHL_HAVE_EMBREE)
    if (k == AccelKind::Embree) kinds.push_back(k);
#endif
  }
  if (kinds.empty()) return;
  int embree_width = 0;
#if defined(STRAHL_HAVE_EMBREE)
  embree_width = embree_native_packet_width();
#endif
  const std::vector<int> sizes = {8, 16};
  std::vector<PacketBatch> primary, shadow;
  for (int size : sizes) {
    primary.push_back(tile_packets(rays, size, false));
    shadow.push_back(tile_packets(rays, size, true));
  }
  strahl::console::out("  packets: primary rays of tiles of 4x2 (8 rays) and 4x4 pixels (16), shadow rays from those "
                       "pixels' hits ({} and {} primary packets, lanes {:.0f}% and {:.0f}% active in shadow packets)\n",
                       grouped(primary[0].packets()), grouped(primary[1].packets()),
                       shadow[0].packets() ? 100.0 * double(shadow[0].ray_count) / double(8 * shadow[0].packets()) : 0.0,
                       shadow[1].packets() ? 100.0 * double(shadow[1].ray_count) / double(16 * shadow[1].packets()) : 0.0);
  Table table({"packets", "rays", "threads", "primary Mrays/s", "shadow Mrays/s", "× single primary", "× single shadow",
               "differ from single rays (primary, shadow)"});
  struct Built {
    AccelKind kind;
    Accel accel;
    AccelView view;
    PacketTrace single[2];
    const AccelResult* result = nullptr;
  };
  std::vector<Built> built;
  for (AccelKind kind : kinds) {
    Built b;
    b.kind = kind;
    tbb::task_arena arena(plan.threads.back());
    arena.execute([&] { b.accel = build_accel(kind, prims); });
    built.push_back(std::move(b));
  }
  for (Built& b : built) {
    b.view = b.accel.view(prims);
    b.single[0] = trace_single(b.view, rays.primary, Query::Nearest, plan.threads.back());
    b.single[1] = trace_single(b.view, rays.shadow, Query::Occluded, plan.threads.back());
    for (const AccelResult& ar : result.accels)
      if (ar.kind == b.kind) b.result = &ar;
  }
  bool skipped16 = false;
  for (std::size_t si = 0; si < sizes.size(); ++si) {
    for (std::size_t ti = 0; ti < plan.threads.size(); ++ti) {
      const int threads = plan.threads[ti];
      std::vector<Built*> take;
      for (Built& b : built) {
        bool embree = false;
#if defined(STRAHL_HAVE_EMBREE)
        embree = b.kind == AccelKind::Embree;
#endif
        if (embree && sizes[si] > embree_width)
          skipped16 = true;
        else
          take.push_back(&b);
      }
      // Run by run, alternating between the structures (bvh, embree, bvh, embree, ...): the
      // fastest run of each counts, and a change in the machine's load hits both.
      std::vector<PacketTrace> best_p(take.size()), best_s(take.size());
      double spent = 0;
      int runs = 0;
      do {
        for (std::size_t j = 0; j < take.size(); ++j) {
          PacketTrace p = trace_packets(take[j]->view, primary[si], rays.primary.size(), Query::Nearest, threads, Repeat{0, 1});
          PacketTrace s = trace_packets(take[j]->view, shadow[si], rays.shadow.size(), Query::Occluded, threads, Repeat{0, 1});
          spent += p.seconds + s.seconds;
          if (runs == 0 || p.seconds < best_p[j].seconds) best_p[j] = std::move(p);
          if (runs == 0 || s.seconds < best_s[j].seconds) best_s[j] = std::move(s);
        }
        ++runs;
      } while (runs < plan.repeat.max_runs && spent < 2 * plan.repeat.min_seconds * double(take.size()));
      for (std::size_t j = 0; j < take.size(); ++j) {
        const Built& b = *take[j];
        bool embree = false;
#if defined(STRAHL_HAVE_EMBREE)
        embree = b.kind == AccelKind::Embree;
#endif
        const PacketTrace &p = best_p[j], &s = best_s[j];
        PacketFigures f{b.kind, sizes[si], threads, p.mrays(), s.mrays()};
        result.packets.push_back(f);
        const PacketDiff dp = compare(p, b.single[0], !embree), ds = compare(s, b.single[1], !embree);
        std::string single_p = "-", single_s = "-";
        if (b.result && ti < b.result->per_threads.size()) {
          const Figures& single = b.result->per_threads[ti];
          if (single.mrays[0] > 0) single_p = fmt::format("{:.2f}", f.primary / single.mrays[0]);
          if (single.mrays[2] > 0) single_s = fmt::format("{:.2f}", f.shadow / single.mrays[2]);
        }
        std::string differ = fmt::format("{}, {}", grouped(dp.differ), grouped(ds.differ));
        if (dp.ties > 0) differ += fmt::format(" ({} ties)", grouped(dp.ties));
        table.add({std::string(accel_name(b.kind)), std::to_string(sizes[si]), std::to_string(threads),
                   fmt::format("{:.2f}", f.primary), fmt::format("{:.2f}", f.shadow), single_p, single_s, differ});
      }
    }
  }
  table.print();
  strahl::console::out("  (× single: against the structure's single-ray figure above at the same threads; differ: rays "
                       "whose packet answer is not the single ray's — bvh: bit for bit, ties = another primitive at the "
                       "same t; embree: as in the checksums)\n");
  if (skipped16)
    strahl::console::out("  (Embree's 16-ray packets skipped: its kernels for this CPU are {} wide)\n", embree_width);
}

}  // namespace

void print_header(const Plan& plan, int width, int height) {
  std::string threads;
  for (int t : plan.threads) threads += (threads.empty() ? "" : " and ") + std::to_string(t);
  std::string kinds;
  for (AccelKind k : plan.kinds) kinds += (kinds.empty() ? "" : ", ") + std::string(accel_name(k));
#if defined(STRAHL_EMBREE_VERSION)
  const std::string embree = "Embree " STRAHL_EMBREE_VERSION " built in";
#else
  const std::string embree = "built without Embree";
#endif
  strahl::console::out("strahl-bench: {}x{} primary rays, {} thread(s), structures: {} ({})\n", width, height, threads, kinds,
             embree);
  strahl::console::out("Traversal time only (rays made beforehand; the same arrays for every structure); the fastest of up to {} "
             "runs.\n",
             plan.repeat.max_runs);
  strahl::console::out("Mrays/s = rays traced / seconds. Memory: the structure (strahl's own triangles, {} bytes each, are "
             "extra; Embree's figure includes its float copy of the geometry).\n\n",
             sizeof(kernel::Triangle));
}

void warm_up(const Plan& plan) {
  const PrimitiveSet none;
  for (AccelKind k : plan.kinds) build_accel(k, none);  // creates the Embree device, if any
  tbb::task_arena arena(plan.threads.back());
  arena.execute([] {
    tbb::parallel_for(tbb::blocked_range<int>(0, 1 << 16, 64), [](const auto& r) {
      volatile int sink = 0;
      for (int i = r.begin(); i != r.end(); ++i) sink = sink + i;
    });
  });
}

SceneResult measure_scene(const BenchScene& scene, const Plan& plan) {
  const PrimitiveSet prims = scene.primitives();
  SceneResult result;
  result.name = scene.name;
  result.spheres = scene.spheres.size();
  result.triangles = scene.triangles.size();

  // The reference structure that places the secondary rays: strahl's BVH, all threads.
  const BenchRays rays = [&] {
    tbb::task_arena arena(plan.threads.back());
    BenchRays r;
    arena.execute([&] {
      const Accel bvh = build_accel(AccelKind::Bvh, prims);
      r = make_rays(scene, bvh.view(prims));
    });
    return r;
  }();
  strahl::console::out("== {}: {} spheres, {} triangles ({} of triangle data); {} primary rays, {} hit → {} incoherent and {} "
             "shadow rays\n",
             scene.name, grouped(result.spheres), grouped(result.triangles),
             bytes_text(result.triangles * sizeof(kernel::Triangle)), grouped(rays.primary.size()),
             grouped(rays.incoherent.size()), grouped(rays.incoherent.size()), grouped(rays.shadow.size()));

  Table table({"accel", "threads", "build ms", "memory", "B/prim", "primary Mrays/s", "incoherent Mrays/s",
               "shadow Mrays/s"});
  for (AccelKind kind : plan.kinds) {
    AccelResult ar;
    ar.kind = kind;
    std::array<std::size_t, kBatches> stride{1, 1, 1};
    for (int b = 0; b < kBatches; ++b)
      if (kind == AccelKind::Naive) stride[b] = naive_stride(plan, prims.size(), batch_of(rays, b).size());
    // The naive loop is not built, and one run of it is plenty.
    const Repeat repeat = kind == AccelKind::Naive ? Repeat{0, 1} : plan.repeat;
    std::array<TraceResult, kBatches> previous;
    for (std::size_t ti = 0; ti < plan.threads.size(); ++ti) {
      const int threads = plan.threads[ti];
      Figures f;
      const BuildResult built = timed_build(kind, prims, threads, plan.repeat);
      f.build_seconds = built.seconds;
      f.bytes = built.accel.stats.bytes;
      const AccelView view = built.accel.view(prims);
      for (int b = 0; b < kBatches; ++b) {
        TraceResult tr = trace(view, batch_of(rays, b), kBatchQuery[b], threads, stride[b], repeat);
        f.mrays[std::size_t(b)] = tr.mrays();
        if (ti > 0 && differing(tr, previous[std::size_t(b)]) != 0) ar.threads_disagree = true;
        previous[std::size_t(b)] = std::move(tr);
      }
      ar.per_threads.push_back(f);
      const std::size_t prim_count = std::max<std::size_t>(1, prims.size());
      const bool built_nothing = kind == AccelKind::Naive;
      std::vector<std::string> row = {std::string(accel_name(kind)), std::to_string(threads),
                                      built_nothing ? "-" : fmt::format("{:.2f}", f.build_seconds * 1e3),
                                      built_nothing ? "-" : bytes_text(f.bytes),
                                      built_nothing ? "-" : fmt::format("{:.1f}", double(f.bytes) / double(prim_count))};
      for (int b = 0; b < kBatches; ++b) {
        const double m = f.mrays[std::size_t(b)];
        std::string cell = m >= 0.1 || m == 0 ? fmt::format("{:.2f}", m) : fmt::format("{:.2g}", m);
        if (stride[b] > 1) cell = fmt::format("(1/{} of rays) ", stride[b]) + cell;
        row.push_back(cell);
      }
      table.add(std::move(row));
    }
    ar.traces = std::move(previous);
    result.accels.push_back(std::move(ar));
  }
  table.print();

  // Checksums: what each structure answered, and on how many rays it disagrees with the BVH.
  const AccelResult* reference = nullptr;
  for (const AccelResult& ar : result.accels)
    if (ar.kind == AccelKind::Bvh) reference = &ar;
  Table sums({"checksum", "primary hits", "incoherent hits", "shadow occluded"});
  for (const AccelResult& ar : result.accels) {
    std::vector<std::string> row = {std::string(accel_name(ar.kind))};
    for (int b = 0; b < kBatches; ++b) {
      const TraceResult& tr = ar.traces[std::size_t(b)];
      std::string cell = grouped(tr.hits);
      if (tr.stride > 1) cell += fmt::format(" of {}", grouped(tr.rays));
      if (reference && reference != &ar) cell += fmt::format(" ({} differ)", grouped(differing(tr, reference->traces[std::size_t(b)])));
      row.push_back(cell);
    }
    if (ar.threads_disagree) row.push_back("answers at 1 thread differ!");
    sums.add(std::move(row));
  }
  sums.print();
  if (reference)
    strahl::console::out("  (n differ: rays where the structure and the BVH disagree on hit or miss, or hit different primitives at\n"
               "  different distances; float Embree differs on a few rays that graze an edge or the surface they leave)\n");
  if (plan.packets) measure_packets(prims, rays, plan, result);
  strahl::console::out("\n");
  return result;
}

void print_ratios(const std::vector<SceneResult>& results, const Plan& plan) {
  if (!has(plan, AccelKind::Bvh)) return;
#if defined(STRAHL_HAVE_EMBREE)
  if (!has(plan, AccelKind::Embree)) return;
  strahl::console::out("== strahl bvh / Embree, figure by figure (Mrays/s: below 1 = strahl slower; build time and memory: above 1 "
             "= strahl slower / larger)\n");
  Table table({"scene", "threads", "build time", "memory", "primary", "incoherent", "shadow"});
  const auto ratio = [](double a, double b) { return b > 0 ? fmt::format("{:.2f}", a / b) : std::string("-"); };
  for (const SceneResult& s : results) {
    const AccelResult *bvh = nullptr, *embree = nullptr;
    for (const AccelResult& ar : s.accels) {
      if (ar.kind == AccelKind::Bvh) bvh = &ar;
      if (ar.kind == AccelKind::Embree) embree = &ar;
    }
    if (!bvh || !embree) continue;
    for (std::size_t ti = 0; ti < plan.threads.size(); ++ti) {
      const Figures &a = bvh->per_threads[ti], &b = embree->per_threads[ti];
      table.add({s.name, std::to_string(plan.threads[ti]), ratio(a.build_seconds, b.build_seconds),
                 ratio(double(a.bytes), double(b.bytes)), ratio(a.mrays[0], b.mrays[0]), ratio(a.mrays[1], b.mrays[1]),
                 ratio(a.mrays[2], b.mrays[2])});
    }
  }
  table.print();
  strahl::console::out("\n");
  bool any_packets = false;
  for (const SceneResult& s : results) any_packets = any_packets || !s.packets.empty();
  if (!any_packets) return;
  strahl::console::out("== strahl bvh packets / Embree packets, the same rays in the same packets (Mrays/s: below 1 = strahl slower)\n");
  Table packets({"scene", "rays", "threads", "primary", "shadow"});
  for (const SceneResult& s : results)
    for (const PacketFigures& a : s.packets) {
      if (a.kind != AccelKind::Bvh) continue;
      for (const PacketFigures& b : s.packets)
        if (b.kind == AccelKind::Embree && b.size == a.size && b.threads == a.threads)
          packets.add({s.name, std::to_string(a.size), std::to_string(a.threads), ratio(a.primary, b.primary),
                       ratio(a.shadow, b.shadow)});
    }
  packets.print();
  strahl::console::out("\n");
#else
  (void)results;
#endif
}

namespace {

// Least-squares fit y = a + b·x.
std::pair<double, double> fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = double(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double d = n * sxx - sx * sx;
  if (x.size() < 2 || d == 0) return {n > 0 ? sy / n : 0, 0};
  const double b = (n * sxy - sx * sy) / d;
  return {(sy - b * sx) / n, b};
}

}  // namespace

void run_scaling(const std::vector<std::size_t>& sizes, int width, int height, const Plan& plan) {
  std::vector<AccelKind> kinds;
  for (AccelKind k : plan.kinds)
    if (k != AccelKind::Naive) kinds.push_back(k);
  if (kinds.empty()) return;
  const int all = plan.threads.back();
  strahl::console::out("== scaling: the procedural mesh (bumpy sphere), {}x{} primary rays; build with {} thread(s), ns per ray "
             "on 1 thread\n",
             width, height, all);
  std::vector<std::string> header = {"triangles", "log2 n"};
  for (AccelKind k : kinds) {
    const std::string name(accel_name(k));
    header.push_back(name + " build ms");
    header.push_back(name + " primary ns");
    header.push_back(name + " incoherent ns");
  }
  Table table(header);
  std::vector<double> log_n;
  std::vector<std::vector<double>> ns(kinds.size() * 2);
  for (std::size_t size : sizes) {
    const BenchScene scene = procedural_bench_scene(size, width, height);
    const PrimitiveSet prims = scene.primitives();
    // Big meshes are built and traced once: their runs are long enough to time.
    const Repeat repeat = prims.size() >= 1'000'000 ? Repeat{0, 1} : plan.repeat;
    std::vector<std::string> row = {grouped(prims.size()), fmt::format("{:.1f}", std::log2(double(prims.size())))};
    log_n.push_back(std::log2(double(prims.size())));
    BenchRays rays;
    for (std::size_t ki = 0; ki < kinds.size(); ++ki) {
      const BuildResult built = timed_build(kinds[ki], prims, all, repeat);
      const AccelView view = built.accel.view(prims);
      if (ki == 0) {
        // Rays from the first structure (the BVH unless excluded): the same for every structure.
        tbb::task_arena arena(all);
        arena.execute([&] { rays = make_rays(scene, view); });
      }
      row.push_back(fmt::format("{:.2f}", built.seconds * 1e3));
      for (int b = 0; b < 2; ++b) {
        const TraceResult tr = trace(view, batch_of(rays, b), kBatchQuery[b], 1, 1, repeat);
        row.push_back(fmt::format("{:.1f}", tr.ns_per_ray()));
        ns[2 * ki + std::size_t(b)].push_back(tr.ns_per_ray());
      }
    }
    table.add(std::move(row));
    if (sizes.size() > 3) {  // progress for the long default run; the table follows at the end
      strahl::console::err("  scaling: {} triangles done\n", grouped(prims.size()));
    }
  }
  table.print();
  for (std::size_t ki = 0; ki < kinds.size(); ++ki) {
    for (int b = 0; b < 2; ++b) {
      const auto [a, slope] = fit_line(log_n, ns[2 * ki + std::size_t(b)]);
      strahl::console::out("  fit {} {}: {:.1f} {} {:.1f}·log2(n) ns per ray\n", accel_name(kinds[ki]), kBatchNames[b], a,
                 slope < 0 ? '-' : '+', std::fabs(slope));
    }
  }
  strahl::console::out("\n");
}

}  // namespace strahl::bench
