#pragma once
// What each rank did in a cluster render, for the summary on rank 0.

#include <cstdint>
#include <vector>

namespace strahl::mpi {

struct RankStats {
  int rank = 0;
  int threads = 1;
  std::uint64_t tiles = 0;
  double busy = 0;  // seconds its render threads spent rendering, per thread
  double idle = 0;  // seconds of the render it was not rendering, per thread
  double comm = 0;  // seconds its MPI thread spent inside MPI calls
  int most_in_flight = 0;  // a worker: the most tiles it held at once (prefetch × threads when tiles were plenty)
  bool lost = false;
};

struct ClusterStats {
  std::vector<RankStats> ranks;  // by rank
  double seconds = 0;            // wall time of the render on rank 0
  double latency = 0;            // one-way seconds of a small message, measured before the render

  // max / mean of the ranks' busy seconds (ranks that rendered; 1 = perfectly balanced).
  double imbalance() const;
  // Σ busy thread-seconds / (render threads × wall seconds): the share of the cluster's time spent rendering.
  double efficiency() const;
  std::vector<int> lost_ranks() const;
};

}  // namespace strahl::mpi
