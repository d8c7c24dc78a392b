// The scene API in Python (docs/python.md): Material, the shapes, Mesh (from files or numpy
// arrays), the lights, Camera, RenderSettings and Scene. Values are checked when an object is
// made (the same messages as scene files); compile() checks everything again when rendering.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "bindings.h"
#include "convert.h"
#include "shape_args.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "strahl/scene/validate.h"
#include "strahl/shading/area_light.h"

namespace strahl::python {

Vec3 color_arg(const py::handle& value, const char* what) {
  if (PyNumber_Check(value.ptr()) && !PySequence_Check(value.ptr())) return Vec3(value.cast<double>());
  try {
    return value.cast<Vec3>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(what) + " must be three numbers (r, g, b) or one number for grey");
  }
}

Material object_material(const py::object& color, const std::optional<Material>& material) {
  if (!color.is_none() && material) throw py::type_error("give either color or material, not both");
  Material m = material ? *material : Material{};
  if (!color.is_none()) m.color = color_arg(color, "color");
  validate::material(m, {});
  return m;
}

Transform make_transform(const py::object& scale, const Vec3& rotate, const Vec3& translate, const char* what) {
  Transform t;
  t.scale = color_arg(scale, "scale");  // one number scales uniformly
  t.rotate_degrees = rotate;
  t.translate = translate;
  validate::finite(t.scale, {}, std::string(what) + " scale");
  validate::finite(t.rotate_degrees, {}, std::string(what) + " rotate");
  validate::finite(t.translate, {}, std::string(what) + " translate");
  if (t.scale.x == 0 || t.scale.y == 0 || t.scale.z == 0) throw Error(std::string(what) + " scale must not be zero");
  return t;
}

