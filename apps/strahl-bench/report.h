#pragma once
// What strahl-bench measures and how it prints it: the per-scene tables, the strahl-BVH /
// Embree ratios and the scaling table.

#include <array>
#include <string>
#include <vector>

#include "measure.h"
#include "scenes.h"

namespace strahl::bench {

struct Plan {
  std::vector<int> threads;  // {1, all}
  std::vector<AccelKind> kinds;
  Repeat repeat;
  // Primitive tests the naive loop may spend on one batch; beyond it, only every k-th ray is traced.
  double naive_budget = 5e7;
  bool packets = true;  // the packet table (bvh and embree, where in `kinds`)
};

inline constexpr int kBatches = 3;  // primary, incoherent, shadow

// One structure at one thread count.
struct Figures {
  double build_seconds = 0;
  std::size_t bytes = 0;
  std::array<double, kBatches> mrays{};
};

struct AccelResult {
  AccelKind kind = AccelKind::Bvh;
  std::vector<Figures> per_threads;            // parallel to Plan::threads
  std::array<TraceResult, kBatches> traces;    // the last thread count's answers (checksums)
  bool threads_disagree = false;               // answers at 1 thread differed from all threads
};

// One structure's packets of one size at one thread count (packets.h).
struct PacketFigures {
  AccelKind kind = AccelKind::Bvh;
  int size = 8;
  int threads = 1;
  double primary = 0, shadow = 0;  // Mrays/s
};

struct SceneResult {
  std::string name;
  std::size_t spheres = 0, triangles = 0;
  std::vector<AccelResult> accels;
  std::vector<PacketFigures> packets;
};

void print_header(const Plan& plan, int width, int height);

// Creates the Embree device and starts TBB's workers before anything is timed.
void warm_up(const Plan& plan);

// Makes the rays, measures every structure of the plan, prints the scene's tables.
SceneResult measure_scene(const BenchScene& scene, const Plan& plan);

// strahl's BVH relative to Embree, for every scene where both ran (nothing without Embree).
void print_ratios(const std::vector<SceneResult>& results, const Plan& plan);

// The procedural mesh at each size: BVH (and Embree) build time with all threads, ns per primary
// and incoherent ray on one thread, and a least-squares fit a + b·log2(n).
void run_scaling(const std::vector<std::size_t>& sizes, int width, int height, const Plan& plan);

}  // namespace strahl::bench
