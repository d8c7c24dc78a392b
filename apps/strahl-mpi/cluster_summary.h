#pragma once
// The cluster part of strahl-mpi's summary: per rank tiles, busy / idle / communication seconds,
// load imbalance and parallel efficiency; lost ranks named.

#include <string>

#include "strahl/mpi/cluster_stats.h"

namespace strahl::cli {

std::string cluster_summary(const mpi::ClusterStats& s);

}  // namespace strahl::cli
