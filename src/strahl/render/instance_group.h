#pragma once
// A group of objects shared by instances (geometry/instance.h), as kernels read it: its own
// primitive set and acceleration structure (of the scene's --accel kind; Embree falls back to
// the BVH), and its vertex normals and texture coordinates. Materials index the scene's one
// material array.

#include "strahl/accel/accel.h"
#include "strahl/geometry/instance.h"

namespace strahl {

struct InstanceGroupView {
  AccelView accel;  // over the group's spheres, triangles and solids, in its object space
  const kernel::VertexNormals* vertex_normals = nullptr;
  const kernel::VertexTexcoords* vertex_texcoords = nullptr;
};

}  // namespace strahl
