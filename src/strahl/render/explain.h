#pragma once
// One camera sample explained: the ray tree of sample `index` of pixel (x, row), as the lecture
// writes it — the camera ray from e, u, v, w and l, r, b, t, d; at each hit the object, t, the
// point and the normal, the ambient term and each light's N·L, shadow ray, N·H and share of the
// local colour; the reflected and refracted rays with k_r and T (total internal reflection
// named); and each ray's colour as local + k_r·reflected + T·tint·refracted. The integrator that
// renders the image walks the tree (trace()'s observer, render/whitted.h), so the explanation's
// radiance is the renderer's for that sample, bit for bit (`strahl --explain`, docs/cli.md).
// Whitted's integrator only: a scene that renders with integrator: path (render/path_tracer.h)
// has no ray tree; explain_pixel() throws for it, with explain_refusal()'s reason.

#include <cstdint>
#include <string>

#include "strahl/math/vec3.h"
#include "strahl/render/ray_counters.h"

namespace strahl {

struct RenderScene;
struct SamplingSettings;
struct SceneView;

struct PixelExplanation {
  std::string text;  // lines ending in '\n'
  Vec3 radiance;     // the sample's radiance (after the film's guard: NaN or ∞ become black)
  RayCounters rays;  // the sample's rays, as the renderer counts them
};

// `row` counts from the top of the image (as image viewers do), x from the left; both must lie
// in the image (throws strahl::Error otherwise). The scene as compiled, or a view `s` of it with
// its own camera and settings and the sampling it renders with (the viewer's).
PixelExplanation explain_pixel(const RenderScene& scene, int x, int row, std::uint32_t index = 0);
// Why the samples of view `s` cannot be explained (a path-traced scene), or "" where they can.
std::string explain_refusal(const SceneView& s);
PixelExplanation explain_pixel(const RenderScene& scene, const SceneView& s, const SamplingSettings& sampling, int x,
                               int row, std::uint32_t index = 0);

}  // namespace strahl
