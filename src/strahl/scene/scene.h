#pragma once
// The editable, user-facing scene (the lecture's C++ API and what scene files load into).
// compile() turns it into the immutable RenderScene.
//
//   Scene* scene = new Scene();
//   scene->addSceneObject(new Plane(Vec3(0.0, 1.0, 0.0), 0.0, Vec3(0.3, 0.3, 0.3)));
//   scene->addSceneObject(new Sphere(Vec3(0.05, 0.3, 0.0), 0.3, Vec3(0.8, 0.2, 0.2)));
//   scene->addLightSource(Vec3(1.0, 1.5, 1.0));
//
// or with value types:  Scene s; s.add(Sphere{{0, 1, 0}, 0.5, glass}); s.add(point_light({1, 2, 3}));

#include <concepts>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "strahl/accel/accel.h"
#include "strahl/image/image.h"
#include "strahl/math/transform.h"
#include "strahl/render/integrator_kind.h"
#include "strahl/render/ray_budget.h"
#include "strahl/sampling/pixel_sampler.h"
#include "strahl/scene/mesh_data.h"
#include "strahl/shading/light.h"
#include "strahl/shading/material.h"
#include "strahl/util/error.h"

namespace strahl {

struct RenderScene;

// Material with the given colour and the default finish.
inline Material material_with_color(const Vec3& color) {
  Material m;
  m.color = color;
  return m;
}

// How an object moves during the shutter interval (motion blur): not at all, with a linear
// velocity (units per unit of shutter time: at time τ it is displaced by velocity·τ), or between
// two keyframed transforms, `from` at shutter open and `to` at shutter close (in between on
// straight lines, or on arcs where the keys turn: scene/move_solid.h). Keyframes (any transform: scale/rotate/translate
// or a matrix) act in world space, after the object's own placement, for spheres, triangles,
// solids and instances; a mesh's act in its own coordinates, before its scale/rotate/translate
// (so a mesh turns about its own origin). A Spin may come with either, or alone. Planes cannot
// move.

// A spin: the object turns by `angle` degrees (any size, either sign: 1080 is three turns,
// right-handed about `axis`) from shutter open to close, uniformly, about the line along `axis`
// through `center` — both in the coordinates the motion acts in (world space; a mesh's own) —
// while the motion's velocity or keyframes carry the centre along; the axis keeps its direction.
struct Spin {
  Vec3 axis{0, 0, 1};
  Real angle = 0;
  Vec3 center{0};
};

// (One shared, immutable record behind each motion: most objects have none, and a scene file's
// many objects must stay small — docs/scene-format.md, "Memory bound".)
class Motion {
 public:
  enum class Kind { None, Velocity, Keyframes };
  Kind kind = Kind::None;

  static Motion linear(const Vec3& v) { return Motion(Kind::Velocity, {v, {}, {}, {}}); }
  static Motion keyframes(const Transform& a, const Transform& b) { return Motion(Kind::Keyframes, {Vec3(0), a, b, {}}); }
  static Motion spinning(const Spin& s) { return Motion(Kind::None, {Vec3(0), {}, {}, s}); }
  // This motion with a spin (none while its angle is 0); with keyframes, theirs may not turn as well.
  Motion with_spin(const Spin& s) const { return Motion(kind, {velocity(), from(), to(), s}); }

  const Vec3& velocity() const { return data().velocity; }
  const Transform& from() const { return data().from; }
  const Transform& to() const { return data().to; }
  const Spin& spin() const { return data().spin; }
  bool spins() const { return spin().angle != 0; }
  bool moving() const { return kind != Kind::None || spins(); }

  Motion() = default;

 private:
  struct Data {
    Vec3 velocity{0};
    Transform from, to;
    Spin spin;
  };
  Motion(Kind k, Data d) : kind(k), data_(std::make_shared<const Data>(std::move(d))) {}
  const Data& data() const {
    static const Data none;
    return data_ ? *data_ : none;
  }
  std::shared_ptr<const Data> data_;
};

class SceneObject {
 public:
  explicit SceneObject(const Material& m) : material(m) {}
  virtual ~SceneObject() = default;

  // Appends the kernel shapes and checks the values (throws strahl::Error naming `loc`).
  virtual void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const = 0;

  Material material;
  FileLoc loc;  // where a scene file defined it, if it did
  Motion motion;
  // Where the object's own coordinates are placed (scale, then rotate about x, y, z, then
  // translate, or a general affine map). Meshes have their own `transform`; a plane or a
  // triangle takes its placement into its coordinates when compiled (scene/place_solid.h).
  Transform placement;
  bool placed() const { return !placement.identity(); }
};

class Sphere : public SceneObject {
 public:
  Sphere(const Vec3& center_, Real radius_, const Vec3& color) : Sphere(center_, radius_, material_with_color(color)) {}
  Sphere(const Vec3& center_, Real radius_, const Material& m) : SceneObject(m), center(center_), radius(radius_) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 center;
  Real radius;
};

// The plane N·p = d (N need not be unit length; it is normalised, and d scaled with it).
class Plane : public SceneObject {
 public:
  Plane(const Vec3& normal_, Real d, const Vec3& color) : Plane(normal_, d, material_with_color(color)) {}
  Plane(const Vec3& normal_, Real d, const Material& m) : SceneObject(m), normal(normal_), distance(d) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 normal;
  Real distance;
};

// One triangle; its front face is the one from which v0 → v1 → v2 runs counter-clockwise.
class Triangle : public SceneObject {
 public:
  Triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& color) : Triangle(a, b, c, material_with_color(color)) {}
  Triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Material& m) : SceneObject(m), v0(a), v1(b), v2(c) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  Vec3 v0, v1, v2;
};

