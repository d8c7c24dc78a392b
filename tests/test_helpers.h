#pragma once
// Shared helpers of the strahl test suite: tiny scenes built through the C++ API, one-pixel
// renders, temporary directories and vector comparisons.

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "strahl/image/image.h"
#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"

namespace strahl {
namespace fs = std::filesystem;
}

namespace strahl::test {

// Component-wise |a − b| ≤ tol, with a readable failure message.
inline ::testing::AssertionResult vec_near(const Vec3& a, const Vec3& b, Real tol) {
  const Real dx = std::fabs(a.x - b.x), dy = std::fabs(a.y - b.y), dz = std::fabs(a.z - b.z);
  if (dx <= tol && dy <= tol && dz <= tol) return ::testing::AssertionSuccess();
  std::ostringstream s;
  s.precision(17);
  s << "(" << a.x << ", " << a.y << ", " << a.z << ") vs expected (" << b.x << ", " << b.y << ", " << b.z
    << "), tolerance " << tol;
  return ::testing::AssertionFailure() << s.str();
}
#define EXPECT_VEC_NEAR(a, b, tol) EXPECT_TRUE(::strahl::test::vec_near((a), (b), (tol)))

inline Vec3 to_vec(const Rgb& c) { return {c.r, c.g, c.b}; }

// A material that shows its colour exactly under ambient light 1 and nothing else.
inline Material emissive_like(const Vec3& color) {
  Material m;
  m.color = color;
  m.ambient = 1;
  m.diffuse = 0;
  m.specular = Vec3(0);
  return m;
}

// A material with ambient, Lambert and Blinn-Phong terms chosen by the test.
inline Material phong(const Vec3& color, Real ka, Real kd, const Vec3& ks, Real shininess) {
  Material m;
  m.color = color;
  m.ambient = ka;
  m.diffuse = kd;
  m.specular = ks;
  m.shininess = shininess;
  return m;
}

// Transparency 1, no local terms, no reflection: only the refracted ray contributes.
inline Material clear_glass(Real ior) {
  Material m;
  m.color = Vec3(1);
  m.ambient = 0;
  m.diffuse = 0;
  m.specular = Vec3(0);
  m.transparency = 1;
  m.ior = ior;
  return m;
}

// A perfect (or partial) mirror with no local terms except an optional ambient colour.
inline Material mirror(Real reflectivity, const Vec3& ambient_color = Vec3(0)) {
  Material m;
  m.color = ambient_color;
  m.ambient = 1;
  m.diffuse = 0;
  m.specular = Vec3(0);
  m.reflectivity = reflectivity;
  return m;
}

// Camera with an explicit image plane.
inline void set_camera(Scene& s, const Vec3& eye, const Vec3& look_at, const Vec3& up, Real l, Real r, Real b,
                       Real t, Real d, int nx, int ny) {
  s.camera.position = eye;
  s.camera.look_at = look_at;
  s.camera.up = up;
  s.camera.explicit_image_plane = true;
  s.camera.l = l;
  s.camera.r = r;
  s.camera.b = b;
  s.camera.t = t;
  s.camera.d = d;
  s.settings.width = nx;
  s.settings.height = ny;
}

// A 1×1 image whose only (centre) ray runs exactly from `eye` towards `target`.
inline void one_ray_camera(Scene& s, const Vec3& eye, const Vec3& target, const Vec3& up = Vec3(0, 1, 0)) {
  set_camera(s, eye, target, up, -1, 1, -1, 1, 1, 1, 1);
}

// Radiance of one pixel (row counted from the top), through the same code path as render().
inline Vec3 pixel(const Scene& scene, int x = 0, int row = 0, RayCounters* counters = nullptr) {
  const RenderScene rs = compile(scene);
  RayCounters local;
  return render_pixel(rs.view(), x, row, rs.supersample, counters ? *counters : local);
}

inline Image render_image(const Scene& scene, int threads = 1, int tile = 32, RenderStats* stats = nullptr) {
  RenderOptions o;
  o.threads = threads;
  o.tile_size = tile;
  return render(compile(scene), o, stats);
}

// The largest channel difference between two images of the same size.
inline float max_abs_diff(const Image& a, const Image& b) {
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  float worst = 0;
  for (std::size_t i = 0; i < a.pixels().size() && i < b.pixels().size(); ++i) {
    const Rgb &p = a.pixels()[i], &q = b.pixels()[i];
    worst = std::fmax(worst, std::fabs(p.r - q.r));
    worst = std::fmax(worst, std::fabs(p.g - q.g));
    worst = std::fmax(worst, std::fabs(p.b - q.b));
  }
  return worst;
}

// A fresh directory under the system's temporary directory, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "strahl-test-XXXXXX").string();
    if (::mkdtemp(templ.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = templ;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline Real deg(Real degrees) { return degrees * kPi / 180; }

// The message of the strahl::Error that f throws ("" and a failure if it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no strahl::Error thrown";
  return {};
}

// The error a scene file's text (read as "bad.yaml") gives when parsed and compiled, or "no error".
inline std::string compile_error(const std::string& text) {
  try {
    compile(parse_scene(text, "bad.yaml", "."));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace strahl::test
