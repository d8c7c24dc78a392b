#pragma once
// A triangle mesh as loaded from a file: shared positions and normals, faces indexing them.

#include <array>
#include <cstdint>
#include <vector>

#include "strahl/math/vec3.h"

namespace strahl {

struct MeshData {
  struct Face {
    std::array<std::uint32_t, 3> v{};        // position indices
    std::array<std::int32_t, 3> n{-1, -1, -1};  // normal indices, −1 where the file gives none
  };
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Face> faces;
};

}  // namespace strahl