namespace {

std::string repr(const Vec3& v) {
  std::ostringstream out;
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

Real ior_arg(const py::handle& value) {
  if (PyUnicode_Check(value.ptr())) {
    const std::string name = value.cast<std::string>();
    Real ior = 0;
    if (!named_ior(name, ior))
      throw Error("unknown ior '" + name + "' (a number or one of vacuum, air, water, ice, acrylic, glass, diamond)");
    return ior;
  }
  return value.cast<double>();
}

template <class T>
T& placed(T& object, const std::optional<Motion>& motion) {
  object.loc = caller_loc();
  if (motion) object.motion = *motion;
  return object;
}


// numpy (or anything numpy takes) → N × 3 doubles.
py::array_t<double, py::array::c_style> rows3(const py::handle& values, const char* what) {
  const py::array a = py::module_::import("numpy").attr("asarray")(values);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error(std::string(what) + " must be numbers (got dtype " + py::str(a.dtype()).cast<std::string>() + ")");
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (d.ndim() != 2 || d.shape(1) != 3) throw py::value_error(std::string(what) + " must have the shape (n, 3)");
  return d;
}

MeshData mesh_from_arrays(const py::handle& vertices, const py::handle& indices, const py::handle& normals) {
  MeshData data;
  const auto v = rows3(vertices, "mesh vertices");
  const auto vv = v.unchecked<2>();
  data.positions.reserve(std::size_t(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    const Vec3 p(vv(i, 0), vv(i, 1), vv(i, 2));
    validate::finite(p, {}, "mesh vertex " + std::to_string(i));
    data.positions.push_back(p);
  }
  const py::array ia = py::module_::import("numpy").attr("asarray")(indices);
  const char kind = ia.dtype().kind();
  if (ia.size() > 0 && kind != 'i' && kind != 'u')
    throw py::type_error("mesh indices must be integers (got dtype " + py::str(ia.dtype()).cast<std::string>() + ")");
  const auto idx = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(ia);
  if (idx.ndim() != 2 || idx.shape(1) != 3) throw py::value_error("mesh indices must have the shape (m, 3)");
  const auto ii = idx.unchecked<2>();
  const auto n = static_cast<long long>(data.positions.size());
  const bool with_normals = !normals.is_none();
  data.faces.reserve(std::size_t(idx.shape(0)));
  for (py::ssize_t f = 0; f < idx.shape(0); ++f) {
    MeshData::Face face;
    for (int k = 0; k < 3; ++k) {
      const long long i = ii(f, k);
      if (i < 0 || i >= n)
        throw Error("mesh face " + std::to_string(f) + " refers to vertex " + std::to_string(i) + ", which does not exist (" +
                    std::to_string(n) + " vertices)");
      face.v[std::size_t(k)] = std::uint32_t(i);
      if (with_normals) face.n[std::size_t(k)] = std::int32_t(i);
    }
    data.faces.push_back(face);
  }
  if (with_normals) {
    const auto nrm = rows3(normals, "mesh normals");
    if (nrm.shape(0) != v.shape(0)) throw py::value_error("mesh normals must have one row per vertex");
    const auto nn = nrm.unchecked<2>();
    for (py::ssize_t i = 0; i < nrm.shape(0); ++i) {
      const Vec3 p(nn(i, 0), nn(i, 1), nn(i, 2));
      validate::finite(p, {}, "mesh normal " + std::to_string(i));
      data.normals.push_back(p);
    }
  }
  if (data.faces.empty()) throw Error("mesh has no faces");
  return data;
}

py::array_t<double> vec3_rows(const LargeArray<Vec3>& values) {
  py::array_t<double> out({py::ssize_t(values.size()), py::ssize_t(3)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < values.size(); ++i) {
    o(py::ssize_t(i), 0) = values[i].x;
    o(py::ssize_t(i), 1) = values[i].y;
    o(py::ssize_t(i), 2) = values[i].z;
  }
  return out;
}

// Area lights: radiance = colour × intensity, or from the total power (Φ = π·L·area).
Light finish_light(Light l, const Vec3& color, const std::optional<double>& intensity, const std::optional<double>& power,
                   int samples) {
  validate::non_negative(color, {}, "light color");
  if (intensity && power) throw py::type_error("give either intensity or power, not both");
  validate::int_range(samples, 1, 64, {}, "light samples");
  l.samples = samples;
  if (power) {
    validate::non_negative(*power, {}, "power");
    l.radiance = color * radiance_from_power(l, *power);
  } else {
    const double i = intensity.value_or(1.0);
    validate::non_negative(i, {}, "intensity");
    l.radiance = color * i;
  }
  return l;
}

const char* light_kind_name(LightKind k) {
  switch (k) {
    case LightKind::Point: return "point";
    case LightKind::Directional: return "directional";
    case LightKind::Rect: return "rect";
    case LightKind::Disk: return "disk";
    case LightKind::Sphere: return "sphere";
  }
  return "?";
}

void add_object(Scene& scene, const SceneObject& object) {
  std::unique_ptr<SceneObject> copy = copy_object(object);
  if (!copy) throw py::type_error("Scene.add takes a shape (a Sphere, Plane, Triangle, Mesh, solid or CSG tree) or a light");
  scene.addSceneObject(copy.release());
}

void bind_material(py::module_& m) {
  const Material d;
  py::class_<Material>(m, "Material",
                       "The lecture's surface: colour, ambient, Lambert, Blinn-Phong, mirror and refraction "
                       "(docs/scene-format.md, materials). Every field is a keyword argument and an attribute.")
      .def(py::init([](const py::object& color, double ambient, double diffuse, const py::object& specular,
                       double shininess, double reflectivity, double transparency, const py::object& ior, bool fresnel,
                       bool filter, double roughness, double checker_size, const py::object& checker_color) {
             Material mat;
             mat.color = color_arg(color, "color");
             mat.ambient = ambient;
             mat.diffuse = diffuse;
             mat.specular = color_arg(specular, "specular");
             mat.shininess = shininess;
             mat.reflectivity = reflectivity;
             mat.transparency = transparency;
             mat.ior = ior_arg(ior);
             mat.fresnel = fresnel;
             mat.filter = filter;
             mat.roughness = roughness;
             mat.checker_size = checker_size;
             mat.checker_color = color_arg(checker_color, "checker_color");
             validate::material(mat, {});
             validate::in_range(mat.roughness, 0, 1, {}, "roughness");
             return mat;
           }),
           py::arg("color") = py::make_tuple(d.color.x, d.color.y, d.color.z), py::kw_only(),
           py::arg("ambient") = d.ambient, py::arg("diffuse") = d.diffuse,
           py::arg("specular") = py::make_tuple(d.specular.x, d.specular.y, d.specular.z),
           py::arg("shininess") = d.shininess, py::arg("reflectivity") = d.reflectivity,
           py::arg("transparency") = d.transparency, py::arg("ior") = d.ior, py::arg("fresnel") = d.fresnel,
           py::arg("filter") = d.filter, py::arg("roughness") = d.roughness, py::arg("checker_size") = d.checker_size,
           py::arg("checker_color") = py::make_tuple(d.checker_color.x, d.checker_color.y, d.checker_color.z))
      .def_readwrite("color", &Material::color)
      .def_readwrite("ambient", &Material::ambient)
      .def_readwrite("diffuse", &Material::diffuse)
      .def_readwrite("specular", &Material::specular)
      .def_readwrite("shininess", &Material::shininess)
      .def_readwrite("reflectivity", &Material::reflectivity)
      .def_readwrite("transparency", &Material::transparency)
      .def_property(
          "ior", [](const Material& mat) { return mat.ior; },
          [](Material& mat, const py::object& v) { mat.ior = ior_arg(v); })
      .def_readwrite("fresnel", &Material::fresnel)
      .def_readwrite("filter", &Material::filter)
      .def_readwrite("roughness", &Material::roughness)
      .def_readwrite("checker_size", &Material::checker_size)
      .def_readwrite("checker_color", &Material::checker_color)
      .def("__repr__", [](const Material& mat) {
        std::ostringstream out;
        out << "strahl.Material(color=" << repr(mat.color) << ", ambient=" << mat.ambient << ", diffuse=" << mat.diffuse
            << ", specular=" << repr(mat.specular) << ", shininess=" << mat.shininess
            << ", reflectivity=" << mat.reflectivity << ", transparency=" << mat.transparency << ", ior=" << mat.ior
            << ")";
        return out.str();
      });
}

void bind_motion(py::module_& m) {
  py::class_<Transform>(m, "Transform", "Scale, then rotate about x, y, z (degrees), then translate.")
      .def(py::init([](const py::object& scale, const Vec3& rotate, const Vec3& translate) {
             return make_transform(scale, rotate, translate, "transform");
           }),
           py::kw_only(), py::arg("scale") = 1.0, py::arg("rotate") = py::make_tuple(0, 0, 0),
           py::arg("translate") = py::make_tuple(0, 0, 0))
      .def_readwrite("scale", &Transform::scale)
      .def_readwrite("rotate", &Transform::rotate_degrees)
      .def_readwrite("translate", &Transform::translate);
  py::class_<Spin>(m, "Spin",
                   "A turn by `angle` degrees (any size: 1080 is three turns) over the shutter, about the line "
                   "along `axis` through `center`, carried by the rest of the motion.")
      .def(py::init([](const Vec3& axis, Real angle, const Vec3& center) {
             Spin s{axis, angle, center};
             validate_motion(Motion::spinning(s), {});
             if (s.axis == Vec3(0)) throw Error("motion spin axis must not be zero");
             return s;
           }),
           py::arg("axis"), py::arg("angle"), py::arg("center") = py::make_tuple(0, 0, 0))
      .def_readonly("axis", &Spin::axis)
      .def_readonly("angle", &Spin::angle)
      .def_readonly("center", &Spin::center)
      .def("__repr__", [](const Spin& s) {
        std::ostringstream out;
        out << "strahl.Spin(" << repr(s.axis) << ", " << s.angle << ", center=" << repr(s.center) << ")";
        return out.str();
      });
  py::class_<Motion>(m, "Motion",
                     "Motion blur: Motion.linear(velocity), Motion.keyframes(from_, to) or Motion.spinning(spin); "
                     "the first two take a spin= too.")
      .def_static("linear", [](const Vec3& v, const std::optional<Spin>& spin) {
        validate::finite(v, {}, "motion velocity");
        return Motion::linear(v).with_spin(spin.value_or(Spin{}));
      }, py::arg("velocity"), py::arg("spin") = py::none())
      .def_static("keyframes", [](const Transform& from, const Transform& to, const std::optional<Spin>& spin) {
        return Motion::keyframes(from, to).with_spin(spin.value_or(Spin{}));
      }, py::arg("from_"), py::arg("to"), py::arg("spin") = py::none())
      .def_static("spinning", &Motion::spinning, py::arg("spin"))
      .def_property_readonly("kind", [](const Motion& mo) {
        return mo.kind == Motion::Kind::None ? "none" : mo.kind == Motion::Kind::Velocity ? "velocity" : "keyframes";
      })
      .def_property_readonly("velocity", &Motion::velocity)
      .def_property_readonly("from_", &Motion::from)
      .def_property_readonly("to", &Motion::to)
      .def_property_readonly("spin", [](const Motion& mo) -> std::optional<Spin> {
        if (mo.spins()) return mo.spin();
        return std::nullopt;
      }, "The motion's Spin, or None");
}

void bind_shapes(py::module_& m) {
  py::class_<SceneObject>(m, "SceneObject", "A shape of a scene (Sphere, Plane, Triangle, Mesh, a solid or a CSG tree).")
      .def_readwrite("material", &SceneObject::material)
      .def_readwrite("motion", &SceneObject::motion)
      .def_readwrite("placement", &SceneObject::placement,
                     "Where the shape's own coordinates are placed (scale, rotate, translate)")
      .def_property_readonly("location", [](const SceneObject& o) { return o.loc.str(); },
                             "Where it was defined: file:line of a scene file or of the Python code");

  py::class_<Sphere, SceneObject>(m, "Sphere", "A sphere; scaled unevenly (scale=(a, b, c)), an ellipsoid.")
      .def(py::init([](const Vec3& center, double radius, const py::object& color, const std::optional<Material>& material,
                       const std::optional<Motion>& motion, const py::object& scale, const Vec3& rotate,
                       const Vec3& translate) {
             validate::finite(center, {}, "sphere center");
             validate::positive(radius, {}, "sphere radius");
             Sphere s(center, radius, object_material(color, material));
             s.placement = make_transform(scale, rotate, translate, "sphere");
             return placed(s, motion);
           }),
           py::arg("center"), py::arg("radius"), py::arg("color") = py::none(), py::kw_only(),
           py::arg("material") = py::none(), py::arg("motion") = py::none(), py::arg("scale") = 1.0,
           py::arg("rotate") = py::make_tuple(0, 0, 0), py::arg("translate") = py::make_tuple(0, 0, 0))
      .def_readwrite("center", &Sphere::center)
      .def_readwrite("radius", &Sphere::radius)
      .def("__repr__", [](const Sphere& s) {
        std::ostringstream out;
        out << "strahl.Sphere(" << repr(s.center) << ", " << s.radius << ", color=" << repr(s.material.color) << ")";
        return out.str();
      });

  py::class_<Plane, SceneObject>(m, "Plane", "The plane N·p = d.")
      .def(py::init([](const Vec3& normal, double distance, const py::object& color, const std::optional<Material>& material) {
             validate::non_zero(normal, {}, "plane normal");
             validate::finite(distance, {}, "plane distance");
             Plane p(normal, distance, object_material(color, material));
             return placed(p, std::nullopt);
           }),
           py::arg("normal"), py::arg("distance") = 0.0, py::arg("color") = py::none(), py::kw_only(),
           py::arg("material") = py::none())
      .def_readwrite("normal", &Plane::normal)
      .def_readwrite("distance", &Plane::distance);

  py::class_<Triangle, SceneObject>(m, "Triangle", "One triangle; its front face sees v0 → v1 → v2 counter-clockwise.")
      .def(py::init([](const Vec3& a, const Vec3& b, const Vec3& c, const py::object& color,
                       const std::optional<Material>& material, const std::optional<Motion>& motion) {
             for (const Vec3* v : {&a, &b, &c}) validate::finite(*v, {}, "triangle vertex");
             if (!(length_squared(cross(b - a, c - a)) > 0)) throw Error("degenerate triangle (its vertices are collinear)");
             Triangle t(a, b, c, object_material(color, material));
             return placed(t, motion);
           }),
           py::arg("v0"), py::arg("v1"), py::arg("v2"), py::arg("color") = py::none(), py::kw_only(),
           py::arg("material") = py::none(), py::arg("motion") = py::none())
      .def_readwrite("v0", &Triangle::v0)
      .def_readwrite("v1", &Triangle::v1)
      .def_readwrite("v2", &Triangle::v2);

  py::class_<Mesh, SceneObject>(m, "Mesh",
                                "A triangle mesh: vertices (n × 3), indices (m × 3, into the vertices) and optional "
                                "per-vertex normals (n × 3), placed by scale, rotate (degrees about x, y, z) and "
                                "translate. Mesh.load(path) reads .obj or .ply.")
      .def(py::init([](const py::object& vertices, const py::object& indices, const py::object& normals,
                       const py::object& color, const std::optional<Material>& material, const py::object& scale,
                       const Vec3& rotate, const Vec3& translate, const std::optional<Motion>& motion) {
             Mesh mesh(mesh_from_arrays(vertices, indices, normals), object_material(color, material),
                       make_transform(scale, rotate, translate, "mesh"));
             return placed(mesh, motion);
           }),
           py::arg("vertices"), py::arg("indices"), py::arg("normals") = py::none(), py::arg("color") = py::none(),
           py::kw_only(), py::arg("material") = py::none(), py::arg("scale") = 1.0,
           py::arg("rotate") = py::make_tuple(0, 0, 0), py::arg("translate") = py::make_tuple(0, 0, 0),
           py::arg("motion") = py::none())
      .def_static(
          "load",
          [](const std::filesystem::path& path, const py::object& color, const std::optional<Material>& material,
             const py::object& scale, const Vec3& rotate, const Vec3& translate, const std::optional<Motion>& motion) {
            Material mat = object_material(color, material);
            Transform t = make_transform(scale, rotate, translate, "mesh");
            Mesh mesh(interruptible<MeshData>([&] { return load_mesh(path); }), mat, t);
            return placed(mesh, motion);
          },
          py::arg("path"), py::arg("color") = py::none(), py::kw_only(), py::arg("material") = py::none(),
          py::arg("scale") = 1.0, py::arg("rotate") = py::make_tuple(0, 0, 0),
          py::arg("translate") = py::make_tuple(0, 0, 0), py::arg("motion") = py::none(),
          "Reads a mesh file (.obj or .ply) with the scene files' reader and its errors.")
      .def_property_readonly("vertices", [](const Mesh& mesh) { return vec3_rows(mesh.data.positions); })
      .def_property_readonly("normals", [](const Mesh& mesh) { return vec3_rows(mesh.data.normals); })
      .def_property_readonly("indices", [](const Mesh& mesh) {
        py::array_t<std::int64_t> out({py::ssize_t(mesh.data.faces.size()), py::ssize_t(3)});
        auto o = out.mutable_unchecked<2>();
        for (std::size_t f = 0; f < mesh.data.faces.size(); ++f)
          for (int k = 0; k < 3; ++k) o(py::ssize_t(f), k) = mesh.data.faces[f].v[std::size_t(k)];
        return out;
      })
      .def_property_readonly("normal_indices", [](const Mesh& mesh) {
        py::array_t<std::int64_t> out({py::ssize_t(mesh.data.faces.size()), py::ssize_t(3)});
        auto o = out.mutable_unchecked<2>();
        for (std::size_t f = 0; f < mesh.data.faces.size(); ++f)
          for (int k = 0; k < 3; ++k) o(py::ssize_t(f), k) = mesh.data.faces[f].n[std::size_t(k)];
        return out;
      }, "Per face the normals' indices (−1 where the file gives none)")
      .def_property_readonly("transform", [](const Mesh& mesh) { return mesh.transform; });
}

void bind_instance(py::module_& m) {
  py::class_<Instance, SceneObject>(m, "Instance", "A placed group (Scene.add_instance; scene files' `instance`).")
      .def_readonly("group", &Instance::group, "The group's index in Scene.groups")
      .def("__repr__", [](const Instance& in) {
        return "<strahl.Instance of group " + std::to_string(in.group) + (in.motion.moving() ? ", moving>" : ">");
      });
}

void bind_lights(py::module_& m) {
  const auto white = py::make_tuple(1, 1, 1);
  py::class_<Light>(m, "Light", "A light source; made by PointLight, DirectionalLight, RectLight, DiskLight, SphereLight.")
      .def_property_readonly("kind", [](const Light& l) { return light_kind_name(l.kind); })
      .def_readonly("position", &Light::position)
      .def_readonly("direction", &Light::direction)
      .def_readonly("radiance", &Light::radiance)
      .def_readonly("edge_u", &Light::edge_u)
      .def_readonly("edge_v", &Light::edge_v)
      .def_readonly("normal", &Light::normal)
      .def_readonly("radius", &Light::radius)
      .def_readonly("samples", &Light::samples)
      .def("__repr__", [](const Light& l) {
        return std::string("strahl.Light(") + light_kind_name(l.kind) + ", position=" + repr(l.position) +
               ", radiance=" + repr(l.radiance) + ")";
      });
  m.def("PointLight", [](const Vec3& position, const py::object& color, double intensity) {
        validate::finite(position, {}, "light position");
        const Vec3 c = color_arg(color, "light color");
        validate::non_negative(c, {}, "light color");
        validate::non_negative(intensity, {}, "intensity");
        return point_light(position, c, intensity);
      }, py::arg("position"), py::arg("color") = white, py::arg("intensity") = 1.0,
      "A point light: radiance colour × intensity, falling off with the squared distance.");
  m.def("DirectionalLight", [](const Vec3& direction, const py::object& color, double intensity) {
        validate::non_zero(direction, {}, "light direction");
        const Vec3 c = color_arg(color, "light color");
        validate::non_negative(c, {}, "light color");
        validate::non_negative(intensity, {}, "intensity");
        return directional_light(direction, c, intensity);
      }, py::arg("direction"), py::arg("color") = white, py::arg("intensity") = 1.0,
      "A light from infinitely far away; `direction` is the way its light travels.");
  m.def("RectLight", [](const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, const py::object& color,
                        std::optional<double> intensity, std::optional<double> power, int samples) {
        validate::finite(corner, {}, "light corner");
        validate::non_zero(edge_u, {}, "edge_u");
        validate::non_zero(edge_v, {}, "edge_v");
        if (std::fabs(dot(normalize(edge_u), normalize(edge_v))) > 1e-6) throw Error("rect light edges must be perpendicular");
        Light l = rect_light(corner, edge_u, edge_v, Vec3(1), samples);
        l.normal = normalize(l.normal);  // (for radiance_from_power; compile() sets it again from the edges)
        return finish_light(l, color_arg(color, "light color"), intensity, power, samples);
      }, py::arg("corner"), py::arg("edge_u"), py::arg("edge_v"), py::arg("color") = white, py::kw_only(),
      py::arg("intensity") = py::none(), py::arg("power") = py::none(), py::arg("samples") = 4,
      "A rectangular area light; it emits towards edge_u × edge_v.");
  m.def("DiskLight", [](const Vec3& center, const Vec3& normal, double radius, const py::object& color,
                        std::optional<double> intensity, std::optional<double> power, int samples) {
        validate::finite(center, {}, "light center");
        validate::non_zero(normal, {}, "light normal");
        validate::positive(radius, {}, "light radius");
        const Light l = disk_light(center, normal, radius, Vec3(1), samples);  // compile() normalises the normal
        return finish_light(l, color_arg(color, "light color"), intensity, power, samples);
      }, py::arg("center"), py::arg("normal"), py::arg("radius"), py::arg("color") = white, py::kw_only(),
      py::arg("intensity") = py::none(), py::arg("power") = py::none(), py::arg("samples") = 4,
      "A disk-shaped area light emitting towards `normal`.");
  m.def("SphereLight", [](const Vec3& center, double radius, const py::object& color, std::optional<double> intensity,
                          std::optional<double> power, int samples) {
        validate::finite(center, {}, "light center");
        validate::positive(radius, {}, "light radius");
        const Light l = sphere_light(center, radius, Vec3(1), samples);
        return finish_light(l, color_arg(color, "light color"), intensity, power, samples);
      }, py::arg("center"), py::arg("radius"), py::arg("color") = white, py::kw_only(),
      py::arg("intensity") = py::none(), py::arg("power") = py::none(), py::arg("samples") = 4,
      "A spherical area light emitting from its whole surface.");
}

void bind_camera(py::module_& m) {
  using FovAxis = CameraDescription::FovAxis;
  const CameraDescription d;
  py::class_<CameraDescription>(m, "Camera",
                                "The lecture's camera: eye position, look-at point, up vector and a field of view "
                                "(or the image plane l, r, b, t at distance d); thin lens and shutter.")
      .def(py::init([](const Vec3& position, const Vec3& look_at, const Vec3& up, double fov, const std::string& fov_axis,
                       const std::optional<std::tuple<double, double, double, double, double>>& image_plane,
                       double aperture, double focus_distance, const std::optional<Vec3>& focus_point,
                       const std::tuple<double, double>& shutter) {
             CameraDescription c;
             c.position = position;
             c.look_at = look_at;
             c.up = up;
             if (!(fov > 0 && fov < 180)) throw Error("fov must lie in (0, 180) degrees");
             c.fov_degrees = fov;
             if (fov_axis == "horizontal") c.fov_axis = FovAxis::Horizontal;
             else if (fov_axis == "vertical") c.fov_axis = FovAxis::Vertical;
             else throw Error("fov_axis must be 'horizontal' or 'vertical'");
             if (image_plane) {
               c.explicit_image_plane = true;
               std::tie(c.l, c.r, c.b, c.t, c.d) = *image_plane;
             }
             c.aperture = aperture;
             c.focus_distance = focus_distance;
             if (focus_point) {
               if (focus_distance != 0) throw py::type_error("give either focus_distance or focus_point, not both");
               c.has_focus_point = true;
               c.focus_point = *focus_point;
             }
             std::tie(c.shutter_open, c.shutter_close) = shutter;
             c.loc = caller_loc();
             // The checks compile() makes, now, so that a bad camera fails where it is made.
             Scene probe;
             probe.camera = c;
             probe.settings.width = probe.settings.height = 1;
             probe.add(Sphere(Vec3(0), 1, Material{}));
             (void)compile(probe);
             return c;
           }),
           py::kw_only(), py::arg("position") = py::make_tuple(d.position.x, d.position.y, d.position.z),
           py::arg("look_at") = py::make_tuple(d.look_at.x, d.look_at.y, d.look_at.z),
           py::arg("up") = py::make_tuple(d.up.x, d.up.y, d.up.z), py::arg("fov") = d.fov_degrees,
           py::arg("fov_axis") = "horizontal", py::arg("image_plane") = py::none(), py::arg("aperture") = 0.0,
           py::arg("focus_distance") = 0.0, py::arg("focus_point") = py::none(),
           py::arg("shutter") = py::make_tuple(0.0, 1.0))
      .def_readwrite("position", &CameraDescription::position)
      .def_readwrite("look_at", &CameraDescription::look_at)
      .def_readwrite("up", &CameraDescription::up)
      .def_readwrite("fov", &CameraDescription::fov_degrees)
      .def_property(
          "fov_axis", [](const CameraDescription& c) { return c.fov_axis == FovAxis::Horizontal ? "horizontal" : "vertical"; },
          [](CameraDescription& c, const std::string& axis) {
            if (axis == "horizontal") c.fov_axis = FovAxis::Horizontal;
            else if (axis == "vertical") c.fov_axis = FovAxis::Vertical;
            else throw Error("fov_axis must be 'horizontal' or 'vertical'");
          })
      .def_property(
          "image_plane",
          [](const CameraDescription& c) -> py::object {
            if (!c.explicit_image_plane) return py::none();
            return py::make_tuple(c.l, c.r, c.b, c.t, c.d);
          },
          [](CameraDescription& c, const std::optional<std::tuple<double, double, double, double, double>>& p) {
            c.explicit_image_plane = bool(p);
            if (p) std::tie(c.l, c.r, c.b, c.t, c.d) = *p;
          },
          "(l, r, b, t, d), or None for the field of view")
      .def_readwrite("aperture", &CameraDescription::aperture)
      .def_readwrite("focus_distance", &CameraDescription::focus_distance)
      .def_property(
          "focus_point",
          [](const CameraDescription& c) -> std::optional<Vec3> {
            if (!c.has_focus_point) return std::nullopt;
            return c.focus_point;
          },
          [](CameraDescription& c, const std::optional<Vec3>& p) {
            c.has_focus_point = bool(p);
            if (p) c.focus_point = *p;
          })
      .def_property(
          "shutter", [](const CameraDescription& c) { return py::make_tuple(c.shutter_open, c.shutter_close); },
          [](CameraDescription& c, const std::tuple<double, double>& s) { std::tie(c.shutter_open, c.shutter_close) = s; });
}

// Enumerations as their scene-file names.
template <class Kind>
Kind kind_from(const std::string& name, std::optional<Kind> (*from_name)(std::string_view), const char* what,
               const std::string& names) {
  const std::optional<Kind> kind = from_name(name);
  if (!kind) throw Error(std::string("unknown ") + what + " '" + name + "' (" + names + ")");
  return *kind;
}

void bind_settings(py::module_& m) {
  py::class_<RenderSettings>(m, "RenderSettings",
                             "A scene's render settings (docs/scene-format.md, render); strahl.render's keyword "
                             "arguments override them for one render.")
      .def_readwrite("width", &RenderSettings::width)
      .def_readwrite("height", &RenderSettings::height)
      .def_readwrite("max_depth", &RenderSettings::max_depth)
      .def_readwrite("min_weight", &RenderSettings::min_weight)
      .def_readwrite("supersample", &RenderSettings::supersample)
      .def_readwrite("background", &RenderSettings::background)
      .def_readwrite("ambient_light", &RenderSettings::ambient_light)
      .def_readwrite("medium_ior", &RenderSettings::medium_ior)
      .def_property(
          "accel", [](const RenderSettings& s) { return std::string(accel_name(s.accel)); },
          [](RenderSettings& s, const std::string& n) { s.accel = kind_from(n, accel_from_name, "accel", accel_names()); })
      .def_property(
          "sampler", [](const RenderSettings& s) { return sampler_name(s.sampling.sampler); },
          [](RenderSettings& s, const std::string& n) {
            s.sampling.sampler = kind_from(n, sampler_from_name, "sampler", kSamplerNames);
          })
      .def_property(
          "spp", [](const RenderSettings& s) { return s.sampling.spp; },
          [](RenderSettings& s, int v) { s.sampling.spp = v; }, "samples per pixel; 0: supersample² on the grid")
      .def_property(
          "seed", [](const RenderSettings& s) { return s.sampling.seed; },
          [](RenderSettings& s, std::uint64_t v) { s.sampling.seed = v; })
      .def_property(
          "filter", [](const RenderSettings& s) { return filter_name(s.sampling.filter.kind); },
          [](RenderSettings& s, const std::string& n) {
            s.sampling.filter.kind = kind_from(n, filter_from_name, "filter", kFilterNames);
          })
      .def_property(
          "filter_radius", [](const RenderSettings& s) { return s.sampling.filter.radius; },
          [](RenderSettings& s, double v) { s.sampling.filter.radius = v; })
      .def_property(
          "adaptive_min", [](const RenderSettings& s) { return s.sampling.adaptive_min; },
          [](RenderSettings& s, int v) { s.sampling.adaptive_min = v; })
      .def_property(
          "adaptive_threshold", [](const RenderSettings& s) { return s.sampling.adaptive_threshold; },
          [](RenderSettings& s, double v) { s.sampling.adaptive_threshold = v; });
}

void bind_scene_class(py::module_& m) {
  py::class_<Scene>(m, "Scene",
                    "The editable scene: shapes, lights, camera and render settings. add() copies the object into "
                    "the scene; scene.objects gives the scene's own (changing them changes the scene).")
      .def(py::init<>())
      .def("add", [](Scene& s, const SceneObject& o) { add_object(s, o); }, py::arg("object"),
           "Adds a copy of a shape (Sphere, Plane, Triangle, Mesh).")
      .def("add", [](Scene& s, const Light& l) { s.add(l, caller_loc()); }, py::arg("light"), "Adds a light.")
      .def("addSceneObject", [](Scene& s, const SceneObject& o) { add_object(s, o); }, py::arg("object"),
           "The lecture's name for add().")
      .def("add_light", [](Scene& s, const Vec3& position, const py::object& color, double intensity) {
             validate::finite(position, {}, "light position");
             const Vec3 c = color_arg(color, "light color");
             validate::non_negative(c, {}, "light color");
             validate::non_negative(intensity, {}, "intensity");
             s.add(point_light(position, c, intensity), caller_loc());
           }, py::arg("position"), py::arg("color") = py::make_tuple(1, 1, 1), py::arg("intensity") = 1.0,
           "Adds a point light (white, intensity 1 unless given).")
      .def("addLightSource", [](Scene& s, const Vec3& position) {
             validate::finite(position, {}, "light position");
             s.add(point_light(position), caller_loc());
           }, py::arg("position"), "The lecture's addLightSource: a white point light of intensity 1.")
      .def("add_group", [](Scene& s, const std::string& name, const std::vector<const SceneObject*>& objects) {
             for (const ObjectGroup& g : s.groups)
               if (g.name == name) throw Error("group '" + name + "' is defined twice");
             ObjectGroup g;
             g.name = name;
             g.loc = caller_loc();
             for (const SceneObject* o : objects) {
               std::unique_ptr<SceneObject> copy = o ? copy_object(*o) : nullptr;
               if (!copy) throw py::type_error("a group holds shapes (a Sphere, Triangle, Mesh, solid or CSG tree)");
               g.objects.push_back(std::move(copy));
             }
             s.groups.push_back(std::move(g));
           }, py::arg("name"), py::arg("objects") = std::vector<const SceneObject*>{},
           "Defines a group (copies of the objects), placed by add_instance as often as you like (scene files' `groups`); "
           "add_instance(..., into=name) places earlier groups in it (it must hold something when the scene compiles).")
      .def_property_readonly("groups", [](const Scene& s) {
        std::vector<std::string> names;
        for (const ObjectGroup& g : s.groups) names.push_back(g.name);
        return names;
      }, "The groups' names")
      .def("group", [](py::object self, const std::string& name) {
             Scene& s = self.cast<Scene&>();
             for (const ObjectGroup& g : s.groups)
               if (g.name == name) {
                 py::list out;
                 for (const auto& o : g.objects)
                   out.append(py::cast(o.get(), py::return_value_policy::reference_internal, self));
                 return out;
               }
             throw Error("unknown group '" + name + "'");
           }, py::arg("name"),
           "The group's own objects (its shapes and the instances placed in it), as scene.objects gives the scene's: "
           "changing them changes the group")
      .def("add_instance", [](Scene& s, const std::string& group, const py::object& scale, const Vec3& rotate,
                              const Vec3& translate, const std::optional<Motion>& motion,
                              const std::optional<std::string>& into) {
             const auto find = [&](const std::string& name) {
               std::uint32_t index = 0;
               while (index < s.groups.size() && s.groups[index].name != name) ++index;
               if (index == s.groups.size()) throw Error("unknown group '" + name + "' (add it with add_group first)");
               return index;
             };
             const std::uint32_t index = find(group);
             Instance in(index, make_transform(scale, rotate, translate, "instance"));
             in.loc = caller_loc();
             if (motion) in.motion = *motion;
             if (!into) {
               s.add(std::move(in));
               return;
             }
             // Nested: into a group added after `group`.
             const std::uint32_t outer = find(*into);
             if (outer <= index)
               throw Error("group '" + *into + "' can place only the groups added before it ('" + group + "' is not)");
             s.groups[outer].objects.push_back(std::make_unique<Instance>(std::move(in)));
           }, py::arg("group"), py::kw_only(), py::arg("scale") = 1.0, py::arg("rotate") = py::make_tuple(0, 0, 0),
           py::arg("translate") = py::make_tuple(0, 0, 0), py::arg("motion") = py::none(), py::arg("into") = py::none(),
           "Places a group (scene files' `type: instance`), moved by `motion` if given; with `into`, inside that "
           "group (added after this one: nested instances) instead of the scene.")
      .def("getNumLightSources", &Scene::getNumLightSources)
      .def("getLightSource", [](const Scene& s, int i) {
        if (i < 0 || i >= s.getNumLightSources()) throw py::index_error("no light source " + std::to_string(i));
        return s.getLightSource(i);
      })
      .def_property_readonly("objects", [](py::object self) {
        const Scene& s = self.cast<const Scene&>();
        py::list out;
        for (const auto& o : s.objects())
          out.append(py::cast(o.get(), py::return_value_policy::reference_internal, self));
        return out;
      })
      .def_property_readonly("lights", [](const Scene& s) { return s.lights(); })
      .def_property(
          "camera", [](Scene& s) -> CameraDescription& { return s.camera; },
          [](Scene& s, const CameraDescription& c) { s.camera = c; }, py::return_value_policy::reference_internal)
      .def_property(
          "settings", [](Scene& s) -> RenderSettings& { return s.settings; },
          [](Scene& s, const RenderSettings& r) { s.settings = r; }, py::return_value_policy::reference_internal)
      .def("save", [](const Scene& s, const std::filesystem::path& path) { save_scene(s, path); }, py::arg("path"),
           "Writes the scene as a YAML scene file (.yaml, .yml) that strahl.load and the strahl CLI read back to the "
           "same compiled scene: materials in place, mesh i in <stem>.mesh<i>.obj beside it.")
      .def("to_yaml", [](const Scene& s, const std::string& mesh_stem) { return scene_to_yaml(s, mesh_stem); },
           py::arg("mesh_stem") = "scene",
           "The scene as YAML text (what save writes); mesh i refers to the file <mesh_stem>.mesh<i>.obj.")
      .def("__len__", [](const Scene& s) { return s.objects().size(); })
      .def("__repr__", [](const Scene& s) {
        return "<strahl.Scene: " + std::to_string(s.objects().size()) + " objects, " + std::to_string(s.lights().size()) +
               " lights, " + std::to_string(s.settings.width) + "×" + std::to_string(s.settings.height) + ">";
      });

  m.def("lecture_scene", &lecture_scene, "The lecture's scene (five spheres, a plane, one light): what `strahl` renders without a scene file.");
  m.def("load", [](const std::filesystem::path& path, std::optional<int> width, std::optional<int> height,
                   const std::map<std::string, double>& declare) {
    // As the CLI's --width, --height and --declare (apps/strahl/setup.cpp).
    PovOptions pov;
    if (width) pov.width = *width;
    if (height) pov.height = *height;
    pov.declares.assign(declare.begin(), declare.end());
    Scene scene = interruptible<Scene>([&] { return load_scene(path, pov); });
    if (width) scene.settings.width = *width;
    if (height) scene.settings.height = *height;
    return scene;
  }, py::arg("path"), py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
  py::arg("declare") = std::map<std::string, double>{},
  "Reads a scene file (.yaml, .yml, .json, or a POV-Ray scene .pov: docs/pov-import.md); errors raise strahl.Error with "
  "file, line and column. Ctrl-C (KeyboardInterrupt) stops it. width and height override the scene's size, as the CLI's "
  "--width and --height: for a .pov scene they are also its image_width and image_height (default 1280×720). declare: a "
  ".pov scene's Declare=NAME=VALUE floats, e.g. {\"WHITTED\": 1}.");
  m.def("loads", [](const std::string& text, const std::string& name, const std::filesystem::path& base_dir) {
    return interruptible<Scene>([&] { return parse_scene(text, name, base_dir); });
  }, py::arg("text"), py::arg("name") = "<string>", py::arg("base_dir") = ".",
  "Reads a scene from YAML or JSON text; `name` stands for the file in errors, mesh paths are relative to base_dir.");
}

}  // namespace

void bind_scene(py::module_& m) {
  bind_material(m);
  bind_motion(m);
  bind_shapes(m);
  bind_instance(m);
  bind_lights(m);
  bind_camera(m);
  bind_settings(m);
  bind_scene_class(m);
}

}  // namespace strahl::python
