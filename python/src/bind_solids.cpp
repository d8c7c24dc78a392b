// The solids and CSG in Python (docs/python.md, "Solids and CSG"): Box, Cylinder, Cone, Disk, Torus,
// Quadric, Implicit and the CSG operations Union, Intersection, Difference, Merge, Inverse, each
// with the scene files' keys as arguments, a placement (scale, rotate, translate) and a motion.
// Each is checked when made by compiling it alone: the scene files' messages, naming the line of
// Python that made it.

#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <vector>

#include "bindings.h"
#include "shape_args.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/copy_object.h"
#include "strahl/scene/csg.h"
#include "strahl/scene/solids.h"

// A CSG node owns its operands (std::unique_ptr): pybind11 must not try to copy one (std::vector
// claims to be copyable whatever it holds); Scene.add copies trees with copy_object.
template <>
struct pybind11::detail::is_copy_constructible<strahl::Csg> : std::false_type {};

namespace strahl::python {

namespace {

// Every solid's last arguments: color (positional), then material, motion and the placement.
struct Common {
  py::object color = py::none();
  std::optional<Material> material;
  std::optional<Motion> motion;
  py::object scale = py::float_(1.0);
  Vec3 rotate{0}, translate{0};
};

// The solid with its material, motion, placement and the caller's line, checked by compiling it
// alone (compile_into throws the scene files' messages at o.loc).
template <class T>
T finish(T o, const Common& c, const char* what) {
  o.material = object_material(c.color, c.material);
  if (c.motion) o.motion = *c.motion;
  o.placement = make_transform(c.scale, c.rotate, c.translate, what);
  o.loc = caller_loc();
  RenderScene scratch;
  scratch.camera.shutter_close = 1;
  o.compile_into(scratch, 0, 0);
  return o;
}

// py::arg list of the Common arguments, in order (after the solid's own).
#define STRAHL_COMMON_ARGS                                                                                         \
  py::arg("color") = py::none(), py::kw_only(), py::arg("material") = py::none(), py::arg("motion") = py::none(), \
      py::arg("scale") = 1.0, py::arg("rotate") = py::make_tuple(0, 0, 0),                                         \
      py::arg("translate") = py::make_tuple(0, 0, 0)
#define STRAHL_COMMON_PARAMS                                                                               \
  const py::object &color, const std::optional<Material>&material, const std::optional<Motion>&motion, \
      const py::object &scale, const Vec3 &rotate, const Vec3 &translate
#define STRAHL_COMMON Common{color, material, motion, scale, rotate, translate}

CsgOperation operation_named(const std::string& name) {
  for (const CsgOperation op : {CsgOperation::Union, CsgOperation::Intersection, CsgOperation::Difference,
                                CsgOperation::Merge, CsgOperation::Inverse})
    if (name == csg_operation_name(op)) return op;
  throw Error("unknown CSG operation '" + name + "' (union, intersection, difference, merge or inverse)");
}

Csg make_csg(CsgOperation op, const std::vector<const SceneObject*>& objects, const Common& c) {
  std::vector<std::unique_ptr<SceneObject>> children;
  for (const SceneObject* o : objects) {
    if (o == nullptr) throw py::type_error("a CSG operand must be a shape, not None");
    children.push_back(copy_object(*o));
    if (!children.back()) throw py::type_error("this shape cannot be a CSG operand");
  }
  return finish(Csg(op, std::move(children), Material{}), c, csg_operation_name(op));
}

}  // namespace

void bind_solids(py::module_& m) {
  py::class_<Box, SceneObject>(m, "Box", "An axis-aligned box between two opposite corners (scene files' `box`).")
      .def(py::init([](const Vec3& a, const Vec3& b, STRAHL_COMMON_PARAMS) {
             return finish(Box(a, b, Material{}), STRAHL_COMMON, "box");
           }),
           py::arg("corner_a"), py::arg("corner_b"), STRAHL_COMMON_ARGS)
      .def_readwrite("corner_a", &Box::corner_a)
      .def_readwrite("corner_b", &Box::corner_b);

  py::class_<Cone, SceneObject>(m, "Cone",
                                "A truncated cone from base (radius base_radius) to cap (radius cap_radius); "
                                "open=True leaves out the end caps. Cylinder(...) makes one with equal radii.")
      .def(py::init([](const Vec3& base, double base_radius, const Vec3& cap, double cap_radius, bool open,
                       STRAHL_COMMON_PARAMS) {
             return finish(Cone(base, base_radius, cap, cap_radius, Material{}, open), STRAHL_COMMON, "cone");
           }),
           py::arg("base"), py::arg("base_radius"), py::arg("cap"), py::arg("cap_radius"), py::arg("open") = false,
           STRAHL_COMMON_ARGS)
      .def_readwrite("base", &Cone::base)
      .def_readwrite("cap", &Cone::cap)
      .def_readwrite("base_radius", &Cone::base_radius)
      .def_readwrite("cap_radius", &Cone::cap_radius)
      .def_readwrite("open", &Cone::open);
  m.def(
      "Cylinder",
      [](const Vec3& base, const Vec3& cap, double radius, bool open, STRAHL_COMMON_PARAMS) {
        Cone c = Cone::cylinder(base, cap, radius, Material{}, open);
        return finish(std::move(c), STRAHL_COMMON, "cylinder");
      },
      py::arg("base"), py::arg("cap"), py::arg("radius"), py::arg("open") = false, STRAHL_COMMON_ARGS,
      "A cylinder from base to cap (scene files' `cylinder`): a Cone with equal radii.");

  py::class_<Disk, SceneObject>(m, "Disk", "A flat disk (scene files' `disk`).")
      .def(py::init([](const Vec3& center, const Vec3& normal, double radius, STRAHL_COMMON_PARAMS) {
             return finish(Disk(center, normal, radius, Material{}), STRAHL_COMMON, "disk");
           }),
           py::arg("center"), py::arg("normal"), py::arg("radius"), STRAHL_COMMON_ARGS)
      .def_readwrite("center", &Disk::center)
      .def_readwrite("normal", &Disk::normal)
      .def_readwrite("radius", &Disk::radius);

  py::class_<Torus, SceneObject>(m, "Torus", "A ring torus around axis through center: 0 < minor_radius < major_radius.")
      .def(py::init([](const Vec3& center, double major, double minor, const Vec3& axis, STRAHL_COMMON_PARAMS) {
             return finish(Torus(center, major, minor, Material{}, axis), STRAHL_COMMON, "torus");
           }),
           py::arg("center"), py::arg("major_radius"), py::arg("minor_radius"), py::arg("axis") = py::make_tuple(0, 1, 0),
           STRAHL_COMMON_ARGS)
      .def_readwrite("center", &Torus::center)
      .def_readwrite("axis", &Torus::axis)
      .def_readwrite("major_radius", &Torus::major)
      .def_readwrite("minor_radius", &Torus::minor);

  py::class_<Quadric, SceneObject>(m, "Quadric",
                                   "Ax² + By² + Cz² + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0 (inside: < 0), "
                                   "coefficients (A … J); clipped_by=(corner, corner) keeps the surface in that box.")
      .def(py::init([](const std::array<double, 10>& coefficients, const std::optional<std::pair<Vec3, Vec3>>& clip,
                       STRAHL_COMMON_PARAMS) {
             std::array<Real, 10> k{};
             for (std::size_t i = 0; i < 10; ++i) k[i] = coefficients[i];
             std::optional<ClipBox> box;
             if (clip) box = ClipBox{clip->first, clip->second};
             return finish(Quadric(k, Material{}, box), STRAHL_COMMON, "quadric");
           }),
           py::arg("coefficients"), py::arg("clipped_by") = py::none(), STRAHL_COMMON_ARGS)
      .def_property_readonly("coefficients", [](const Quadric& q) { return q.coefficients; });

  py::class_<ImplicitSurface, SceneObject>(
      m, "Implicit",
      "The surface f(x, y, z) = 0 of an expression (inside: f < 0) within a bound: contained_by=(corner, corner) "
      "a box, or contained_by_sphere=(center, radius); method 'lipschitz', 'distance' or 'march' (scene files' "
      "`implicit`).")
      .def(py::init([](const std::string& expression, const std::optional<std::pair<Vec3, Vec3>>& box,
                       const std::optional<std::pair<Vec3, double>>& sphere, const std::map<std::string, double>& parameters,
                       double max_gradient, double accuracy, const std::string& method, double step, STRAHL_COMMON_PARAMS) {
             ImplicitSurface s(expression, Material{});
             if (box.has_value() == sphere.has_value())
               throw py::type_error("give one bound: contained_by=(corner, corner) or contained_by_sphere=(center, radius)");
             if (box) {
               s.bound = kernel::ImplicitBound::Box;
               s.box_a = box->first;
               s.box_b = box->second;
             } else {
               s.bound = kernel::ImplicitBound::Sphere;
               s.center = sphere->first;
               s.radius = sphere->second;
             }
             for (const auto& [name, value] : parameters) s.parameters[name] = value;
             s.max_gradient = max_gradient;
             s.accuracy = accuracy;
             if (method == "lipschitz") s.method = kernel::RootMethod::Lipschitz;
             else if (method == "distance") s.method = kernel::RootMethod::SphereTrace;
             else if (method == "march") s.method = kernel::RootMethod::March;
             else throw Error("unknown method '" + method + "' (lipschitz, distance or march)");
             if (step != 0 && s.method != kernel::RootMethod::March) throw Error("step is for method: march");
             s.step = step;
             return finish(std::move(s), STRAHL_COMMON, "implicit");
           }),
           py::arg("expression"), py::kw_only(), py::arg("contained_by") = py::none(),
           py::arg("contained_by_sphere") = py::none(), py::arg("parameters") = std::map<std::string, double>{},
           py::arg("max_gradient") = 1.1, py::arg("accuracy") = 1e-3, py::arg("method") = "lipschitz",
           py::arg("step") = 0.0, py::arg("color") = py::none(), py::arg("material") = py::none(),
           py::arg("motion") = py::none(), py::arg("scale") = 1.0, py::arg("rotate") = py::make_tuple(0, 0, 0),
           py::arg("translate") = py::make_tuple(0, 0, 0))
      .def_readonly("expression", &ImplicitSurface::expression);

  py::class_<Csg, SceneObject>(m, "Csg",
                               "A CSG tree: Union, Intersection, Difference, Merge or Inverse of solids and other "
                               "trees (copies of them); the outermost node's material and motion apply to the whole.")
      .def(py::init([](const std::string& operation, const std::vector<const SceneObject*>& objects,
                       STRAHL_COMMON_PARAMS) { return make_csg(operation_named(operation), objects, STRAHL_COMMON); }),
           py::arg("operation"), py::arg("objects"), STRAHL_COMMON_ARGS)
      .def_property_readonly("operation", [](const Csg& c) { return csg_operation_name(c.operation); })
      .def_property_readonly(
          "objects",
          [](py::object self) {
            const Csg& c = self.cast<const Csg&>();
            py::list out;
            for (const auto& o : c.children) out.append(py::cast(o.get(), py::return_value_policy::reference_internal, self));
            return out;
          },
          "The operands (the tree's own: changing them changes the tree)");
  for (const CsgOperation op : {CsgOperation::Union, CsgOperation::Intersection, CsgOperation::Difference,
                                CsgOperation::Merge}) {
    std::string name = csg_operation_name(op);
    name[0] = char(name[0] - 'a' + 'A');
    m.def(
        name.c_str(),
        [op](const std::vector<const SceneObject*>& objects, STRAHL_COMMON_PARAMS) {
          return make_csg(op, objects, STRAHL_COMMON);
        },
        py::arg("objects"), STRAHL_COMMON_ARGS,
        ("The " + std::string(csg_operation_name(op)) + " of solids and CSG trees (scene files' `" +
         csg_operation_name(op) + "`).")
            .c_str());
  }
  m.def(
      "Inverse",
      [](const SceneObject* object, STRAHL_COMMON_PARAMS) {
        return make_csg(CsgOperation::Inverse, {object}, STRAHL_COMMON);
      },
      py::arg("object"), STRAHL_COMMON_ARGS, "Everything but the solid (scene files' `inverse`).");
}

#undef STRAHL_COMMON_ARGS
#undef STRAHL_COMMON_PARAMS
#undef STRAHL_COMMON

}  // namespace strahl::python