// A triangle mesh, placed by a transform. Degenerate (zero-area) faces are dropped at compile time.
class Mesh : public SceneObject {
 public:
  Mesh(MeshData data_, const Material& m, const Transform& t = {}) : SceneObject(m), data(std::move(data_)), transform(t) {}
  void compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const override;

  MeshData data;
  Transform transform;
  // The materials its faces take from the file (data.face_materials index them; −1 and a mesh
  // without them: `material`), made by use_file_materials() (scene/file_materials.h), and the
  // file they came from (absolute: the scene writer names it instead of writing the mesh).
  std::vector<Material> file_materials;
  std::filesystem::path file_materials_source;
};

// Area lights (shading/area_light.h). `radiance` is the emitted radiance L (colour × intensity);
// set_power() derives it from a total power Φ instead. n×n stratified samples per shading point.
// Rect: a corner and two perpendicular edges; it emits towards edge_u × edge_v.
inline Light rect_light(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, const Vec3& radiance = Vec3(1),
                        int samples = 4) {
  Light l;
  l.kind = LightKind::Rect;
  l.position = corner;
  l.edge_u = edge_u;
  l.edge_v = edge_v;
  l.normal = cross(edge_u, edge_v);
  l.radiance = radiance;
  l.samples = samples;
  return l;
}
// Disk: centre, normal of the emitting side and radius.
inline Light disk_light(const Vec3& center, const Vec3& normal, Real radius, const Vec3& radiance = Vec3(1),
                        int samples = 4) {
  Light l;
  l.kind = LightKind::Disk;
  l.position = center;
  l.normal = normal;
  l.radius = radius;
  l.radiance = radiance;
  l.samples = samples;
  return l;
}
// Sphere: emits from its whole surface, outwards.
inline Light sphere_light(const Vec3& center, Real radius, const Vec3& radiance = Vec3(1), int samples = 4) {
  Light l;
  l.kind = LightKind::Sphere;
  l.position = center;
  l.radius = radius;
  l.radiance = radiance;
  l.samples = samples;
  return l;
}

inline Light point_light(const Vec3& position, const Vec3& color = Vec3(1), Real intensity = 1) {
  Light l;
  l.kind = LightKind::Point;
  l.position = position;
  l.radiance = color * intensity;
  return l;
}

// A spotlight (POV-Ray's): a point light at `position` that shines into a cone about
// `direction` (the axis, from the light into the scene): full light within `angle` degrees of
// the axis, none beyond `falloff` degrees, a smooth step between, all times cos^tightness
// (shading/light.h, spot_factor). compile() normalises the axis and takes the cosines.
inline Light spot_light(const Vec3& position, const Vec3& direction, Real angle = 30, Real falloff = 45,
                        Real tightness = 0, const Vec3& color = Vec3(1), Real intensity = 1) {
  Light l;
  l.kind = LightKind::Spot;
  l.position = position;
  l.direction = direction;
  l.angle = angle;
  l.falloff = falloff;
  l.tightness = tightness;
  l.radiance = color * intensity;
  return l;
}

// `direction` is the way the light travels (from the light into the scene).
inline Light directional_light(const Vec3& direction, const Vec3& color = Vec3(1), Real intensity = 1) {
  Light l;
  l.kind = LightKind::Directional;
  l.direction = direction;
  l.radiance = color * intensity;
  return l;
}

// The lecture's camera: eye, look-at point and up vector give {u, v, w}; the image plane is
// either a field of view (with the aspect ratio from the resolution) or explicit l, r, b, t, d.
struct CameraDescription {
  enum class FovAxis { Horizontal, Vertical };
  Vec3 position{0, 0.8, 2.2};
  Vec3 look_at{0, 0.25, 0};
  Vec3 up{0, 1, 0};
  Real fov_degrees = 50;
  FovAxis fov_axis = FovAxis::Horizontal;
  bool explicit_image_plane = false;
  Real l = -1, r = 1, b = -1, t = 1, d = 1;
  // Thin lens (depth of field): lens radius; 0 is the pinhole camera. The plane in focus lies
  // at focus_distance along the view axis, or through focus_point; by default through look_at.
  Real aperture = 0;
  Real focus_distance = 0;  // 0: not given
  bool has_focus_point = false;
  Vec3 focus_point{0};
  // Shutter interval (motion blur): each camera ray gets a time in [open, close].
  Real shutter_open = 0, shutter_close = 1;
  FileLoc loc;
};

