#pragma once
// Start-up of a cluster render: every rank has loaded and compiled the scene itself; each worker
// tells rank 0 its scene hash (or why it could not load the scene), and rank 0 answers go — when
// every rank compiled the same scene — or give up.

#include <cstdint>
#include <string>
#include <vector>

#include "strahl/mpi/comm.h"

namespace strahl::mpi {

// Rank 0: waits up to `timeout` seconds for every worker's word. Returns "" when all have the
// scene rank 0 has (`own_hash`), else the reason to refuse ("rank 2: …"). Tells the workers.
// `own_error` non-empty: rank 0 itself failed; the workers are told to give up. `threads`, when
// given, receives each rank's render thread count (index = rank; 1 where a rank did not say).
std::string agree_on_scene(Comm& comm, std::uint64_t own_hash, const std::string& own_error, double timeout,
                           std::vector<int>* threads = nullptr);

// A worker: sends its hash (or its error) and its render thread count, and waits for rank 0's
// answer; true: render.
bool report_scene(Comm& comm, std::uint64_t hash, const std::string& error, double timeout, int threads = 1);

}  // namespace strahl::mpi
