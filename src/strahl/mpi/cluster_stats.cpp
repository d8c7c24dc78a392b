#include "strahl/mpi/cluster_stats.h"

#include <algorithm>

namespace strahl::mpi {

double ClusterStats::imbalance() const {
  double max = 0, sum = 0;
  int n = 0;
  for (const RankStats& r : ranks) {
    if (r.tiles == 0) continue;
    max = std::max(max, r.busy);
    sum += r.busy;
    ++n;
  }
  return n > 0 && sum > 0 ? max / (sum / n) : 1.0;
}

double ClusterStats::efficiency() const {
  double busy = 0, capacity = 0;
  for (const RankStats& r : ranks) {
    busy += r.busy * r.threads;
    capacity += seconds * r.threads;
  }
  return capacity > 0 ? busy / capacity : 0;
}

std::vector<int> ClusterStats::lost_ranks() const {
  std::vector<int> lost;
  for (const RankStats& r : ranks)
    if (r.lost) lost.push_back(r.rank);
  return lost;
}

}  // namespace strahl::mpi