struct RenderSettings {
  int width = 1280;
  int height = 720;
  int max_depth = 8;
  Real min_weight = 1e-3;
  int ray_budget = int(kDefaultRayBudget);  // reflected and refracted rays per camera sample
  int supersample = 1;
  Vec3 background{0};
  Vec3 ambient_light{1};
  Real medium_ior = 1;
  IntegratorKind integrator = IntegratorKind::Whitted;
  AccelKind accel = AccelKind::Bvh;
  // Pixel sampler, spp, seed, filter, adaptive settings; spp 0: supersample² on the grid.
  SamplingSettings sampling = [] {
    SamplingSettings s;
    s.spp = 0;
    return s;
  }();
  FileLoc loc;
};

// An image texture (shading/image_texture.h): a picture wrapped onto the surfaces whose material
// names it (Material::texture = the index Scene::add_texture returned), as POV-Ray's image_map.
struct ImageTexture {
  std::filesystem::path file;  // where the picture was read from (for messages; may be empty)
  std::shared_ptr<const Image> image;  // its pixels, linear RGB (read_texture_image)
  ImageMapping mapping = ImageMapping::Planar;
  bool bilinear = true;   // blend the four nearest pixels (else the pixel a point falls into)
  bool once = false;      // not repeated: outside the image the material's colour shows
  // Texture space → world space (a group's own space for shapes in instanced groups): the planar
  // image's unit square, the spherical one's centre are placed by it.
  Transform placement;
  FileLoc loc;
};

// Reads a texture's picture (.png, .jpg, .ppm, .pfm, .exr): linear RGB; 8- and 16-bit formats are
// decoded from sRGB (as POV-Ray and image editors take them) unless `linear`. Throws strahl::Error.
std::shared_ptr<const Image> read_texture_image(const std::filesystem::path& file, bool linear = false);
// The same from a PNG's or JPEG's bytes in memory (image_io.h decode_image), always sRGB-decoded
// (a glTF file's embedded pictures). Throws strahl::Error naming `name`.
std::shared_ptr<Image> decode_texture_image(std::string_view bytes, const std::string& name);

// A named group of objects, placed by instances (scene/instances.h; docs/scene-format.md,
// "Instances").
struct ObjectGroup {
  std::string name;
  FileLoc loc;
  std::vector<std::unique_ptr<SceneObject>> objects;
};

class Scene {
 public:
  Scene() = default;
  Scene(Scene&&) = default;
  Scene& operator=(Scene&&) = default;

  // The lecture's API. The scene takes ownership of `object`.
  void addSceneObject(SceneObject* object) { objects_.emplace_back(object); }
  // A white point light of intensity 1.
  void addLightSource(const Vec3& position) { add(point_light(position)); }
  int getNumLightSources() const { return static_cast<int>(lights_.size()); }
  Vec3 getLightSource(int i) const { return lights_.at(static_cast<std::size_t>(i)).position; }

  // Value-type API.
  template <std::derived_from<SceneObject> T>
  T& add(T object) {
    auto owned = std::make_unique<T>(std::move(object));
    T& ref = *owned;
    objects_.push_back(std::move(owned));
    return ref;
  }
  void add(const Light& light, const FileLoc& loc = {}) {
    lights_.push_back(light);
    light_locs_.push_back(loc);
  }

  const std::vector<std::unique_ptr<SceneObject>>& objects() const { return objects_; }
  // Takes the last object added back out (the YAML loader reads a CSG's operands so).
  std::unique_ptr<SceneObject> take_last() {
    std::unique_ptr<SceneObject> o = std::move(objects_.back());
    objects_.pop_back();
    return o;
  }
  const std::vector<Light>& lights() const { return lights_; }
  const std::vector<FileLoc>& light_locs() const { return light_locs_; }
  // Adds an image texture (its image must hold pixels); returns the index a Material's `texture`
  // takes.
  std::uint32_t add_texture(ImageTexture texture) {
    if (texture.image == nullptr || texture.image->width() <= 0 || texture.image->height() <= 0)
      throw Error(texture.loc, "an image texture needs an image with pixels");
    textures_.push_back(std::move(texture));
    return static_cast<std::uint32_t>(textures_.size() - 1);
  }
  const std::vector<ImageTexture>& textures() const { return textures_; }
  std::vector<FileLoc>& light_locs() { return light_locs_; }  // (one per light; its text may change)

  CameraDescription camera;
  RenderSettings settings;
  // Groups of objects that `Instance` objects place (scene/instances.h).
  std::vector<ObjectGroup> groups;
  // What the loader noticed but accepted, one line each ("file:line:column: what"); compile()
  // passes them on in RenderScene::warnings with its own.
  std::vector<std::string> warnings;

 private:
  std::vector<std::unique_ptr<SceneObject>> objects_;
  std::vector<Light> lights_;
  std::vector<FileLoc> light_locs_;
  std::vector<ImageTexture> textures_;
};

// Validates everything (throws strahl::Error with the location of the offending definition)
// and builds the render-ready scene.
RenderScene compile(const Scene& scene);

// The lecture's scene (five spheres, a plane, one light) with the benchmark's camera and finish.
Scene lecture_scene();

}  // namespace strahl
