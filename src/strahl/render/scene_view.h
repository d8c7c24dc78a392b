#pragma once
// The render-ready scene as plain pointers and counts: what kernel code (CPU now, CUDA later)
// reads. Built from a RenderScene, which owns the arrays.

#include <cstdint>

#include "strahl/accel/accel.h"
#include "strahl/accel/motion_bvh.h"
#include "strahl/accel/wide_bvh.h"
#include "strahl/camera/camera.h"
#include "strahl/geometry/moving.h"
#include "strahl/geometry/moving_instance.h"
#include "strahl/geometry/moving_solid.h"
#include "strahl/geometry/plane.h"
#include "strahl/geometry/sphere.h"
#include "strahl/geometry/triangle.h"
#include "strahl/math/bounds.h"
#include "strahl/render/instance_group.h"
#include "strahl/render/integrator_kind.h"
#include "strahl/render/ray_budget.h"
#include "strahl/shading/light.h"
#include "strahl/shading/material.h"

namespace strahl {

struct TraceSettings {
  int max_depth = 8;          // camera rays are depth 1 (POV-Ray's max_trace_level)
  Real min_weight = 1e-3;     // rays contributing less than this to the pixel are not traced
  Vec3 background{0};         // radiance of rays that hit nothing
  Vec3 ambient_light{1};      // scales every material's ambient term
  Real medium_ior = 1;        // index of refraction of the space between objects
  // Reflected and refracted rays one camera sample may spawn (docs/scene-format.md, "Recursion").
  // With min_weight 0 and glass (k_r + k_t = 1 at every hit) the ray tree doubles at each bounce;
  // the budget bounds one sample's work, so a cancel checked between samples acts in bounded time.
  std::uint32_t ray_budget = kDefaultRayBudget;
  IntegratorKind integrator = IntegratorKind::Whitted;
};

struct SceneView {
  const kernel::Sphere* spheres = nullptr;
  std::uint32_t sphere_count = 0;
  const kernel::Plane* planes = nullptr;
  std::uint32_t plane_count = 0;
  const kernel::Triangle* triangles = nullptr;
  std::uint32_t triangle_count = 0;
  const kernel::VertexNormals* vertex_normals = nullptr;
  const kernel::VertexTexcoords* vertex_texcoords = nullptr;
  AccelView accel;  // over spheres, triangles and bounded solids; planes are tested one by one
  // Every solid (geometry/solid.h): the first bounded_solid_count are in the structure (as its
  // primitives from accel.prims.first_solid() on), the rest (unclipped quadrics) are unbounded
  // and tested one by one, as planes are. Their arrays: accel.prims.shapes.
  const kernel::Solid* solids = nullptr;
  std::uint32_t solid_count = 0;
  std::uint32_t bounded_solid_count = 0;
  // Moving shapes (motion blur), in BVHs of their own over their swept boxes, one per time
  // segment (accel/motion_bvh.h): primitive i is moving sphere i, then come the moving triangles,
  // the moving solids (their shapes in the solids' arrays, accel.prims.shapes) and the moving
  // instances (their groups in `groups`), each numbered on from the kinds before it. Empty for
  // static scenes.
  const kernel::MovingSphere* moving_spheres = nullptr;
  std::uint32_t moving_sphere_count = 0;
  const kernel::MovingTriangle* moving_triangles = nullptr;
  std::uint32_t moving_triangle_count = 0;
  const kernel::MovingSolid* moving_solids = nullptr;
  std::uint32_t moving_solid_count = 0;
  const kernel::MovingInstance* moving_instances = nullptr;
  std::uint32_t moving_instance_count = 0;
  MotionBvhView moving_bvh;
  // Instances (render/instance_queries.h): small records in a BVH of their own over their world
  // boxes, each placing one of the groups. Empty without instances.
  const kernel::Instance* instances = nullptr;
  std::uint32_t instance_count = 0;
  IndexTreeView instance_bvh;
  const InstanceGroupView* groups = nullptr;
  Real shutter_open = 0, inv_shutter = 0;  // u = (time − open) · inv_shutter; 0 for no interval
  const Material* materials = nullptr;
  kernel::Textures textures;  // the image textures materials refer to
  bool opaque = false;  // no material is transparent: a shadow ray needs only an any-hit test
  const Light* lights = nullptr;
  std::uint32_t light_count = 0;
  std::uint32_t area_light_count = 0;  // of those, area lights (0: no emitter tests per ray)
  Camera camera;
  TraceSettings settings;

  // How many shapes move (0: the ray's time matters to nothing).
  STRAHL_HOST_DEVICE std::uint32_t moving_count() const {
    return moving_sphere_count + moving_triangle_count + moving_solid_count + moving_instance_count;
  }
};

}  // namespace strahl
