#pragma once
// CSG in the scene API and scene files (docs/scene-format.md, "CSG"): union, intersection,
// difference, merge and inverse over solids (box, cylinder, cone, torus, unclipped quadric,
// implicit, sphere) and other CSG nodes. compile() turns a tree into a kernel::Csg
// (geometry/csg.h) with one material: the outermost node's.
//
//   std::vector<std::unique_ptr<SceneObject>> parts;
//   parts.push_back(std::make_unique<Box>(Vec3(-1), Vec3(1), m));
//   parts.push_back(std::make_unique<Sphere>(Vec3(0), 1.3, m));
//   scene.add(Csg(CsgOperation::Difference, std::move(parts), m));

#include <memory>
#include <vector>

#include "strahl/scene/scene.h"

namespace strahl {

enum class CsgOperation { Union, Intersection, Difference, Merge, Inverse };

const char* csg_operation_name(CsgOperation op);

// Nesting: a tree may hold CSG nodes at most this many levels deep (the outermost is level 1),
// and at most kernel::kMaxCsgLeaves solids in all.
inline constexpr int kMaxCsgDepth = 7;

class Csg : public SceneObject {
 public:
  Csg(CsgOperation op, std::vector<std::unique_ptr<SceneObject>> children_, const Material& m)
      : SceneObject(m), operation(op), children(std::move(children_)) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  CsgOperation operation;
  std::vector<std::unique_ptr<SceneObject>> children;  // inverse: exactly one
};

}  // namespace strahl
