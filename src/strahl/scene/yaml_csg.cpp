// The CSG nodes of YAML scene files (docs/scene-format.md, "CSG"): union, intersection,
// difference, merge and inverse with their `objects` (yaml_reader.h).

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "strahl/scene/yaml_reader.h"

namespace strahl {
namespace {

struct Named {
  const char* name;
  CsgOperation op;
};
constexpr std::array<Named, 5> kOperations{{{"union", CsgOperation::Union},
                                            {"intersection", CsgOperation::Intersection},
                                            {"difference", CsgOperation::Difference},
                                            {"merge", CsgOperation::Merge},
                                            {"inverse", CsgOperation::Inverse}}};

// Object types that have an inside (what CSG combines).
constexpr std::array<const char*, 7> kOperandTypes{"box", "cylinder", "cone", "torus", "quadric", "implicit", "sphere"};

}  // namespace

bool is_csg_type(const std::string& type) {
  return std::any_of(kOperations.begin(), kOperations.end(), [&](const Named& o) { return type == o.name; });
}

Csg YamlReader::csg(const YAML::Node& n, const std::string& type, int depth) const {
  CsgOperation op = CsgOperation::Union;
  for (const Named& o : kOperations)
    if (type == o.name) op = o.op;
  if (depth == 1) keys(n, {"type", "objects", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, type);
  else
    keys(n, {"type", "objects", "scale", "rotate", "translate", "matrix", "transform"},
         type + " (inside a CSG: the outermost one's material applies)");
  if (depth > kMaxCsgDepth)
    fail(n, type + " is nested too deeply: CSG nodes may be nested at most " + std::to_string(kMaxCsgDepth) +
                " levels deep");
  const YAML::Node list = n["objects"];
  if (!list) fail(n, type + " needs 'objects' (the solids it combines)");
  if (!list.IsSequence()) fail(list, type + " objects must be a list");
  if (list.size() == 0) fail(list, "empty " + type + ": it needs at least one object");
  if (op == CsgOperation::Inverse && list.size() != 1)
    fail(list, "inverse takes exactly one object (got " + std::to_string(list.size()) + ")");
  std::vector<std::unique_ptr<SceneObject>> children;
  for (const YAML::Node& child : list) {
    if (!child.IsMap()) fail(child, "a " + type + " object must be a map of keys to values");
    const YAML::Node t = child["type"];
    if (!t || !t.IsScalar()) fail(child, "a " + type + " object needs 'type'");
    const std::string child_type = t.Scalar();
    if (is_csg_type(child_type)) {
      children.push_back(std::make_unique<Csg>(csg(child, child_type, depth + 1)));
      continue;
    }
    if (std::find_if(kOperandTypes.begin(), kOperandTypes.end(), [&](const char* k) { return child_type == k; }) ==
        kOperandTypes.end())
      fail(t, "'" + child_type + "' cannot be an object of " + type +
                  " (closed solids only: box, cylinder, cone, torus, quadric, implicit, sphere, or union, "
                  "intersection, difference, merge, inverse)");
    if (const YAML::Node m = child["material"])
      fail(m, "an object of a CSG takes the CSG's material: give 'material' on the outermost " + type +
                  " (split it into separate objects to give parts their own)");
    Scene operand;
    object(child, operand);
    children.push_back(operand.take_last());
  }
  Csg c(op, std::move(children), depth == 1 ? object_material(n) : Material{});
  c.loc = loc(n);
  c.placement = placement(n);
  return c;
}

}  // namespace strahl
