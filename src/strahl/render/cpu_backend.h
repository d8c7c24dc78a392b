#pragma once
// The CPU back end: the tiles of a pass rendered by oneTBB's threads, each through render_tile().

#include <memory>

#include "strahl/render/render_job.h"

namespace strahl {

class CpuBackend final : public TileBackend {
 public:
  explicit CpuBackend(int threads = 0);  // 0: all cores
  ~CpuBackend() override;
  void render_pass(RenderJob& job) override;

 private:
  struct Arena;  // a tbb::task_arena of the thread count asked for
  std::unique_ptr<Arena> arena_;
};

}  // namespace strahl
