#include "strahl/mpi/startup.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "strahl/util/error.h"

namespace strahl::mpi {

namespace {
using Clock = std::chrono::steady_clock;

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}
}  // namespace

std::string agree_on_scene(Comm& comm, std::uint64_t own_hash, const std::string& own_error, double timeout,
                           std::vector<int>* threads) {
  std::string problem = own_error.empty() ? "" : "rank 0: " + own_error;
  if (threads) threads->assign(std::size_t(comm.size()), 1);
  std::vector<bool> heard(std::size_t(comm.size()), false);
  int missing = comm.size() - 1;
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  while (missing > 0 && problem.empty() && Clock::now() < end) {
    std::optional<Message> m = comm.poll();
    if (!m) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    if (m->tag != kHello || m->from <= 0 || heard[std::size_t(m->from)]) continue;
    heard[std::size_t(m->from)] = true;
    --missing;
    try {
      std::size_t at = 0;
      const std::uint64_t hash = get_u64(m->bytes, at);
      const std::string error = get_string(m->bytes, at);
      if (threads && at < m->bytes.size()) (*threads)[std::size_t(m->from)] = int(std::clamp<std::uint64_t>(get_u64(m->bytes, at), 1, 4096));
      if (!error.empty())
        problem = "rank " + std::to_string(m->from) + ": " + error;
      else if (hash != own_hash)
        problem = "rank " + std::to_string(m->from) + " compiled a different scene (hash " + hex(hash) + ", rank 0: " +
                  hex(own_hash) + "); every rank must load the same scene file and meshes";
    } catch (const Error& e) {
      problem = "rank " + std::to_string(m->from) + " sent a malformed start-up message";
    }
  }
  if (problem.empty() && missing > 0)
    problem = std::to_string(missing) + " rank(s) did not report within " + std::to_string(int(timeout)) + " s";
  for (int r = 1; r < comm.size(); ++r) comm.send(r, kGo, {std::uint8_t(problem.empty() ? 1 : 0)});
  comm.flush(5.0);
  return problem;
}

bool report_scene(Comm& comm, std::uint64_t hash, const std::string& error, double timeout, int threads) {
  std::vector<std::uint8_t> hello;
  put_u64(hello, hash);
  put_string(hello, error);
  put_u64(hello, std::uint64_t(std::max(1, threads)));
  comm.send(0, kHello, std::move(hello));
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  while (Clock::now() < end) {
    comm.progress();
    std::optional<Message> m = comm.poll();
    if (!m) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    if (m->from == 0 && m->tag == kGo) return !m->bytes.empty() && m->bytes[0] == 1;
  }
  return false;
}

}  // namespace strahl::mpi
