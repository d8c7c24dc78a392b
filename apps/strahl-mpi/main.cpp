// strahl-mpi: one image over many processes (docs/cluster.md). Every rank loads and compiles the
// scene itself; rank 0 checks they all have the same one, runs the render job with the cluster
// back end (strahl/mpi/master.h), renders with its own threads too, journals finished tiles for
// --resume and writes the image, byte for byte what strahl writes. The others are workers.
//   mpirun -np 4 strahl-mpi scene.yaml -o out.png [every strahl flag] [--resume]
// Exit codes as strahl's: 0 ok, 1 usage, 2 scene or I/O error, 130 interrupted.

#include <CLI/CLI.hpp>
#include <tbb/info.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <csignal>
#include <cstdlib>
#include <filesystem>

#include "cluster_summary.h"
#include "console.h"
#include "interrupt.h"
#include "options.h"
#include "outputs.h"
#include "progress.h"
#include "setup.h"
#include "strahl/util/cancel.h"
#include "strahl/image/image_io.h"
#include "strahl/mpi/comm.h"
#include "strahl/mpi/master.h"
#include "strahl/mpi/startup.h"
#include "strahl/mpi/worker.h"
#include "strahl/render/journal.h"
#include "strahl/render/render_job.h"
#include "strahl/render/scene_hash.h"
#include "summary.h"

