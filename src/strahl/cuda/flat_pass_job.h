#pragma once
// A back end that renders a pass as one flat launch (the GPU, cuda/flat_pass.h): takes every tile
// of the job's current pass, flattens them into PassData, has `run` render it, and delivers each
// tile with its sums back to the job. CudaBackend runs the pass on the GPU; the tests run it on
// the host (tests/flat_pass_test.cpp) — the same collecting, flattening and delivering either way.

#include <functional>
#include <string>

#include "strahl/cuda/flat_pass.h"
#include "strahl/render/render_job.h"

namespace strahl {

// Renders `pass` in place (every pixel's samples, PassData::taken filled; counters added to
// `counters`); false when the pass failed.
using FlatPassRun = std::function<bool(const FilmParams& film, PassData& pass, RayCounters& counters)>;

// One pass of `job` through `run`. When run fails, every tile goes back unchanged (no samples
// taken) and the job is cancelled.
void render_flat_pass(RenderJob& job, const FlatPassRun& run);

// PassArgs over `pass`'s own arrays (host memory), for running a pass on the host.
PassArgs host_pass_args(const SceneView& view, const PixelSampler& sampler, const FilmParams& film, PassData& pass,
                        const volatile int* stop);

}  // namespace strahl
