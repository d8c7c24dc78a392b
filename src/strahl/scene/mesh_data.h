#pragma once
// A triangle mesh as loaded from a file: shared positions, normals and texture coordinates, faces
// indexing them.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "strahl/image/image.h"
#include "strahl/math/vec3.h"
#include "strahl/util/large_array.h"

namespace strahl {

// A texture coordinate (OBJ `vt`, PLY u/v): where a uv-mapped image's planar square
// (shading/image_texture.h) lies on the surface — u across, v up.
struct Texcoord {
  Real u = 0, v = 0;
  friend bool operator==(const Texcoord&, const Texcoord&) = default;
};

// A material a mesh file gives some of its faces (a glTF material's base colour, an OBJ file's
// usemtl material's Kd and map_Kd), read only when
// asked for (load_mesh's `materials`); a scene's mesh with `file_materials` uses it
// (scene/file_materials.h).
struct FileMaterial {
  std::string name;
  Vec3 color{1, 1, 1};                // linear RGB
  std::shared_ptr<const Image> image;  // the colour's picture (linear RGB, times `color`), or none
  bool bilinear = true;               // false: the nearest pixel
};

struct MeshData {
  struct Face {
    std::array<std::uint32_t, 3> v{};        // position indices
    std::array<std::int32_t, 3> n{-1, -1, -1};  // normal indices, −1 where the file gives none
    std::array<std::int32_t, 3> t{-1, -1, -1};  // texture-coordinate indices, −1 where none
  };
  // LargeArrays (util/large_array.h): a large mesh's arrays in 2 MiB pages.
  LargeArray<Vec3> positions;
  LargeArray<Vec3> normals;
  LargeArray<Texcoord> texcoords;
  LargeArray<Face> faces;
  // With `materials` read: each face's index into them (−1: none); empty otherwise.
  std::vector<FileMaterial> materials;
  LargeArray<std::int32_t> face_materials;
};

}  // namespace strahl
