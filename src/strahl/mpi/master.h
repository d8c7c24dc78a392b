#pragma once
// The cluster back end on rank 0 (DESIGN.md: "mpi — tiles over ranks"): a TileBackend that hands
// the tiles of each pass out to the worker ranks — a few in flight per worker, so none waits for
// its next tile — while rank 0's own threads render tiles too, and delivers every result to the
// render job. A worker that stops answering (no message for `timeout` seconds while it holds
// tiles) or whose messages fail is lost: its tiles go to the others and the image is still whole
// and the same. After start-up only point-to-point messages are used (a collective after a
// failure would wait forever).

#include <chrono>
#include <cstdio>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "strahl/mpi/cluster_stats.h"
#include "strahl/mpi/comm.h"
#include "strahl/render/render_job.h"

namespace strahl::mpi {

struct MasterOptions {
  int threads = 1;         // rank 0's own render threads (0: none)
  int prefetch = 3;        // tiles in flight per render thread of a worker
  std::vector<int> worker_threads;  // render threads per rank (index = rank; agree_on_scene); 1 where absent
  double timeout = 30;     // seconds without a word from a worker holding tiles: lost
  double stop_grace = 5;   // after a stop, seconds to wait for the workers' partial tiles
  std::FILE* tile_log = nullptr;  // one line per tile: pass index rank cpu_s request_B result_B samples
  std::function<void(const std::string&)> warn{};  // a worker lost, as it happens
};

class Master final : public TileBackend {
 public:
  Master(Comm& comm, MasterOptions options);
  void render_pass(RenderJob& job) override;

  // Mean one-way latency of a small message to the workers, over `round_trips` ping-pongs with
  // each (call before the render); 0 without workers.
  double measure_latency(int round_trips = 50);

  // Tells the workers to quit and collects their statistics (call once, after the render).
  ClusterStats finish(double render_seconds);

 private:
  struct Worker {
    int rank = 0;
    bool lost = false;
    int threads = 1;  // its render threads: it gets prefetch × threads tiles in flight
    std::map<int, TileWork> in_flight;  // tile index → the request sent
    std::chrono::steady_clock::time_point last_heard{};
    std::uint64_t tiles = 0;
    int most_in_flight = 0;
  };

  std::optional<TileWork> take(RenderJob& job);
  void lose(Worker& w, const std::string& why);
  void handle(RenderJob& job, Message&& m);
  void log_tile(const TileWork& t, int rank, double cpu, std::size_t request_bytes, std::size_t result_bytes);

  Comm& comm_;
  MasterOptions options_;
  std::vector<Worker> workers_;  // ranks 1 … size − 1
  std::mutex retry_mutex_;
  std::deque<int> retry_;  // tiles of the current pass to hand out again (guarded by retry_mutex_)
  bool exhausted_ = false;  // the job has handed out every tile of the pass
  int outstanding_ = 0;     // tiles taken and not yet delivered (or given back to retry_)
  std::map<int, std::vector<std::uint8_t>> stats_messages_;  // rank → its kRankStats
  std::mutex log_mutex_;
  std::uint64_t local_tiles_ = 0;
  double local_busy_ = 0;  // thread-seconds rank 0's threads spent rendering
};

}  // namespace strahl::mpi
