#include "cluster_summary.h"

#include <fmt/format.h>

namespace strahl::cli {

std::string cluster_summary(const mpi::ClusterStats& s) {
  std::string out = fmt::format(
      "cluster     {} ranks; load imbalance {:.3f} (max/mean busy), parallel efficiency {:.3f}, latency {:.1f} µs\n",
      s.ranks.size(), s.imbalance(), s.efficiency(), s.latency * 1e6);
  for (const mpi::RankStats& r : s.ranks) {
    if (r.lost) {
      out += fmt::format("  rank {:<4}  LOST; {} tiles arrived from it before\n", r.rank, r.tiles);
      continue;
    }
    out += fmt::format("  rank {:<4}  {} threads, {} tiles, busy {:.3f} s, idle {:.3f} s, communication {:.3f} s", r.rank,
                       r.threads, r.tiles, r.busy, r.idle, r.comm);
    out += r.rank == 0 ? "\n" : fmt::format(", up to {} tiles in flight\n", r.most_in_flight);
  }
  const std::vector<int> lost = s.lost_ranks();
  if (!lost.empty()) {
    std::string names;
    for (int r : lost) names += (names.empty() ? "" : ", ") + std::to_string(r);
    out += fmt::format("warning     lost rank(s) {}; their tiles were rendered by the others\n", names);
  }
  return out;
}

}  // namespace strahl::cli
