#include "scenes.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "strahl/math/bounds.h"
#include "strahl/math/frame.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/scene.h"
#include "strahl/util/error.h"

namespace strahl::bench {

namespace {

// Scales and moves the positions to unit size (largest bounding-box side 1), centred on
// x = z = 0 and resting on y = 0.
void normalise(LargeArray<Vec3>& positions) {
  Bounds b;
  for (const Vec3& p : positions) b.extend(p);
  if (b.empty()) return;
  const Vec3 extent = b.hi - b.lo;
  const Real size = max_component(extent);
  const Real scale = size > 0 ? 1 / size : 1;
  const Vec3 anchor((b.lo.x + b.hi.x) / 2, b.lo.y, (b.lo.z + b.hi.z) / 2);
  for (Vec3& p : positions) p = (p - anchor) * scale;
}

std::vector<kernel::Triangle> triangles_of(const MeshData& mesh, const std::string& name) {
  std::vector<kernel::Triangle> out;
  out.reserve(mesh.faces.size());
  for (const MeshData::Face& f : mesh.faces) {
    for (std::uint32_t v : f.v)
      if (v >= mesh.positions.size()) throw Error(FileLoc{name}, "face refers to a vertex that does not exist");
    const Vec3 a = mesh.positions[f.v[0]];
    const Vec3 b = mesh.positions[f.v[1]], c = mesh.positions[f.v[2]];
    if (!(length_squared(cross(b - a, c - a)) > 0)) continue;  // degenerate, as compile() drops it
    out.push_back({a, b, c, 0, -1, 0});
  }
  return out;
}

// A pinhole camera with a 50° horizontal field of view looking at the bounding box's centre from
// the front, a little from the right and above, just far enough for every vertex to be in view.
Camera framing_camera(const std::vector<kernel::Triangle>& triangles, int width, int height) {
  Bounds b;
  for (const kernel::Triangle& t : triangles) {
    b.extend(t.v0);
    b.extend(t.v1);
    b.extend(t.v2);
  }
  if (b.empty()) b.extend(Vec3(0));
  const Real tan_h = std::tan(25 * kPi / 180);
  const Real tan_v = tan_h * height / width;
  const Vec3 center = (b.lo + b.hi) * Real(0.5);
  const Vec3 towards_eye = normalize(Vec3(0.3, 0.4, 1));
  const Vec3 up(0, 1, 0);
  const Frame f = Frame::look_at(center + towards_eye, center, up);
  Real distance = 0;
  const auto fit = [&](const Vec3& p) {
    const Vec3 q = p - center;
    const Real z = dot(q, f.w);
    distance = std::max({distance, z + std::fabs(dot(q, f.u)) / tan_h, z + std::fabs(dot(q, f.v)) / tan_v});
  };
  for (const kernel::Triangle& t : triangles) {
    fit(t.v0);
    fit(t.v1);
    fit(t.v2);
  }
  if (!(distance > 0)) distance = 1;
  distance *= Real(1.05);
  Camera cam;
  cam.eye = center + towards_eye * distance;
  cam.basis = Frame::look_at(cam.eye, center, up);
  cam.r = tan_h;
  cam.l = -tan_h;
  cam.t = tan_v;
  cam.b = -tan_v;
  cam.d = 1;
  cam.nx = width;
  cam.ny = height;
  return cam;
}

}  // namespace

BenchScene lecture_bench_scene(int width, int height) {
  Scene scene = lecture_scene();
  scene.settings.width = width;
  scene.settings.height = height;
  scene.settings.accel = AccelKind::Naive;  // nothing to build here
  const RenderScene rs = compile(scene);
  BenchScene out;
  out.name = "lecture";
  out.spheres = rs.spheres;
  out.triangles.assign(rs.triangles.begin(), rs.triangles.end());
  out.camera = rs.camera;
  out.light = rs.lights.empty() ? Vec3(1, 1.5, 1) : rs.lights.front().position;
  return out;
}

BenchScene framed_mesh_scene(std::string name, std::vector<kernel::Triangle> triangles, int width, int height) {
  BenchScene out;
  out.name = std::move(name);
  out.triangles = std::move(triangles);
  out.camera = framing_camera(out.triangles, width, height);
  out.light = Vec3(1, 1.5, 1);  // the lecture's light, for a unit-size object at the origin
  return out;
}

BenchScene procedural_bench_scene(std::size_t triangles, int width, int height) {
  const int n = std::max(1, int(std::lround(std::sqrt(double(triangles) / 12))));
  const int side = n + 1;
  MeshData mesh;
  mesh.positions.reserve(6 * std::size_t(side) * std::size_t(side));
  mesh.faces.reserve(12 * std::size_t(n) * std::size_t(n));
  // Each cube face: a grid warped by tan so the quads come out of similar size on the sphere.
  const Vec3 axes[6][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                           {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                           {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
  for (int face = 0; face < 6; ++face) {
    const Vec3& normal = axes[face][0];
    const Vec3& s_axis = axes[face][1];
    const Vec3& t_axis = axes[face][2];
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const Real s = std::tan((Real(2) * i / n - 1) * kPi / 4);
        const Real t = std::tan((Real(2) * j / n - 1) * kPi / 4);
        const Vec3 d = normalize(normal + s_axis * s + t_axis * t);
        const Real bumps = std::sin(11 * d.x) * std::sin(13 * d.y) * std::sin(12 * d.z);
        mesh.positions.push_back(d * (1 + Real(0.12) * bumps));
      }
    }
    // Quads split into two triangles, wound so that the front faces point outwards.
    const bool flip = dot(cross(s_axis, t_axis), normal) < 0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const std::uint32_t a = base + std::uint32_t(j * side + i), b = a + 1, c = a + std::uint32_t(side), d = c + 1;
        MeshData::Face f1, f2;
        f1.v = flip ? std::array<std::uint32_t, 3>{a, c, b} : std::array<std::uint32_t, 3>{a, b, c};
        f2.v = flip ? std::array<std::uint32_t, 3>{b, c, d} : std::array<std::uint32_t, 3>{b, d, c};
        mesh.faces.push_back(f1);
        mesh.faces.push_back(f2);
      }
    }
  }
  normalise(mesh.positions);
  return framed_mesh_scene("bumpy sphere", triangles_of(mesh, "bumpy sphere"), width, height);
}

BenchScene mesh_bench_scene(const std::filesystem::path& path, int width, int height) {
  MeshData mesh = load_mesh(path);
  normalise(mesh.positions);
  std::vector<kernel::Triangle> triangles = triangles_of(mesh, path.string());
  if (triangles.empty()) throw Error(FileLoc{path.string()}, "the mesh has no (non-degenerate) triangles");
  return framed_mesh_scene(path.filename().string(), std::move(triangles), width, height);
}

}  // namespace strahl::bench
