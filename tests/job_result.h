#pragma once
// What the render-job tests compare between back ends: every pixel's film sums (not only the
// rounded image), the job's statistics and each pixel's sample count.

#include <array>
#include <cstdint>
#include <vector>

#include "strahl/render/render_job.h"
#include "strahl/render/render_scene.h"

namespace strahl::test {

struct JobResult {
  std::vector<std::array<double, 4>> sums;
  RenderStats stats;
  std::vector<std::uint32_t> pixel_samples;
};

// One job over `rs` on `backend`.
inline JobResult run_job(const RenderScene& rs, TileBackend& backend, JobOptions options) {
  RenderJob job(rs.view(), rs.sampling, std::move(options));
  job.run(backend);
  JobResult r;
  for (int row = 0; row < rs.camera.ny; ++row)
    for (int x = 0; x < rs.camera.nx; ++x) r.sums.push_back(job.film().sums(x, row));
  r.stats = job.stats();
  r.pixel_samples.assign(job.pixel_samples().begin(), job.pixel_samples().end());
  return r;
}

}  // namespace strahl::test
