#pragma once
// The benchmark's scenes: the bounded primitives an acceleration structure is built over, a
// pinhole camera and a point light. Planes are not part of any structure and are left out.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "strahl/accel/primitive.h"
#include "strahl/camera/camera.h"
#include "strahl/geometry/sphere.h"
#include "strahl/geometry/triangle.h"

namespace strahl::bench {

struct BenchScene {
  std::string name;
  std::vector<kernel::Sphere> spheres;
  std::vector<kernel::Triangle> triangles;
  Camera camera;
  Vec3 light;  // point light for the shadow rays

  PrimitiveSet primitives() const {
    return {spheres.data(), static_cast<std::uint32_t>(spheres.size()), triangles.data(),
            static_cast<std::uint32_t>(triangles.size()), nullptr, 0, {}};
  }
  std::size_t size() const { return spheres.size() + triangles.size(); }
};

// The lecture's five spheres with its own camera and light (its plane is not in the structures).
BenchScene lecture_bench_scene(int width, int height);

// A closed "bumpy sphere": a cube-sphere (6 faces of n×n quads, 12·n² triangles) displaced by a
// product of sines, with n chosen so that the count is close to `triangles`. Normalised to unit
// size resting on y = 0, framed like a mesh file.
BenchScene procedural_bench_scene(std::size_t triangles, int width, int height);

// A mesh file (.obj or .ply), normalised to unit size (largest bounding-box side 1), centred on x = z = 0
// and resting on y = 0; degenerate faces dropped. Throws strahl::Error when it cannot be read.
BenchScene mesh_bench_scene(const std::filesystem::path& path, int width, int height);

// Triangles (unit size, resting on y = 0) with a camera that frames them and a light at (1, 1.5, 1).
BenchScene framed_mesh_scene(std::string name, std::vector<kernel::Triangle> triangles, int width, int height);

}  // namespace strahl::bench
