#pragma once
// Radiance of one camera sample: the one entry point pixel samplers and the film call, whatever
// the integrator does inside (DESIGN.md, "Integrator"). A pure function of the scene, the camera
// sample and the sample's random stream (sampling/rng.h), so images are deterministic.

#include <type_traits>

#include "strahl/camera/camera_sample.h"
#include "strahl/render/path_tracer.h"
#include "strahl/render/sample_guard.h"
#include "strahl/render/whitted.h"
#include "strahl/sampling/rng.h"

namespace strahl {

// `observer`, where given, is told the ray tree (trace_observed(), render/whitted.h).
template <class Observer = NoTraceObserver>
STRAHL_HOST_DEVICE inline Vec3 sample_radiance(const SceneView& s, const CameraSample& cs, SampleStream& rng,
                                               RayCounters& counters, Observer* observer = nullptr) {
  const Ray ray = s.camera.generate_ray(cs);
  ++counters.camera;
  if constexpr (std::is_same_v<Observer, NoTraceObserver>) {
    if (s.settings.integrator == IntegratorKind::Path) return guard_sample(trace_path(s, ray, counters, rng), counters);
    return guard_sample(trace(s, ray, counters, rng), counters);
  } else {
    return guard_sample(trace_observed(s, ray, counters, rng, *observer), counters);
  }
}

}  // namespace strahl
