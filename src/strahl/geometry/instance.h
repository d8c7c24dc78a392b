#pragma once
// An instance (scene `type: instance`, docs/scene-format.md "Instances"): one placement of a
// group of objects that is compiled once, with its own acceleration structure, and shared by
// every instance of it (a two-level hierarchy: render/instance_queries.h). The record is small
// and plain: the world → object map of geometry/placement.h, the group and two numbers.

#include <cstdint>

#include "strahl/geometry/placement.h"

namespace strahl::kernel {

struct Instance {
  Placement to_object;      // world → the group's object space
  Real stretch = 1;         // bounds how much the object → world map lengthens (ray offsets)
  Real shift = 0;           // max |component| of the translation (ray offsets)
  std::uint32_t group = 0;  // into SceneView::groups
  // The linear part is the identity (a translation only): rays keep their direction and normals
  // pass unchanged, so such an instance gives the same bits as its objects written in place.
  bool translation_only = false;
};

// The ray in the group's object space with a unit direction (what the shapes' intersection tests
// expect); object t = world t · scale.
struct InstanceRay {
  Ray ray;
  Real scale = 1;
};

STRAHL_HOST_DEVICE inline InstanceRay instance_ray(const Instance& x, const Ray& ray) {
  InstanceRay r{object_ray(x.to_object, ray), 1};
  if (!x.translation_only) {
    r.scale = std::sqrt(dot(r.ray.direction, r.ray.direction));
    r.ray.direction = r.ray.direction * (1 / r.scale);
  }
  return r;
}

}  // namespace strahl::kernel
