#pragma once
// strahl-view --benchmark N: N interactive frames (one sample per pixel at the full resolution,
// the camera orbiting a little between frames, as when a person drags) rendered headless
// through the viewer's own renderer; prints frames/s and Mrays/s.

#include <atomic>
#include <string>

#include "device_backend.h"
#include "scene_source.h"

namespace strahl::view {

// Returns the exit code (130 when `interrupted` is set meanwhile); prints to stdout. `backend`
// renders the frames (the GPU's holds the scene already).
int run_benchmark(const LoadedScene& scene, const std::string& name, int frames, DeviceBackend& backend, int threads,
                  int tile_size, const std::atomic<bool>* interrupted);

}  // namespace strahl::view
