#pragma once
// What building an acceleration structure cost and produced.

#include <cstddef>

namespace strahl {

struct AccelBuildStats {
  double seconds = 0;
  std::size_t primitives = 0;
  std::size_t nodes = 0;
  std::size_t leaves = 0;
  std::size_t max_depth = 0;
  std::size_t primitive_references = 0;  // > primitives where leaves share primitives (kd-tree, octree)
  std::size_t bytes = 0;                 // memory of the structure itself
};

}  // namespace strahl
