#pragma once
// strahl-view --benchmark N: N interactive frames (one sample per pixel at the full resolution,
// the camera orbiting a little between frames, as when a person drags) rendered headless
// through the viewer's own renderer; prints frames/s and Mrays/s.

#include <atomic>
#include <string>

#include "scene_source.h"

namespace strahl::view {

// Returns the exit code (130 when `interrupted` is set meanwhile); prints to stdout.
int run_benchmark(const LoadedScene& scene, const std::string& name, int frames, int threads, int tile_size,
                  const std::atomic<bool>* interrupted);

}  // namespace strahl::view
