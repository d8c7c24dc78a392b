// A YAML scene's objects (yaml_reader.h): spheres, planes, triangles, meshes, the solids, quadrics,
// implicit surfaces, CSG nodes, groups and their instances.

#include "strahl/scene/yaml_reader.h"

#include <cstdint>
#include <string>
#include <utility>

#include "strahl/scene/file_materials.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/place_solid.h"
#include "strahl/scene/solids.h"
#include "strahl/scene/validate.h"

namespace strahl {

// `groups: {name: [objects…], …}` (docs/scene-format.md, "Instances"), read before the objects
// that place them. An object of a group is read as at the top level.
void YamlReader::groups(const YAML::Node& n, Scene& scene) {
  map(n, "groups");
  for (const auto& kv : n) {
    const std::string name = scalar(kv.first, "group name");
    if (group_index_.count(name)) fail(kv.first, "group '" + name + "' is defined twice");
    if (!kv.second.IsSequence()) fail(kv.second, "group '" + name + "' must be a list of objects");
    ObjectGroup g;
    g.name = name;
    g.loc = loc(kv.first);
    reading_group_ = &name;
    for (const YAML::Node& o : kv.second) {
      Scene objects;
      object(o, objects);
      g.objects.push_back(objects.take_last());
    }
    reading_group_ = nullptr;
    if (g.objects.empty()) fail(kv.second, "group '" + name + "' has no objects");
    group_index_[name] = static_cast<std::uint32_t>(scene.groups.size());
    scene.groups.push_back(std::move(g));
  }
}

// `type: instance, of: name` with its own transform.
SceneObject* YamlReader::instance(const YAML::Node& n, Scene& scene) const {
  keys(n, {"type", "of", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "instance");
  const YAML::Node of = required(n, "of", "instance");
  const std::string name = scalar(of, "instance of");
  // A group places the groups defined above it (nested instances), never itself.
  if (reading_group_ && name == *reading_group_) fail(of, "group '" + name + "' places an instance of itself (a cycle)");
  const auto it = group_index_.find(name);
  if (it == group_index_.end()) {
    std::string known;
    for (const auto& [k, v] : group_index_) known += (known.empty() ? "" : ", ") + k;
    if (reading_group_)
      fail(of, "unknown group '" + name + "': group '" + *reading_group_ + "' can place the groups defined above it" +
                   (known.empty() ? std::string(" (none is)") : " (" + known + ")"));
    fail(of, "unknown group '" + name + "'" + (known.empty() ? std::string(" (the scene defines no groups)") : " (groups: " + known + ")"));
  }
  return &scene.add(Instance(it->second));
}

void YamlReader::object(const YAML::Node& n, Scene& scene) const {
  map(n, "object");
  const std::string type = scalar(required(n, "type", "object"), "object type");
  SceneObject* added = nullptr;
  if (type == "instance") {
    added = instance(n, scene);
  } else if (type == "sphere") {
    keys(n, {"type", "center", "radius", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "sphere");
    const Vec3 center = vec3(required(n, "center", "sphere"), "sphere center");
    const Real radius = positive(required(n, "radius", "sphere"), "sphere radius");
    added = &scene.add(Sphere(center, radius, object_material(n)));
  } else if (type == "plane") {
    keys(n, {"type", "normal", "distance", "material", "scale", "rotate", "translate", "matrix", "transform"}, "plane");
    const YAML::Node nn = required(n, "normal", "plane");
    Vec3 normal = vec3(nn, "plane normal");
    validate::non_zero(normal, loc(nn), "plane normal");
    Real distance = n["distance"] ? number(n["distance"], "plane distance") : Real(0);
    if (const Transform t = placement(n); !t.identity()) place_plane(t, normal, distance, loc(n));
    added = &scene.add(Plane(normal, distance, object_material(n)));
  } else if (type == "triangle") {
    keys(n, {"type", "vertices", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "triangle");
    const YAML::Node v = required(n, "vertices", "triangle");
    if (!v.IsSequence() || v.size() != 3) fail(v, "triangle vertices must be a list of three points");
    Vec3 a = vec3(v[0], "vertex"), b = vec3(v[1], "vertex"), c = vec3(v[2], "vertex");
    if (const Transform t = placement(n); !t.identity()) place_triangle(t, a, b, c, loc(n));
    if (!(length_squared(cross(b - a, c - a)) > 0)) fail(v, "degenerate triangle (its vertices are collinear)");
    added = &scene.add(Triangle(a, b, c, object_material(n)));
  } else if (type == "mesh") {
    keys(n, {"type", "file", "material", "file_materials", "scale", "rotate", "translate", "matrix", "transform", "motion"},
         "mesh");
    const YAML::Node f = required(n, "file", "mesh");
    const std::string file = scalar(f, "mesh file");
    const Transform t = placement(n, "mesh ");
    const Material m = object_material(n);
    const YAML::Node fm = n["file_materials"];
    const bool by_file = fm && boolean(fm, "mesh file_materials");
    if (by_file && !gives_materials(file)) fail(fm, "file_materials: only glTF (.gltf, .glb) and OBJ files give materials");
    MeshData data;
    try {
      data = meshes_ ? meshes_(file) : load_mesh(base_dir_ / file, by_file);
    } catch (const Error& e) {
      fail(f, std::string("mesh: ") + e.what());
    }
    Mesh& mesh = scene.add(Mesh(std::move(data), m, t));
    mesh.loc = loc(n);
    if (by_file && !meshes_) mesh.file_materials_source = std::filesystem::absolute(base_dir_ / file);
    use_file_materials(mesh, [&](ImageTexture texture) {
      textures_.push_back(std::move(texture));
      return std::uint32_t(textures_.size() - 1);
    });
    added = &mesh;
  } else if (SceneObject* solid = this->solid(type, n, scene)) {
    added = solid;
  } else if (is_csg_type(type)) {
    added = &scene.add(csg(n, type));
  } else {
    fail(n["type"], "unknown object type '" + type +
                        "' (sphere, plane, triangle, mesh, box, cylinder, cone, disk, torus, quadric, implicit, "
                        "union, intersection, difference, merge, inverse or instance)");
  }
  added->loc = loc(n);
  if (type != "mesh" && type != "plane" && type != "triangle") added->placement = placement(n);
  if (const auto m = n["motion"]) added->motion = motion(m);
}

// [[x, y, z], [x, y, z]]: two opposite corners.
void YamlReader::corners(const YAML::Node& n, const std::string& what, Vec3& a, Vec3& b) const {
  if (!n.IsSequence() || n.size() != 2) fail(n, what + " must be a list of two corners [[x, y, z], [x, y, z]]");
  a = vec3(n[0], what + " corner");
  b = vec3(n[1], what + " corner");
  const Vec3 lo = min(a, b), hi = max(a, b);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) fail(n, what + " is flat: its corners must differ in x, y and z");
}

// {type: box, corners: [...]} (and, where allowed, {type: sphere, center, radius}).
void YamlReader::bound(const YAML::Node& n, const std::string& what, bool sphere_allowed, ImplicitSurface* s, ClipBox* clip) const {
  map(n, what);
  const std::string type = scalar(required(n, "type", what), what + " type");
  if (type == "box") {
    keys(n, {"type", "corners"}, what);
    Vec3 a, b;
    corners(required(n, "corners", what), what + " box", a, b);
    if (s) { s->bound = kernel::ImplicitBound::Box; s->box_a = a; s->box_b = b; }
    if (clip) *clip = {a, b};
  } else if (type == "sphere" && sphere_allowed) {
    keys(n, {"type", "center", "radius"}, what);
    s->bound = kernel::ImplicitBound::Sphere;
    s->center = vec3(required(n, "center", what), what + " center");
    s->radius = positive(required(n, "radius", what), what + " radius");
  } else {
    fail(n["type"], "unknown " + what + " type '" + type + (sphere_allowed ? "' (box or sphere)" : "' (box)"));
  }
}

// The solids (scene/solids.h); nullptr for another type.
SceneObject* YamlReader::solid(const std::string& type, const YAML::Node& n, Scene& scene) const {
  if (type == "box") {
    keys(n, {"type", "corners", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "box");
    Vec3 a, b;
    corners(required(n, "corners", "box"), "box", a, b);
    return &scene.add(Box(a, b, object_material(n)));
  }
  if (type == "cylinder") {
    keys(n, {"type", "base", "cap", "radius", "open", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "cylinder");
    const Vec3 base = vec3(required(n, "base", "cylinder"), "cylinder base");
    const Vec3 cap = vec3(required(n, "cap", "cylinder"), "cylinder cap");
    if (base == cap) fail(n["cap"], "degenerate cylinder: its base and cap are the same point");
    const Real radius = positive(required(n, "radius", "cylinder"), "cylinder radius");
    const bool open = n["open"] ? boolean(n["open"], "open") : false;
    return &scene.add(Cone::cylinder(base, cap, radius, object_material(n), open));
  }
  if (type == "cone") {
    keys(n, {"type", "base", "base_radius", "cap", "cap_radius", "open", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "cone");
    const Vec3 base = vec3(required(n, "base", "cone"), "cone base");
    const Vec3 cap = vec3(required(n, "cap", "cone"), "cone cap");
    if (base == cap) fail(n["cap"], "degenerate cone: its base and cap are the same point");
    const Real r0 = non_negative(required(n, "base_radius", "cone"), "cone base_radius");
    const Real r1 = non_negative(required(n, "cap_radius", "cone"), "cone cap_radius");
    if (!(r0 > 0 || r1 > 0)) fail(n["cap_radius"], "cone radii are both 0 (one must be positive)");
    const bool open = n["open"] ? boolean(n["open"], "open") : false;
    return &scene.add(Cone(base, r0, cap, r1, object_material(n), open));
  }
  if (type == "disk") {
    keys(n, {"type", "center", "normal", "radius", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "disk");
    const Vec3 center = vec3(required(n, "center", "disk"), "disk center");
    const YAML::Node nn = required(n, "normal", "disk");
    const Vec3 normal = vec3(nn, "disk normal");
    validate::non_zero(normal, loc(nn), "disk normal");
    const Real radius = positive(required(n, "radius", "disk"), "disk radius");
    return &scene.add(Disk(center, normal, radius, object_material(n)));
  }
  if (type == "torus") {
    keys(n, {"type", "center", "axis", "major_radius", "minor_radius", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "torus");
    const Vec3 center = n["center"] ? vec3(n["center"], "torus center") : Vec3(0);
    Vec3 axis(0, 1, 0);
    if (const auto v = n["axis"]) {
      axis = vec3(v, "torus axis");
      validate::non_zero(axis, loc(v), "torus axis");
    }
    const Real major = positive(required(n, "major_radius", "torus"), "torus major_radius");
    const YAML::Node mn = required(n, "minor_radius", "torus");
    const Real minor = positive(mn, "torus minor_radius");
    if (!(minor < major)) fail(mn, "torus minor_radius must be smaller than its major_radius");
    return &scene.add(Torus(center, major, minor, object_material(n), axis));
  }
  if (type == "quadric") {
    keys(n, {"type", "coefficients", "clipped_by", "material", "motion", "scale", "rotate", "translate", "matrix", "transform"}, "quadric");
    const YAML::Node c = required(n, "coefficients", "quadric");
    if (!c.IsSequence() || c.size() != 10)
      fail(c, "quadric coefficients must be a list of ten numbers [A, B, C, D, E, F, G, H, I, J]");
    std::array<Real, 10> k{};
    bool surface = false;
    for (std::size_t i = 0; i < 10; ++i) {
      k[i] = number(c[i], "quadric coefficient");
      surface = surface || (i < 9 && k[i] != 0);
    }
    if (!surface) fail(c, "quadric describes no surface: its coefficients A to I are all 0");
    std::optional<ClipBox> clip;
    if (const auto v = n["clipped_by"]) {
      ClipBox b;
      bound(v, "clipped_by", false, nullptr, &b);
      clip = b;
    }
    return &scene.add(Quadric(k, object_material(n), clip));
  }
  if (type == "implicit") return implicit(n, scene);
  return nullptr;
}

SceneObject* YamlReader::implicit(const YAML::Node& n, Scene& scene) const {
  keys(n, {"type", "expression", "parameters", "contained_by", "max_gradient", "accuracy", "method", "step",
           "material", "motion", "scale", "rotate", "translate", "matrix", "transform"},
       "implicit");
  const YAML::Node e = required(n, "expression", "implicit");
  ImplicitSurface s(scalar(e, "implicit expression"), object_material(n));
  if (const auto p = n["parameters"]) {
    map(p, "parameters");
    for (const auto& kv : p) {
      const std::string name = scalar(kv.first, "parameter name");
      if (!valid_parameter_name(name))
        fail(kv.first, "'" + name + "' cannot be a parameter (a name of letters, digits and _, not x, y, z, pi "
                       "or a function)");
      s.parameters[name] = number(kv.second, "parameter " + name);
    }
  }
  // The expression is compiled here too, so that an error points at its column in the file:
  // the text starts one column later when it is quoted.
  try {
    const kernel::Expression f = compile_expression(s.expression, s.parameters);
    if (!uses_coordinates(f)) fail(e, "implicit expression does not use x, y or z: it describes no surface");
  } catch (const ExpressionError& err) {
    FileLoc at = loc(e);
    if (at.column > 0 && e.Tag() != "!") at.column += err.column() - 1;  // a plain scalar, on its own line
    else if (at.column > 0) at.column += err.column();
    throw Error(at, "implicit expression: " + err.message());
  }
  bound(required(n, "contained_by", "implicit"), "contained_by", true, &s, nullptr);
  if (const auto v = n["max_gradient"]) s.max_gradient = positive(v, "max_gradient");
  if (const auto v = n["accuracy"]) s.accuracy = positive(v, "accuracy");
  if (const auto v = n["method"]) {
    const std::string m = scalar(v, "method");
    if (m == "lipschitz") s.method = kernel::RootMethod::Lipschitz;
    else if (m == "distance") s.method = kernel::RootMethod::SphereTrace;
    else if (m == "march") s.method = kernel::RootMethod::March;
    else fail(v, "unknown method '" + m + "' (lipschitz, distance or march)");
  }
  if (const auto v = n["step"]) {
    if (s.method != kernel::RootMethod::March) fail(v, "step is for method: march");
    s.step = positive(v, "step");
  }
  return &scene.add(std::move(s));
}

}  // namespace strahl
