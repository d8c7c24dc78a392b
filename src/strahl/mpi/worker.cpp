#include "strahl/mpi/worker.h"

#include <time.h>

#include <chrono>
#include <condition_variable>
#include <csignal>
#include <deque>
#include <mutex>
#include <thread>

#include "strahl/render/render_job.h"
#include "strahl/render/tile_codec.h"
#include "strahl/render/tile_renderer.h"
#include "strahl/util/error.h"

namespace strahl::mpi {

namespace {

using Clock = std::chrono::steady_clock;

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

}  // namespace

bool run_worker(Comm& comm, const SceneView& view, const SamplingSettings& sampling, const WorkerOptions& options) {
  const FilmLayout layout = film_layout_for(view, sampling);
  const PixelSampler sampler = make_pixel_sampler(sampling);
  StopToken stop;

  std::mutex mutex;
  std::condition_variable wake;      // render threads: a tile to render, or quit
  std::condition_variable finished;  // this thread: a rendered tile to send
  std::deque<TileWork> todo;
  std::deque<std::vector<std::uint8_t>> done;
  bool quit = false;
  double busy = 0;  // thread-seconds rendering
  std::uint64_t tiles = 0;

  const int threads = std::max(1, options.threads);
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i)
    pool.emplace_back([&] {
      for (;;) {
        TileWork t;
        {
          std::unique_lock lock(mutex);
          wake.wait(lock, [&] { return quit || !todo.empty(); });
          if (todo.empty()) return;
          t = std::move(todo.front());
          todo.pop_front();
        }
        layout.prepare(t);
        const auto start = Clock::now();
        const double cpu0 = thread_cpu_seconds();
        render_tile(view, sampler, layout, stop, t);
        std::vector<std::uint8_t> bytes;
        put_f64(bytes, thread_cpu_seconds() - cpu0);
        const std::vector<std::uint8_t> result = encode_tile(t, TilePart::Result);
        bytes.insert(bytes.end(), result.begin(), result.end());
        std::lock_guard lock(mutex);
        busy += std::chrono::duration<double>(Clock::now() - start).count();
        done.push_back(std::move(bytes));
        if (++tiles == std::uint64_t(options.kill_after_tiles)) std::raise(SIGKILL);
        finished.notify_one();
      }
    });

  bool answered = true, peer_lost = false;
  auto last_sent = Clock::now(), last_heard = Clock::now();
  for (;;) {
    bool active = false;
    while (std::optional<Message> m = comm.poll()) {
      active = true;
      if (m->from != 0) continue;
      last_heard = Clock::now();
      if (m->tag == kTask) {
        TileWork t;
        try {
          decode_tile(m->bytes, TilePart::Request, t);
        } catch (const Error&) {
          continue;  // rank 0 notices the missing result and hands the tile to someone else
        }
        std::lock_guard lock(mutex);
        todo.push_back(std::move(t));
        wake.notify_one();
      } else if (m->tag == kPing) {
        comm.send(0, kPing, {});
      } else if (m->tag == kStop) {
        stop.request();
      } else if (m->tag == kQuit) {
        std::lock_guard lock(mutex);
        quit = true;
        peer_lost = !m->bytes.empty() && m->bytes[0] == 1;
      }
    }
    std::deque<std::vector<std::uint8_t>> outbox;
    bool quitting;
    {
      std::lock_guard lock(mutex);
      outbox.swap(done);
      quitting = quit;
    }
    for (std::vector<std::uint8_t>& bytes : outbox) {
      comm.send(0, kResult, std::move(bytes));
      last_sent = Clock::now();
      active = true;
    }
    if (Clock::now() - last_sent > std::chrono::seconds(1)) {
      comm.send(0, kAlive, {});
      last_sent = Clock::now();
    }
    comm.progress();
    if (options.cancel && options.cancel->load(std::memory_order_relaxed)) stop.request();
    if (quitting) break;
    if (std::chrono::duration<double>(Clock::now() - last_heard).count() > options.timeout) {
      answered = false;  // rank 0 is gone: nothing this rank renders can reach the image
      stop.request();
      std::lock_guard lock(mutex);
      quit = true;
      todo.clear();
      break;
    }
    if (!active) {
      // While tiles wait in the queue the render threads need nothing from rank 0 until one of
      // them finishes (it wakes this thread to send the result); only an empty queue means a task
      // may be on its way. Stop, quit and heartbeats still arrive within 2 ms. Fewer wake-ups:
      // they take the cores from the render threads.
      std::unique_lock lock(mutex);
      const auto wait = todo.empty() ? std::chrono::microseconds(200) : std::chrono::microseconds(2000);
      finished.wait_for(lock, wait, [&] { return !done.empty() || quit; });
    }
  }
  {
    std::lock_guard lock(mutex);
    quit = true;
    todo.clear();
  }
  wake.notify_all();
  for (std::thread& t : pool) t.join();
  if (answered) {
    std::vector<std::uint8_t> stats;
    put_u64(stats, std::uint64_t(threads));
    put_u64(stats, tiles);
    put_f64(stats, busy / threads);
    put_f64(stats, comm.seconds_in_mpi());
    comm.send(0, kRankStats, std::move(stats));
    comm.flush(5.0);
  }
  if (peer_lost) comm.exit_without_finalize(0);
  return answered;
}

}  // namespace strahl::mpi
