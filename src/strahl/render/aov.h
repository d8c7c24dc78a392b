#pragma once
// Arbitrary output variables: what the first hit of each pixel's centre ray (lens centre,
// mid-shutter) sees — not averaged over the pixel's samples, so edges stay crisp and ids exact.
//   depth   distance from the camera to the hit along the ray (+∞ where nothing is hit)
//   normal  the shading normal in world space, as the surface reports it (0 where nothing is hit)
//   albedo  the surface colour C (checkerboards evaluated) (0 where nothing is hit)
//   id      the object's index in scene order, in all three channels (−1 where nothing is hit)

#include "strahl/image/image.h"
#include "strahl/render/intersect_scene.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/surface_point.h"

namespace strahl {

struct AovSample {
  Real depth = kInfinity;
  Vec3 normal{0}, albedo{0};
  Real id = -1;
};

STRAHL_HOST_DEVICE inline AovSample aov_sample(const SceneView& s, int x, int row) {
  CameraSample cs;
  cs.film_x = Real(x) + Real(0.5);
  cs.film_y = Real(s.camera.ny - 1 - row) + Real(0.5);
  cs.time = Real(0.5);
  const Ray ray = s.camera.generate_ray(cs);
  const Hit hit = closest_hit(s, ray, 0, kInfinity);
  AovSample a;
  if (!hit.found()) return a;
  const SurfacePoint sp = surface_at(s, ray, hit);
  a.depth = (sp.p - ray.origin).length();
  a.normal = sp.normal;
  a.albedo = surface_color(s.materials[sp.material], sp.texcoord, s.textures);
  a.id = Real(sp.material);  // compile() gives every scene object its own material slot, in order
  return a;
}

struct AovImages {
  Image depth, normal, albedo, id;
};

AovImages render_aovs(const RenderScene& scene, int threads = 0);

}  // namespace strahl
