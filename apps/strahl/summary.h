#pragma once
// The end-of-render statistics: resolution, times by phase, rays by kind and throughput.

#include <string>

#include "strahl/render/renderer.h"

namespace strahl::cli {

struct Timings {
  double load = 0, build = 0, render = 0, write = 0;
};

std::string summary(const std::string& output, int width, int height, int threads,
                    const Timings& t, const RenderStats& stats, const RenderScene& scene);

}  // namespace strahl::cli
