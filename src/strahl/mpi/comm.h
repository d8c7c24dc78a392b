#pragma once
// A thin layer over MPI for the cluster back end: byte messages between ranks, sent without
// blocking (the buffer is kept until MPI is done with it), received by polling. Errors return
// (MPI_ERRORS_RETURN) instead of ending the process, so a lost rank is something the master can
// handle. Only the thread that made the Comm calls MPI (MPI_THREAD_FUNNELED).

#include <mpi.h>

#include <cstdint>
#include <list>
#include <optional>
#include <string>
#include <vector>

namespace strahl::mpi {

enum Tag : int {
  kHello = 1,   // worker → master: scene hash, or the error that kept it from loading the scene
  kGo,          // master → worker: render (1) or give up (0)
  kTask,        // master → worker: a tile request (render/tile_codec.h)
  kResult,      // worker → master: [CPU seconds, f64][tile result]
  kStop,        // master → worker: stop rendering now, send what you have
  kQuit,        // master → worker: no more work
  kAlive,       // worker → master: still here (while rendering a long tile)
  kRankStats,   // worker → master: its statistics, before it quits
  kPing,        // master → worker → master: a round trip, to measure the latency
};

struct Message {
  int from = -1, tag = 0;
  std::vector<std::uint8_t> bytes;
};

class Comm {
 public:
  Comm(int* argc, char*** argv);
  Comm(const Comm&) = delete;
  Comm& operator=(const Comm&) = delete;
  ~Comm();

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Queues `bytes` for rank `to`; false when MPI reports an error (the rank is gone).
  bool send(int to, int tag, std::vector<std::uint8_t> bytes);
  // The next message that has arrived, if any.
  std::optional<Message> poll();
  // Completes what sends it can; true when none is pending.
  bool progress();
  // Waits for pending sends up to `seconds`; true when all completed.
  bool flush(double seconds);
  // Seconds spent inside MPI calls so far.
  double seconds_in_mpi() const { return mpi_seconds_; }
  // The process ends without MPI_Finalize (which may wait forever for a lost rank).
  [[noreturn]] void exit_without_finalize(int code);

 private:
  struct Pending {
    std::vector<std::uint8_t> bytes;
    MPI_Request request = MPI_REQUEST_NULL;
  };
  int rank_ = 0, size_ = 1;
  std::list<Pending> pending_;
  double mpi_seconds_ = 0;
};

// Little helpers to build and read the small control messages.
void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v);
void put_f64(std::vector<std::uint8_t>& out, double v);
void put_string(std::vector<std::uint8_t>& out, const std::string& s);
// Reads from `bytes` at `at`, advancing it; throws strahl::Error when the bytes end early.
std::uint64_t get_u64(const std::vector<std::uint8_t>& bytes, std::size_t& at);
double get_f64(const std::vector<std::uint8_t>& bytes, std::size_t& at);
std::string get_string(const std::vector<std::uint8_t>& bytes, std::size_t& at);

}  // namespace strahl::mpi
