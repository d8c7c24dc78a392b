#include "strahl/mpi/master.h"

#include <time.h>

#include <algorithm>
#include <atomic>
#include <thread>

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

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

Master::Master(Comm& comm, MasterOptions options) : comm_(comm), options_(std::move(options)) {
  for (int r = 1; r < comm_.size(); ++r) {
    Worker w;
    w.rank = r;
    if (std::size_t(r) < options_.worker_threads.size()) w.threads = std::max(1, options_.worker_threads[std::size_t(r)]);
    workers_.push_back(std::move(w));
  }
}

std::optional<TileWork> Master::take(RenderJob& job) {
  std::lock_guard lock(retry_mutex_);
  std::optional<TileWork> t;
  if (!retry_.empty() && !job.stop().requested()) {
    t = job.tile(retry_.front());
    retry_.pop_front();
  } else if (!exhausted_) {
    t = job.next_tile();
    if (!t) exhausted_ = true;
  }
  if (t) ++outstanding_;
  return t;
}

void Master::lose(Worker& w, const std::string& why) {
  if (w.lost) return;
  w.lost = true;
  {
    std::lock_guard lock(retry_mutex_);
    for (const auto& [index, tile] : w.in_flight) retry_.push_back(index);
    outstanding_ -= int(w.in_flight.size());
  }
  if (options_.warn)
    options_.warn("lost rank " + std::to_string(w.rank) + " (" + why + "); its " + std::to_string(w.in_flight.size()) +
                  " tile(s) in flight go to the others");
  w.in_flight.clear();
}

void Master::log_tile(const TileWork& t, int rank, double cpu, std::size_t request_bytes, std::size_t result_bytes) {
  if (!options_.tile_log) return;
  std::lock_guard lock(log_mutex_);
  std::fprintf(options_.tile_log, "%d %d %d %.9f %zu %zu %llu\n", t.pass, t.index, rank, cpu, request_bytes,
               result_bytes, static_cast<unsigned long long>(t.samples_taken()));
}

void Master::handle(RenderJob& job, Message&& m) {
  if (m.from < 1 || m.from >= comm_.size()) return;
  Worker& w = workers_[std::size_t(m.from - 1)];
  if (w.lost) return;  // too late: its tiles went to others
  w.last_heard = Clock::now();
  if (m.tag == kRankStats) {
    stats_messages_[m.from] = std::move(m.bytes);
    return;
  }
  if (m.tag != kResult) return;  // kAlive: heard is all
  try {
    std::size_t at = 0;
    const double cpu = get_f64(m.bytes, at);
    TileWork result;
    decode_tile({m.bytes.data() + at, m.bytes.size() - at}, TilePart::Result, result);
    const auto it = w.in_flight.find(result.index);
    if (it == w.in_flight.end()) throw Error("a result for a tile it was not given");
    TileWork& t = it->second;
    if (result.pass != t.pass || result.rect.x0 != t.rect.x0 || result.rect.row0 != t.rect.row0 ||
        result.rect.x1 != t.rect.x1 || result.rect.row1 != t.rect.row1 ||
        (t.local.size() != result.local.size() && job.film_layout().pixel_local()))
      throw Error("a result that does not match its tile");
    t.taken = std::move(result.taken);
    t.local = std::move(result.local);
    t.stats = std::move(result.stats);
    t.bx0 = result.bx0;
    t.brow0 = result.brow0;
    t.bw = result.bw;
    t.bh = result.bh;
    t.fixed = std::move(result.fixed);
    t.counters = result.counters;
    if (options_.tile_log) log_tile(t, w.rank, cpu, encode_tile(t, TilePart::Request).size(), m.bytes.size());
    ++w.tiles;
    job.deliver(std::move(t));
    w.in_flight.erase(it);
    std::lock_guard lock(retry_mutex_);
    --outstanding_;
  } catch (const Error& e) {
    lose(w, std::string("bad message: ") + e.what());
  }
}

