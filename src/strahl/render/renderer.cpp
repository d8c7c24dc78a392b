#include "strahl/render/renderer.h"

#include "strahl/render/cpu_backend.h"

namespace strahl {

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats,
             const ProgressCallback& progress) {
  JobOptions job_options;
  job_options.tile_size = options.tile_size;
  job_options.cancel = options.cancel;
  job_options.time_limit = options.time_limit;
  job_options.checkpoint_interval = options.checkpoint_interval;
  job_options.checkpoint = options.checkpoint;
  job_options.progress = progress;
  RenderJob job(scene.view(), scene.sampling, std::move(job_options));
  CpuBackend cpu(options.threads);
  job.run(cpu);
  if (stats) *stats = job.stats();
  return job.image();
}

}  // namespace strahl
