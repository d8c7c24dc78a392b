#pragma once
// A triangle mesh as loaded from a file: shared positions and normals, faces indexing them.

#include <array>
#include <cstdint>
#include <vector>

#include "strahl/math/vec3.h"
#include "strahl/util/large_array.h"

namespace strahl {

struct MeshData {
  struct Face {
    std::array<std::uint32_t, 3> v{};        // position indices
    std::array<std::int32_t, 3> n{-1, -1, -1};  // normal indices, −1 where the file gives none
  };
  // LargeArrays (util/large_array.h): a large mesh's arrays in 2 MiB pages.
  LargeArray<Vec3> positions;
  LargeArray<Vec3> normals;
  LargeArray<Face> faces;
};

}  // namespace strahl