void Master::render_pass(RenderJob& job) {
  {
    std::lock_guard lock(retry_mutex_);
    exhausted_ = false;
    outstanding_ = 0;
    retry_.clear();
  }
  std::atomic<bool> pass_done{false};
  const auto render_local = [&](TileWork& t) {
    const auto start = Clock::now();
    const double cpu0 = thread_cpu_seconds();
    render_tile(job.view(), job.sampler(), job.film_layout(), job.stop(), t);
    const double cpu = thread_cpu_seconds() - cpu0;
    {
      std::lock_guard lock(log_mutex_);
      local_busy_ += since(start);
      ++local_tiles_;
    }
    if (options_.tile_log) {
      const std::size_t request = encode_tile(t, TilePart::Request).size();
      log_tile(t, 0, cpu, request, encode_tile(t, TilePart::Result).size() + 8);
    }
    job.deliver(std::move(t));
    std::lock_guard lock(retry_mutex_);
    --outstanding_;
  };
  std::vector<std::thread> local;
  for (int i = 0; i < options_.threads; ++i)
    local.emplace_back([&] {
      while (!pass_done.load()) {
        std::optional<TileWork> t = take(job);
        if (!t) {
          std::this_thread::sleep_for(std::chrono::microseconds(500));
          continue;
        }
        render_local(*t);
      }
    });

  bool stop_sent = false;
  Clock::time_point stop_deadline{}, last_beat = Clock::now();
  for (;;) {
    const bool stopping = job.stop().requested();
    if (stopping && !stop_sent) {
      for (Worker& w : workers_)
        if (!w.lost) comm_.send(w.rank, kStop, {});
      stop_sent = true;
      stop_deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options_.stop_grace));
    }
    bool busy = false;
    int live = 0;
    for (Worker& w : workers_) {
      if (w.lost) continue;
      ++live;
      while (!stopping && int(w.in_flight.size()) < options_.prefetch * w.threads) {
        std::optional<TileWork> t = take(job);
        if (!t) break;
        const int index = t->index;
        if (w.in_flight.empty()) w.last_heard = Clock::now();  // its clock starts with its first tile
        w.in_flight.emplace(index, std::move(*t));
        w.most_in_flight = std::max(w.most_in_flight, int(w.in_flight.size()));
        if (!comm_.send(w.rank, kTask, encode_tile(w.in_flight.at(index), TilePart::Request))) {
          lose(w, "a send failed");
          break;
        }
        busy = true;
      }
    }
    // Nobody left to render: rank 0's main thread renders (only when it has no threads of its own).
    if (live == 0 && options_.threads == 0 && !stopping) {
      if (std::optional<TileWork> t = take(job)) {
        render_local(*t);
        busy = true;
      }
    }
    while (std::optional<Message> m = comm_.poll()) {
      handle(job, std::move(*m));
      busy = true;
    }
    comm_.progress();
    const auto now = Clock::now();
    if (now - last_beat > std::chrono::seconds(1)) {  // workers give up on a silent rank 0
      for (Worker& w : workers_)
        if (!w.lost) comm_.send(w.rank, kAlive, {});
      last_beat = now;
    }
    for (Worker& w : workers_)
      if (!w.lost && !w.in_flight.empty() && std::chrono::duration<double>(now - w.last_heard).count() > options_.timeout)
        lose(w, "no answer for " + std::to_string(int(options_.timeout)) + " s");
    {
      std::lock_guard lock(retry_mutex_);
      if (stopping ? outstanding_ == 0 : exhausted_ && retry_.empty() && outstanding_ == 0) break;
    }
    if (stopping && now >= stop_deadline) break;  // what has not come back by now is left out
    if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  pass_done = true;
  for (std::thread& t : local) t.join();
  for (Worker& w : workers_) w.in_flight.clear();
}

double Master::measure_latency(int round_trips) {
  double total = 0;
  int measured = 0;
  for (Worker& w : workers_) {
    for (int i = 0; i < round_trips && !w.lost; ++i) {
      const auto start = Clock::now();
      if (!comm_.send(w.rank, kPing, {})) break;
      bool answered = false;
      while (!answered && since(start) < options_.timeout) {
        if (std::optional<Message> m = comm_.poll()) {
          answered = m->from == w.rank && m->tag == kPing;
          continue;
        }
        comm_.progress();
      }
      if (!answered) break;
      total += since(start) / 2;
      ++measured;
    }
  }
  return measured > 0 ? total / measured : 0;
}

ClusterStats Master::finish(double render_seconds) {
  // A lost rank makes MPI_Finalize wait for it forever: the quit message says so, and every rank
  // then ends without it.
  bool any_lost = false;
  for (const Worker& w : workers_) any_lost = any_lost || w.lost;
  for (Worker& w : workers_)
    if (!w.lost) comm_.send(w.rank, kQuit, {std::uint8_t(any_lost ? 1 : 0)});
  // Each live worker answers with its statistics; a worker that does not within a few seconds is lost.
  const auto end = Clock::now() + std::chrono::seconds(5);
  auto missing = [&] {
    for (const Worker& w : workers_)
      if (!w.lost && !stats_messages_.count(w.rank)) return true;
    return false;
  };
  while (missing() && Clock::now() < end) {
    if (std::optional<Message> m = comm_.poll()) {
      if (m->tag == kRankStats && m->from >= 1 && m->from < comm_.size()) stats_messages_[m->from] = std::move(m->bytes);
      continue;
    }
    comm_.progress();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ClusterStats s;
  s.seconds = render_seconds;
  RankStats zero;
  zero.rank = 0;
  zero.threads = std::max(1, options_.threads);
  zero.tiles = local_tiles_;
  zero.busy = options_.threads > 0 ? local_busy_ / options_.threads : local_busy_;
  zero.idle = std::max(0.0, render_seconds - zero.busy);
  zero.comm = comm_.seconds_in_mpi();
  s.ranks.push_back(zero);
  for (Worker& w : workers_) {
    RankStats r;
    r.rank = w.rank;
    r.tiles = w.tiles;
    r.most_in_flight = w.most_in_flight;
    const auto it = stats_messages_.find(w.rank);
    if (!w.lost && it != stats_messages_.end()) {
      try {
        std::size_t at = 0;
        r.threads = int(get_u64(it->second, at));
        get_u64(it->second, at);  // tiles the worker counted (those it rendered; the master's count is what arrived)
        r.busy = get_f64(it->second, at);
        r.comm = get_f64(it->second, at);
      } catch (const Error&) {
      }
      r.idle = std::max(0.0, render_seconds - r.busy);
    } else {
      r.lost = true;
    }
    s.ranks.push_back(r);
  }
  return s;
}

}  // namespace strahl::mpi
