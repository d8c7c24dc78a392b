#include "strahl/mpi/comm.h"

#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "strahl/util/error.h"

namespace strahl::mpi {

namespace {

// Times what it wraps into `total`.
class Timed {
 public:
  explicit Timed(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Timed() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

Comm::Comm(int* argc, char*** argv) {
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  if (provided < MPI_THREAD_FUNNELED) throw Error("the MPI library does not allow threads beside the one calling it");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Comm::~Comm() {
  flush(2.0);
  MPI_Finalize();
}

bool Comm::send(int to, int tag, std::vector<std::uint8_t> bytes) {
  Timed t(mpi_seconds_);
  pending_.push_back({std::move(bytes), MPI_REQUEST_NULL});
  Pending& p = pending_.back();
  const int rc = MPI_Isend(p.bytes.data(), int(p.bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD, &p.request);
  if (rc != MPI_SUCCESS) {
    pending_.pop_back();
    return false;
  }
  return true;
}

bool Comm::progress() {
  Timed t(mpi_seconds_);
  for (auto it = pending_.begin(); it != pending_.end();) {
    int done = 0;
    const int rc = MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
    // A send that failed (its rank is gone) is dropped as if done: the master notices the loss.
    it = done || rc != MPI_SUCCESS ? pending_.erase(it) : std::next(it);
  }
  return pending_.empty();
}

bool Comm::flush(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!progress()) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

std::optional<Message> Comm::poll() {
  Timed t(mpi_seconds_);
  int flag = 0;
  MPI_Status status;
  if (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status) != MPI_SUCCESS || !flag)
    return std::nullopt;
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  Message m;
  m.from = status.MPI_SOURCE;
  m.tag = status.MPI_TAG;
  m.bytes.resize(std::size_t(count));
  if (MPI_Recv(m.bytes.data(), count, MPI_BYTE, m.from, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE) != MPI_SUCCESS)
    return std::nullopt;
  return m;
}

void Comm::exit_without_finalize(int code) {
  flush(2.0);
  std::fflush(nullptr);
  ::_exit(code);
}

void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + 8);
}

void put_f64(std::vector<std::uint8_t>& out, double v) {
  std::uint64_t u;
  std::memcpy(&u, &v, 8);
  put_u64(out, u);
}

void put_string(std::vector<std::uint8_t>& out, const std::string& s) {
  put_u64(out, s.size());
  out.insert(out.end(), s.begin(), s.end());
}

std::uint64_t get_u64(const std::vector<std::uint8_t>& bytes, std::size_t& at) {
  if (bytes.size() < at + 8) throw Error("an MPI message ends early");
  std::uint64_t v;
  std::memcpy(&v, bytes.data() + at, 8);
  at += 8;
  return v;
}

double get_f64(const std::vector<std::uint8_t>& bytes, std::size_t& at) {
  const std::uint64_t u = get_u64(bytes, at);
  double v;
  std::memcpy(&v, &u, 8);
  return v;
}

std::string get_string(const std::vector<std::uint8_t>& bytes, std::size_t& at) {
  const std::uint64_t n = get_u64(bytes, at);
  if (bytes.size() - at < n) throw Error("an MPI message ends early");
  std::string s(bytes.begin() + std::ptrdiff_t(at), bytes.begin() + std::ptrdiff_t(at + n));
  at += n;
  return s;
}

}  // namespace strahl::mpi
