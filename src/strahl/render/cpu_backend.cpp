#include "strahl/render/cpu_backend.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "strahl/render/tile_renderer.h"

namespace strahl {

struct CpuBackend::Arena {
  tbb::task_arena arena;
};

CpuBackend::CpuBackend(int threads)
    : arena_(std::make_unique<Arena>(Arena{tbb::task_arena(threads > 0 ? threads : tbb::task_arena::automatic)})) {}

CpuBackend::~CpuBackend() = default;

void CpuBackend::render_pass(RenderJob& job) {
  arena_->arena.execute([&] {
    // One iteration per tile of the grid; each takes whichever tile the job hands out next.
    tbb::parallel_for(tbb::blocked_range<int>(0, job.tile_count(), 1),
                      [&](const tbb::blocked_range<int>& r) {
                        for (int i = r.begin(); i != r.end(); ++i) {
                          std::optional<TileWork> work = job.next_tile();
                          if (!work) return;
                          render_tile(job.view(), job.sampler(), job.film_layout(), job.stop(), *work);
                          job.deliver(std::move(*work));
                        }
                      },
                      tbb::simple_partitioner());
  });
}

}  // namespace strahl
