// The shapes in Python (docs/python.md): Sphere, Plane, Triangle, Mesh (from files or numpy
// arrays) and Instance, with what the shapes' constructors share (shape_args.h). Values are
// checked when an object is made, with the same messages as scene files.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "shape_args.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/validate.h"

namespace strahl::python {
namespace {

template <class T>
T& placed(T& object, const std::optional<Motion>& motion) {
  object.loc = caller_loc();
  if (motion) object.motion = *motion;
  return object;
}

// numpy (or anything numpy takes) → N × 3 doubles.
// `values` as an (n, columns) array of doubles.
py::array_t<double, py::array::c_style> rows(const py::handle& values, const char* what, py::ssize_t columns) {
  const py::array a = py::module_::import("numpy").attr("asarray")(values);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error(std::string(what) + " must be numbers (got dtype " + py::str(a.dtype()).cast<std::string>() + ")");
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (d.ndim() != 2 || d.shape(1) != columns)
    throw py::value_error(std::string(what) + " must have the shape (n, " + std::to_string(columns) + ")");
  return d;
}

py::array_t<double, py::array::c_style> rows3(const py::handle& values, const char* what) { return rows(values, what, 3); }

MeshData mesh_from_arrays(const py::handle& vertices, const py::handle& indices, const py::handle& normals,
                          const py::handle& texcoords) {
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
  const bool with_normals = !normals.is_none(), with_texcoords = !texcoords.is_none();
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
      if (with_texcoords) face.t[std::size_t(k)] = std::int32_t(i);
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
  if (with_texcoords) {
    const auto uv = rows(texcoords, "mesh texcoords", 2);
    if (uv.shape(0) != v.shape(0)) throw py::value_error("mesh texcoords must have one row per vertex");
    const auto tt = uv.unchecked<2>();
    for (py::ssize_t i = 0; i < uv.shape(0); ++i) {
      if (!std::isfinite(tt(i, 0)) || !std::isfinite(tt(i, 1)))
        throw Error("mesh texture coordinate " + std::to_string(i) + " is not finite");
      data.texcoords.push_back({tt(i, 0), tt(i, 1)});
    }
  }
  if (data.faces.empty()) throw Error("mesh has no faces");
  return data;
}

// Per face the three indices of `field` (MeshData::Face::v, n or t).
template <class Index>
py::array_t<std::int64_t> face_indices(const MeshData& data, std::array<Index, 3> MeshData::Face::*field) {
  py::array_t<std::int64_t> out({py::ssize_t(data.faces.size()), py::ssize_t(3)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t f = 0; f < data.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) o(py::ssize_t(f), k) = (data.faces[f].*field)[std::size_t(k)];
  return out;
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

}  // namespace

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
  validate::material(m, validate::kTexturesUnknown, {});
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
                                "per-vertex normals (n × 3) and texture coordinates (texcoords, n × 2: u, v for a "
                                "uv-mapped image), placed by scale, rotate (degrees about x, y, z) and "
                                "translate. Mesh.load(path) reads .obj or .ply.")
      .def(py::init([](const py::object& vertices, const py::object& indices, const py::object& normals,
                       const py::object& color, const py::object& texcoords, const std::optional<Material>& material,
                       const py::object& scale, const Vec3& rotate, const Vec3& translate,
                       const std::optional<Motion>& motion) {
             Mesh mesh(mesh_from_arrays(vertices, indices, normals, texcoords), object_material(color, material),
                       make_transform(scale, rotate, translate, "mesh"));
             return placed(mesh, motion);
           }),
           py::arg("vertices"), py::arg("indices"), py::arg("normals") = py::none(), py::arg("color") = py::none(),
           py::kw_only(), py::arg("texcoords") = py::none(), py::arg("material") = py::none(), py::arg("scale") = 1.0,
           py::arg("rotate") = py::make_tuple(0, 0, 0), py::arg("translate") = py::make_tuple(0, 0, 0),
           py::arg("motion") = py::none())
      .def_static(
          "load",
          [](const std::filesystem::path& path, const py::object& color, const std::optional<Material>& material,
             const py::object& scale, const Vec3& rotate, const Vec3& translate, const std::optional<Motion>& motion,
             bool file_materials) {
            Material mat = object_material(color, material);
            Transform t = make_transform(scale, rotate, translate, "mesh");
            if (file_materials && !gives_materials(path))
              throw Error("file_materials: only glTF (.gltf, .glb) and OBJ files give materials");
            Mesh mesh(interruptible<MeshData>([&] { return load_mesh(path, file_materials); }), mat, t);
            if (file_materials) mesh.file_materials_source = std::filesystem::absolute(path);
            return placed(mesh, motion);
          },
          py::arg("path"), py::arg("color") = py::none(), py::kw_only(), py::arg("material") = py::none(),
          py::arg("scale") = 1.0, py::arg("rotate") = py::make_tuple(0, 0, 0),
          py::arg("translate") = py::make_tuple(0, 0, 0), py::arg("motion") = py::none(), py::arg("file_materials") = false,
          "Reads a mesh file (.obj, .ply, .gltf or .glb) with the scene files' reader and its errors; with "
          "file_materials, a glTF or OBJ file's faces are drawn in its materials' colours and pictures (the rest "
          "from `material`) once the mesh is added to a scene.")
      .def_property_readonly("vertices", [](const Mesh& mesh) { return vec3_rows(mesh.data.positions); })
      .def_property_readonly("normals", [](const Mesh& mesh) { return vec3_rows(mesh.data.normals); })
      .def_property_readonly("indices", [](const Mesh& mesh) {
        return face_indices(mesh.data, &MeshData::Face::v);
      })
      .def_property_readonly("normal_indices", [](const Mesh& mesh) {
        return face_indices(mesh.data, &MeshData::Face::n);
      }, "Per face the normals' indices (−1 where the file gives none)")
      .def_property_readonly("texcoords", [](const Mesh& mesh) {
        py::array_t<double> out({py::ssize_t(mesh.data.texcoords.size()), py::ssize_t(2)});
        auto o = out.mutable_unchecked<2>();
        for (std::size_t i = 0; i < mesh.data.texcoords.size(); ++i) {
          o(py::ssize_t(i), 0) = mesh.data.texcoords[i].u;
          o(py::ssize_t(i), 1) = mesh.data.texcoords[i].v;
        }
        return out;
      }, "The texture coordinates (u, v), one row each")
      .def_property_readonly("texcoord_indices", [](const Mesh& mesh) {
        return face_indices(mesh.data, &MeshData::Face::t);
      }, "Per face the texture coordinates' indices (−1 where the file gives none)")
      .def_property_readonly("transform", [](const Mesh& mesh) { return mesh.transform; });
}

void bind_instance(py::module_& m) {
  py::class_<Instance, SceneObject>(m, "Instance", "A placed group (Scene.add_instance; scene files' `instance`).")
      .def_readonly("group", &Instance::group, "The group's index in Scene.groups")
      .def("__repr__", [](const Instance& in) {
        return "<strahl.Instance of group " + std::to_string(in.group) + (in.motion.moving() ? ", moving>" : ">");
      });
}

}  // namespace strahl::python
