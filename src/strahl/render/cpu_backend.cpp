#include "strahl/render/cpu_backend.h"

#include <algorithm>

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
    // One task per thread, each rendering whichever tile the job hands out next until none is
    // left, in one TileWork whose buffers it reuses.
    const int tasks = std::min(job.tile_count(), tbb::this_task_arena::max_concurrency());
    tbb::parallel_for(tbb::blocked_range<int>(0, tasks, 1),
                      [&](const tbb::blocked_range<int>&) {
                        TileWork work;
                        while (job.next_tile(work)) {
                          render_tile(job.view(), job.sampler(), job.film_layout(), job.stop(), work);
                          job.deliver(work);
                        }
                      },
                      tbb::simple_partitioner());
  });
}

}  // namespace strahl
