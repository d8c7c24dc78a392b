// The scene API in Python (docs/python.md): Material, Motion and Scene, and the order in which the
// parts of the scene API are bound (bindings.h). Values are checked when an object is made (the
// same messages as scene files); compile() checks everything again when rendering.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <map>
#include <optional>
#include <sstream>

#include "bindings.h"
#include "convert.h"
#include "shape_args.h"
#include "strahl/scene/file_materials.h"
#include "strahl/scene/instances.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "strahl/scene/validate.h"

namespace strahl::python {

namespace {

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

// A mesh read with its file's materials (glTF, OBJ): their pictures become this scene's textures.
void use_file_materials_in(Scene& scene, SceneObject& object) {
  if (auto* mesh = dynamic_cast<Mesh*>(&object); mesh && !mesh->data.materials.empty()) use_file_materials(scene, *mesh);
}

void add_object(Scene& scene, const SceneObject& object) {
  std::unique_ptr<SceneObject> copy = copy_object(object);
  if (!copy) throw py::type_error("Scene.add takes a shape (a Sphere, Plane, Triangle, Mesh, solid or CSG tree) or a light");
  use_file_materials_in(scene, *copy);
  scene.addSceneObject(copy.release());
}

void bind_material(py::module_& m) {
  const Material d;
  py::class_<Material>(m, "Material",
                       "The lecture's surface: colour, ambient, Lambert, Blinn-Phong, mirror and refraction "
                       "(docs/scene-format.md, materials). Every field is a keyword argument and an attribute.")
      .def(py::init([](const py::object& color, double ambient, double diffuse, const py::object& specular,
                       double shininess, double reflectivity, double transparency, const py::object& ior, bool fresnel,
                       bool filter, double roughness, double checker_size, const py::object& checker_color,
                       std::optional<std::uint32_t> texture, const py::object& emission) {
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
             mat.emission = color_arg(emission, "emission");
             if (texture) {
               if (*texture == kNoTexture) throw Error("texture must be an index Scene.add_texture returned");
               mat.texture = *texture;
             }
             validate::material(mat, validate::kTexturesUnknown, {});
             validate::in_range(mat.roughness, 0, 1, {}, "roughness");
             return mat;
           }),
           py::arg("color") = py::make_tuple(d.color.x, d.color.y, d.color.z), py::kw_only(),
           py::arg("ambient") = d.ambient, py::arg("diffuse") = d.diffuse,
           py::arg("specular") = py::make_tuple(d.specular.x, d.specular.y, d.specular.z),
           py::arg("shininess") = d.shininess, py::arg("reflectivity") = d.reflectivity,
           py::arg("transparency") = d.transparency, py::arg("ior") = d.ior, py::arg("fresnel") = d.fresnel,
           py::arg("filter") = d.filter, py::arg("roughness") = d.roughness, py::arg("checker_size") = d.checker_size,
           py::arg("checker_color") = py::make_tuple(d.checker_color.x, d.checker_color.y, d.checker_color.z),
           py::arg("texture") = py::none(), py::arg("emission") = py::make_tuple(0.0, 0.0, 0.0))
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
      .def_readwrite("emission", &Material::emission)
      .def_property(
          "texture", [](const Material& mat) -> py::object {
            return mat.texture == kNoTexture ? py::none() : py::cast(mat.texture);
          },
          [](Material& mat, std::optional<std::uint32_t> t) { mat.texture = t ? *t : kNoTexture; },
          "The image texture giving the colour (an index Scene.add_texture returned), or None")
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
      .def("add_texture", [](Scene& s, const std::filesystem::path& file, const std::string& mapping,
                             const std::string& interpolate, bool once, bool linear, const py::object& scale,
                             const Vec3& rotate, const Vec3& translate) {
             ImageTexture t;
             t.loc = caller_loc();
             t.file = file;
             if (!image_mapping_from(mapping, t.mapping))
               throw Error("unknown image mapping '" + mapping + "' (" + kImageMappingNames + ")");
             if (!image_interpolate_from(interpolate, t.bilinear))
               throw Error("unknown image interpolate '" + interpolate + "' (" + kImageInterpolateNames + ")");
             t.once = once;
             t.placement = make_transform(scale, rotate, translate, "texture");
             t.image = read_texture_image(file, linear);
             return s.add_texture(std::move(t));
           }, py::arg("file"), py::kw_only(), py::arg("mapping") = "planar", py::arg("interpolate") = "bilinear",
           py::arg("once") = false, py::arg("linear") = false, py::arg("scale") = 1.0,
           py::arg("rotate") = Vec3(0), py::arg("translate") = Vec3(0),
           "Reads an image (.png, .jpg, .ppm: sRGB unless linear=True; .pfm, .exr) as a texture and returns the "
           "index a Material's texture takes (docs/scene-format.md, image textures).")
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
               use_file_materials_in(s, *copy);
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
