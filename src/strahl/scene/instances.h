#pragma once
// Instances (docs/scene-format.md, "Instances"): a group of objects (Scene::groups) compiled once
// into its own primitive arrays and acceleration structure, and placed any number of times by
// `type: instance` objects, each a small record (geometry/instance.h) with its own transform.

#include <cstdint>

#include "strahl/scene/scene.h"

namespace strahl {

// One placement of group number `group` of the scene (Scene::groups), by `placement`.
class Instance : public SceneObject {
 public:
  explicit Instance(std::uint32_t group_, const Transform& t = {}) : SceneObject(Material{}), group(group_) { placement = t; }
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  std::uint32_t group;
};

// Compiles every group of `scene` into out.groups (with out.group_bounds), before the objects
// that place them: their materials join out.materials. Throws strahl::Error at the object that
// cannot be in a group (a plane, an unbounded solid, a moving object, an instance).
void compile_groups(const Scene& scene, RenderScene& out);

// The top-level BVH over the instances' world boxes (after every object is compiled).
void build_instance_bvh(RenderScene& out);

}  // namespace strahl
