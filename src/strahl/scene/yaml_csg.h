#pragma once
// The CSG objects of YAML scene files (docs/scene-format.md, "CSG"): union, intersection,
// difference, merge and inverse with their `objects`. The YAML loader hands a node whose type is
// one of these to read_csg() with what it lends it: locations, keys checks, materials and the
// reading of an operand (any object, a CSG node again through read_csg).

#include <yaml-cpp/yaml.h>

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>

#include "strahl/scene/csg.h"

namespace strahl {

struct CsgReader {
  std::function<FileLoc(const YAML::Node&)> loc;
  std::function<void(const YAML::Node&, std::initializer_list<std::string_view>, const std::string&)> keys;
  std::function<Material(const YAML::Node&)> material;               // the node's `material`
  std::function<Transform(const YAML::Node&)> placement;             // its scale, rotate, translate
  std::function<std::unique_ptr<SceneObject>(const YAML::Node&)> solid;  // an operand that is not CSG
};

bool is_csg_type(const std::string& type);

// `depth`: 1 for a CSG node in the objects list, one more for each node it is an operand of.
Csg read_csg(const YAML::Node& n, const std::string& type, const CsgReader& r, int depth = 1);

}  // namespace strahl
