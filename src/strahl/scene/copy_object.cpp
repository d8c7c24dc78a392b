#include "strahl/scene/copy_object.h"

#include <vector>

#include "strahl/scene/csg.h"
#include "strahl/scene/solids.h"

namespace strahl {

std::unique_ptr<SceneObject> copy_object(const SceneObject& o) {
  if (const auto* c = dynamic_cast<const Csg*>(&o)) {
    std::vector<std::unique_ptr<SceneObject>> children;
    for (const auto& child : c->children) {
      children.push_back(copy_object(*child));
      if (!children.back()) return nullptr;
    }
    auto copy = std::make_unique<Csg>(c->operation, std::move(children), c->material);
    copy->loc = c->loc;
    copy->motion = c->motion;
    copy->placement = c->placement;
    return copy;
  }
  if (const auto* x = dynamic_cast<const Sphere*>(&o)) return std::make_unique<Sphere>(*x);
  if (const auto* x = dynamic_cast<const Plane*>(&o)) return std::make_unique<Plane>(*x);
  if (const auto* x = dynamic_cast<const Triangle*>(&o)) return std::make_unique<Triangle>(*x);
  if (const auto* x = dynamic_cast<const Mesh*>(&o)) return std::make_unique<Mesh>(*x);
  if (const auto* x = dynamic_cast<const Box*>(&o)) return std::make_unique<Box>(*x);
  if (const auto* x = dynamic_cast<const Cone*>(&o)) return std::make_unique<Cone>(*x);
  if (const auto* x = dynamic_cast<const Disk*>(&o)) return std::make_unique<Disk>(*x);
  if (const auto* x = dynamic_cast<const Torus*>(&o)) return std::make_unique<Torus>(*x);
  if (const auto* x = dynamic_cast<const Quadric*>(&o)) return std::make_unique<Quadric>(*x);
  if (const auto* x = dynamic_cast<const ImplicitSurface*>(&o)) return std::make_unique<ImplicitSurface>(*x);
  return nullptr;
}

}  // namespace strahl
