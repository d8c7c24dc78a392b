#pragma once
// Instances (docs/scene-format.md, "Instances"): a group of objects (Scene::groups) compiled once
// into its own primitive arrays and acceleration structure, and placed any number of times by
// `type: instance` objects, each a small record (geometry/instance.h) with its own transform. A
// group may place earlier groups (nesting): compiling an instance unfolds them into one record
// per group reached, each with the composed transform, so the kernels see one level only.

#include <cstdint>

#include "strahl/geometry/moving_map.h"
#include "strahl/scene/scene.h"

namespace strahl {

// The most instance records a scene may hold once nested groups are unfolded (each instance of a
// group that places others becomes one record per group it reaches; about 400 bytes each at the
// peak of the build).
inline constexpr std::uint64_t kMaxInstanceRecords = std::uint64_t(1) << 24;

// One placement of group number `group` of the scene (Scene::groups), by `placement`.
class Instance : public SceneObject {
 public:
  explicit Instance(std::uint32_t group_, const Transform& t = {}) : SceneObject(Material{}), group(group_) { placement = t; }
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  std::uint32_t group;
};

// Compiles every group of `scene` into out.groups (with out.group_bounds and out.group_nesting),
// before the objects that place them: their materials join out.materials. A group may place
// instances of the groups defined before it (nested; they stand still in it). Throws strahl::Error
// at the object that cannot be in a group (a plane, an unbounded solid, a moving object, an
// instance of itself or of a later group).
void compile_groups(const Scene& scene, RenderScene& out);

// A moving object that turns (scene/move_solid.h: a sphere, triangle or mesh whose keyframes
// turn it): `group` holds it unmoved, and becomes a group of out's (its BVH built), placed by a
// moving instance carried by `map` — as a moving instance of a group in the scene file is.
void move_by_instance(RenderScene& out, RenderScene&& group, const kernel::MovingMap& map, const FileLoc& loc);

// The top-level BVH over the instances' world boxes (after every object is compiled).
void build_instance_bvh(RenderScene& out);

}  // namespace strahl
