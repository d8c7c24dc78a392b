#pragma once
// The POV-Ray importer's parser: directives (#declare, #if, #while, #for, #include …), float
// and vector expressions, and the scene's items, read into the plain records below. The
// translation into strahl's scene format (pov_scene.cpp) reads these records.

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "strahl/scene/mesh_data.h"
#include "strahl/scene/pov/pov_scene.h"
#include "strahl/util/error.h"
#include "strahl/util/number_syntax.h"

namespace strahl::pov {

using Color = std::array<double, 5>;  // red, green, blue, filter, transmit
using Vector = std::array<double, 3>;

inline constexpr double kPi = 3.14159265358979323846;  // (in double whatever strahl's Real is)

// The few vector operations the importer needs, in double.
inline double length(const Vector& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
inline Vector minus(const Vector& a, const Vector& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vector& a, const Vector& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vector cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Numbers and vectors as YAML text: the shortest form that reads back to the same double.
inline std::string yaml_number(double v) { return number::shortest(v); }
inline std::string yaml_vector(const Vector& v) {
  return "[" + yaml_number(v[0]) + ", " + yaml_number(v[1]) + ", " + yaml_number(v[2]) + "]";
}

// A string as a YAML double-quoted scalar.
inline std::string yaml_string(const std::string& text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s = "\"";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') s += '\\', s += ch;
    else if (c < 0x20 || c == 0x7f) s += "\\x", s += kHex[c >> 4], s += kHex[c & 15];
    else s += ch;
  }
  return s + "\"";
}

struct Pigment {
  Color color{};  // POV-Ray's default pigment is black
  bool checker = false;
  Color color2{};
  double scale = 1;  // the checker's square size
  // An image_map: its keys of a scene file's `image` map (empty: none) — `image` the file
  // ("file: …"), `mapping` map_type's (planar, spherical, cylindrical), `image_options` the rest
  // ("interpolate: …, once: …") — and the pigment's transforms in order (steps of a transform
  // list), which place it.
  std::string image, mapping = "planar", image_options;
  std::vector<std::string> steps;
  // uv_mapping: the image is read at the surface's UVs (strahl's mapping uv), its transforms act
  // on (u, v, 0) and the object's transforms do not move it.
  bool uv = false;
};

// POV-Ray's default finish.
struct Finish {
  double ambient = 0.1, diffuse = 0.6, specular = 0, roughness = 0.05, reflection = 0;
  double phong = 0, phong_size = 40;
  Color emission{};  // times the pigment's colour
  bool fresnel = false;
};

struct Interior {
  double ior = 1;
  bool fresnel = false;
};

struct Texture {
  bool has_pigment = false, has_finish = false, has_interior = false;
  Pigment pigment;
  Finish finish;
  Interior interior;
  // What it holds that strahl draws otherwise or leaves out ("file:line:column: what"): warnings
  // where an object uses it, not where it is declared (an include file's unused textures say nothing).
  std::vector<std::string> notes;
  bool given() const { return has_pigment || has_finish || has_interior; }
};

// A shape or CSG node: its strahl type, its own keys as YAML text, transform steps in order.
struct Object {
  std::string type;
  FileLoc loc;
  std::string keys;                // ", center: [0, 1, 0], radius: 0.5"
  std::vector<std::string> steps;  // "{translate: [1, 0, 0]}", applied in this order
  std::vector<Object> children;    // union, intersection, difference, merge
  Texture texture;
  std::size_t texture_steps = 0;   // how many of `steps` came before the pigment (those do not move it)
  bool inverse = false;
  int mesh = -1;                   // index in Parsed::meshes
};

struct Light {
  Vector position{};
  Color color{1, 1, 1, 0, 0};
  bool parallel = false;   // a directional light along point_at − position
  bool spotlight = false;  // a spot light along point_at − position (radius, falloff in degrees)
  Vector point_at{0, 0, 1};
  double radius = 30, falloff = 45, tightness = 0;
  double fade_distance = 0, fade_power = 0;  // POV-Ray's fade (point and spot lights)
  FileLoc loc;
};

struct Camera {
  Vector location{0, 0, 0}, look_at{0, 0, 1}, right{1.33, 0, 0}, up{0, 1, 0}, direction{0, 0, 1}, sky{0, 1, 0};
  bool has_look_at = false, has_angle = false;
  double angle = 0;
  double aperture = 0;
  bool has_focal_point = false;
  Vector focal_point{};
  int blur_samples = 0;
  FileLoc loc;
};

struct Parsed {
  Camera camera;
  std::vector<Light> lights;
  std::vector<Object> objects;
  std::vector<MeshData> meshes;
  std::vector<std::string> warnings;
  Color background{};
  Color ambient_light{1, 1, 1, 0, 0};
  int max_trace_level = 5;
  bool radiosity = false;  // global_settings { radiosity { … } }: drawn by path tracing
  Texture default_texture;
};

// Reads `text` (the file `name`: #include finds files beside it) and what it includes. Throws
// strahl::Error at the offending file:line:column.
Parsed parse_pov(const std::string& text, const std::string& name, const PovOptions& options);

}  // namespace strahl::pov