namespace {

using namespace strahl;
using Clock = std::chrono::steady_clock;

struct MpiOptions {
  bool resume = false;
  double timeout = 30;
  int prefetch = 3;
  std::string tile_log;
};

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

int threads_of(const cli::Options& o) { return o.threads > 0 ? o.threads : tbb::info::default_concurrency(); }

// What a tile holds depends on the scene and on these settings (the journal's key).
JobOptions job_options(const cli::Options& o) {
  JobOptions j;
  j.tile_size = o.tile_size;
  j.time_limit = o.time_limit;
  j.checkpoint_interval = o.checkpoint;
  return j;
}
bool progressive(const cli::Options& o, const RenderScene& rs) {
  return rs.sampling.sampler == SamplerKind::Adaptive || o.time_limit > 0 || o.checkpoint > 0;
}

int worker(mpi::Comm& comm, const cli::Options& o, const MpiOptions& m, const std::atomic<bool>* cancel) {
  std::string error;
  std::uint64_t hash = 0;
  std::optional<RenderScene> rs;
  try {
    rs.emplace(compile(cli::configured_scene(o)));
    hash = scene_hash(*rs);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!mpi::report_scene(comm, hash, error, 600, threads_of(o)) || !rs) return cancel->load() ? 130 : 2;  // rank 0 says why
  mpi::WorkerOptions w;
  w.threads = threads_of(o);
  w.timeout = m.timeout;
  if (env_int("STRAHL_MPI_KILL_RANK", -1) == comm.rank()) w.kill_after_tiles = env_int("STRAHL_MPI_KILL_AFTER", 1);
  w.cancel = cancel;
  return mpi::run_worker(comm, rs->view(), rs->sampling, w) ? 0 : 2;
}

int master(mpi::Comm& comm, const cli::Options& o, const MpiOptions& m, const std::atomic<bool>* cancel) {
  cli::Timings timings;
  const std::string output = cli::output_path(o);
  const std::filesystem::path journal_path = output + ".journal";
  std::string error;
  std::optional<RenderScene> rs;
  std::optional<TileJournal> journal;
  std::uint64_t hash = 0, key = 0;
  try {
    cli::check_outputs(o, output);
    auto t = Clock::now();
    const Scene scene = cli::configured_scene(o);
    timings.load = seconds_since(t);
    t = Clock::now();
    rs.emplace(compile(scene));
    timings.build = seconds_since(t);
    hash = scene_hash(*rs);
    key = journal_key(hash, o.tile_size, progressive(o, *rs), 0);
    if (m.resume) journal.emplace(TileJournal::resume(journal_path, key));
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::vector<int> worker_threads;
  const std::string problem = mpi::agree_on_scene(comm, hash, error, 600, &worker_threads);
  if (!problem.empty() && cancel->load()) {  // loading stopped by a signal (util/cancel.h)
    console::err("strahl-mpi: interrupted before rendering; nothing written\n");
    return 130;
  }
  if (!problem.empty()) {
    console::err("strahl-mpi: error: {}\n", error.empty() ? problem : error);
    return 2;
  }
  if (!journal) journal.emplace(TileJournal::create(journal_path, key));
  if (cancel->load()) {
    console::err("strahl-mpi: interrupted before rendering; nothing written\n");
    return 130;
  }

  std::FILE* tile_log = m.tile_log.empty() ? nullptr : std::fopen(m.tile_log.c_str(), "w");
  if (!m.tile_log.empty() && !tile_log) throw Error("cannot write the tile log " + m.tile_log + ": " + std::strerror(errno));
  mpi::MasterOptions mo;
  mo.threads = threads_of(o);
  mo.prefetch = m.prefetch;
  mo.worker_threads = worker_threads;
  mo.timeout = m.timeout;
  mo.tile_log = tile_log;
  mo.warn = [](const std::string& what) { console::err("strahl-mpi: warning: {}\n", what); };
  mpi::Master backend(comm, mo);
  const double latency = backend.measure_latency();

  cli::Progress progress(!o.quiet);
  JobOptions jo = job_options(o);
  jo.cancel = cancel;
  jo.progress = [&](long done, long total) { progress.update(done, total); };
  if (o.checkpoint > 0) jo.checkpoint = [&](const Image& partial) { write_image(partial, output, {o.linear}); };
  // Test hook (tests/mpi/resume.sh): STRAHL_MPI_KILL_RANK=0 kills the whole job (rank 0 by
  // SIGKILL: Open MPI then ends every rank) after STRAHL_MPI_KILL_AFTER journalled tiles.
  const int kill_after = env_int("STRAHL_MPI_KILL_RANK", -1) == 0 ? env_int("STRAHL_MPI_KILL_AFTER", 1) : 0;
  std::atomic<int> recorded{0};
  jo.on_tile = [&](const TileWork& t) {
    journal->record(t);
    if (kill_after > 0 && ++recorded == kill_after) std::raise(SIGKILL);
  };
  if (m.resume) jo.replay = [&](int pass, int index) { return journal->find(pass, index); };
  RenderJob job(rs->view(), rs->sampling, std::move(jo));
  job.run(backend);
  const RenderStats stats = job.stats();
  if (!stats.cancelled) progress.finish();
  timings.render = stats.seconds;
  mpi::ClusterStats cluster = backend.finish(stats.seconds);
  cluster.latency = latency;
  if (tile_log) std::fclose(tile_log);

  const auto t = Clock::now();
  const Image image = job.image();
  write_image(image, output, {o.linear});
  if (!o.aov.empty()) cli::write_aovs(*rs, o, output);
  timings.write = seconds_since(t);
  const bool whole = !stats.cancelled && !stats.time_limited;
  if (whole) journal->remove();
  if (stats.cancelled) {
    console::err("strahl-mpi: interrupted; wrote the image rendered so far to {} (--resume continues it)\n", output);
    // mpirun is ending the job and does not answer MPI_Finalize any more: the workers wait in it
    // until mpirun kills them, which it does as soon as one rank has ended — this one, now.
    comm.exit_without_finalize(130);
  }
  if (!o.quiet) {
    console::out("{}", cli::summary(output, image.width(), image.height(), mo.threads, timings, stats, *rs));
    if (stats.replayed_tiles > 0) console::out("resumed     {} tiles from {}\n", stats.replayed_tiles, journal_path.string());
    console::out("{}", cli::cluster_summary(cluster));
  }
  // MPI_Finalize may wait forever for a rank that is gone: end without it (the image is written).
  if (!cluster.lost_ranks().empty()) comm.exit_without_finalize(0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  console::protect_streams();
  mpi::Comm comm(&argc, &argv);
  MpiOptions m;
  // Only rank 0 prints --help, --version and usage errors; every rank ends the same way.
  const int saved_out = ::dup(1), saved_err = ::dup(2);
  if (comm.rank() != 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::close(null);
  }
  const cli::ParseResult parsed = cli::parse_options(argc, argv, "strahl-mpi", [&](CLI::App& app) {
    app.add_flag("--resume", m.resume, "Continue an interrupted render from <output>.journal: only missing tiles are rendered");
    app.add_option("--mpi-timeout", m.timeout, "Seconds without a word from a rank before it counts as lost (default 30)")
        ->check(CLI::Range(0.1, 86400.0));
    app.add_option("--prefetch", m.prefetch, "Tiles in flight per render thread of a worker (default 3)")->check(CLI::Range(1, 64));
    app.add_option("--tile-log", m.tile_log, "Write one line per tile: pass index rank cpu_seconds request_bytes result_bytes samples");
  });
  std::fflush(stdout);
  ::dup2(saved_out, 1);
  ::dup2(saved_err, 2);
  ::close(saved_out);
  ::close(saved_err);
  if (!parsed.options) return parsed.exit_code;
  const std::atomic<bool>* cancel = cli::install_interrupt_handlers();
  int code = 2;
  try {
    code = comm.rank() == 0 ? master(comm, *parsed.options, m, cancel) : worker(comm, *parsed.options, m, cancel);
  } catch (const strahl::Cancelled&) {  // a signal while loading or building (util/cancel.h)
    if (comm.rank() == 0) console::err("strahl-mpi: interrupted before rendering; nothing written\n");
    code = 130;
  } catch (const std::exception& e) {
    console::err("strahl-mpi: error: rank {}: {}\n", comm.rank(), e.what());
    code = 2;
  }
  return code;
}
