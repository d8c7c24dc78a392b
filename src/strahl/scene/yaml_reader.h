#pragma once
// The reader of YAML/JSON scene files, shared by the files that read its parts (scene_file.h is
// the interface: parse_scene, load_scene). Strict: unknown keys, wrong types and impossible values
// are errors naming the file:line:column of the offending node.
//
//   yaml_loader.cpp     the entry: limits, the objects parsed in batches, the scene's sections
//   yaml_values.cpp     numbers, whole numbers, booleans, vectors, colours, keys
//   yaml_settings.cpp   render and sampling settings, camera, materials, lights
//   yaml_placement.cpp  transforms and motion
//   yaml_objects.cpp    objects, solids, implicit surfaces, groups and instances
//   yaml_csg.cpp        CSG nodes: union, intersection, difference, merge, inverse

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "strahl/scene/csg.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/solids.h"

namespace strahl {

// One element of the top-level objects list, read on its own.
// union, intersection, difference, merge or inverse (yaml_csg.cpp).
bool is_csg_type(const std::string& type);

struct ObjectText {
  int line;          // of its first line in the file, 0-based
  std::string text;  // from there on, the `- ` before it blanked
};

class YamlReader {
 public:
  YamlReader(std::string name, std::filesystem::path base_dir, MeshSource meshes)
      : name_(std::move(name)), base_dir_(std::move(base_dir)), meshes_(std::move(meshes)) {}

  // `objects`: when not empty, the text of each element of the top-level objects list, read one
  // at a time (the list itself was blanked out of `root`'s text, line numbers kept).
  Scene read(const YAML::Node& root, const std::vector<ObjectText>& objects = {});

 private:
  using Keys = std::initializer_list<std::string_view>;

  // ---- values (yaml_values.cpp) ---------------------------------------------------------------
  FileLoc loc(const YAML::Node& n) const;
  [[noreturn]] void fail(const YAML::Node& n, const std::string& message) const { throw Error(loc(n), message); }
  void map(const YAML::Node& n, const std::string& what) const;
  void sequence(const YAML::Node& n, const std::string& what) const;
  void keys(const YAML::Node& n, Keys allowed, const std::string& what) const;
  YAML::Node required(const YAML::Node& n, const char* key, const std::string& what) const;
  std::string scalar(const YAML::Node& n, const std::string& what) const;
  void plain(const YAML::Node& n, const std::string& what, const char* kind) const;
  Real number(const YAML::Node& n, const std::string& what) const;
  std::uint64_t whole(const YAML::Node& n, const std::string& what, std::int64_t lo, std::uint64_t hi) const;
  int integer(const YAML::Node& n, const std::string& what, int lo, int hi) const;
  bool boolean(const YAML::Node& n, const std::string& what) const;
  Vec3 vec3(const YAML::Node& n, const std::string& what) const;
  Vec3 color(const YAML::Node& n, const std::string& what) const;
  Real non_negative(const YAML::Node& n, const std::string& what) const;
  Real positive(const YAML::Node& n, const std::string& what) const;
  Real unit(const YAML::Node& n, const std::string& what) const;
  Real ior(const YAML::Node& n, const std::string& what) const;

  // ---- settings (yaml_settings.cpp) -----------------------------------------------------------
  void render(const YAML::Node& n, RenderSettings& s) const;
  void sampling(const YAML::Node& n, SamplingSettings& s) const;
  void camera(const YAML::Node& n, CameraDescription& c) const;
  Material material(const YAML::Node& n) const;
  std::uint32_t image_texture(const YAML::Node& n) const;
  Material object_material(const YAML::Node& object) const;
  void light(const YAML::Node& n, Scene& scene) const;
  void spot_light(const YAML::Node& n, const Vec3& c, Real intensity, Scene& scene) const;
  void fade(const YAML::Node& n, Light& l) const;
  void area_light(const YAML::Node& n, const std::string& type, const Vec3& c, Scene& scene) const;

  // ---- placement and motion (yaml_placement.cpp) ----------------------------------------------
  Transform transform(const YAML::Node& n, const std::string& what) const;
  Motion motion(const YAML::Node& n) const;
  Spin spin(const YAML::Node& n) const;
  Transform placement(const YAML::Node& n, const std::string& what = "") const;
  Vec3 scale(const YAML::Node& v, const std::string& what) const;
  Mat3 rotation(const YAML::Node& v) const;
  void affine_matrix(const YAML::Node& v, Mat3& m, Vec3& t) const;
  void check_determinant(const YAML::Node& v, Real det, const std::string& what) const;

  // ---- objects (yaml_objects.cpp) -------------------------------------------------------------
  void groups(const YAML::Node& n, Scene& scene);
  SceneObject* instance(const YAML::Node& n, Scene& scene) const;
  void object(const YAML::Node& n, Scene& scene) const;
  // A CSG node (yaml_csg.cpp); `depth`: 1 for one in the objects list, one more for each node it
  // is an operand of. Its solid operands are read by object().
  Csg csg(const YAML::Node& n, const std::string& type, int depth = 1) const;
  void corners(const YAML::Node& n, const std::string& what, Vec3& a, Vec3& b) const;
  void bound(const YAML::Node& n, const std::string& what, bool sphere_allowed, ImplicitSurface* s, ClipBox* clip) const;
  SceneObject* solid(const std::string& type, const YAML::Node& n, Scene& scene) const;
  SceneObject* implicit(const YAML::Node& n, Scene& scene) const;

  std::string name_;
  std::filesystem::path base_dir_;
  MeshSource meshes_;  // empty: mesh files are read from base_dir_
  std::map<std::string, Material> materials_;
  // The image textures the materials read so far name (Material::texture indexes this list, which
  // read() hands to the scene), and each picture read, by file, so that materials share it.
  mutable std::vector<ImageTexture> textures_;
  mutable std::map<std::pair<std::filesystem::path, bool>, std::shared_ptr<const Image>> images_;
  int line_offset_ = 0;                               // of the object being read from its own text
  std::map<std::string, std::uint32_t> group_index_;  // into Scene::groups
  const std::string* reading_group_ = nullptr;        // the group whose objects are being read
};

}  // namespace strahl
