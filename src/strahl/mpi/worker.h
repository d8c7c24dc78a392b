#pragma once
// A worker rank of a cluster render: renders the tiles rank 0 sends (render_tile(), on its own
// threads) and sends each back, until rank 0 says quit. Its main thread does all the MPI calls
// and tells rank 0 every second that it is alive, also while a long tile renders.

#include <atomic>

#include "strahl/mpi/comm.h"
#include "strahl/render/scene_view.h"
#include "strahl/sampling/pixel_sampler.h"

namespace strahl::mpi {

struct WorkerOptions {
  int threads = 1;
  double timeout = 30;  // seconds without a word from rank 0: it is gone, the worker ends
  // Test hook (STRAHL_MPI_KILL_AFTER in strahl-mpi): raise SIGKILL after rendering this many tiles.
  int kill_after_tiles = 0;
  // A flag set from outside (the signal handler): stop rendering, as on rank 0's kStop.
  const std::atomic<bool>* cancel = nullptr;
};

// Returns when rank 0 has said quit (true) or has gone silent for `timeout` seconds (false). When
// rank 0 says another rank was lost, the process ends here, without MPI_Finalize.
bool run_worker(Comm& comm, const SceneView& view, const SamplingSettings& sampling, const WorkerOptions& options);

}  // namespace strahl::mpi
