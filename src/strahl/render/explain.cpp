#include "strahl/render/explain.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "strahl/util/error.h"

namespace strahl {
namespace {

std::string num(Real x) {
  if (x == 0) x = 0;  // −0 prints as 0
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", double(x));
  return buffer;
}

std::string vec(const Vec3& v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }

const char* solid_name(kernel::SolidKind kind) {
  switch (kind) {
    case kernel::SolidKind::Box: return "box";
    case kernel::SolidKind::Cone: return "cone or cylinder";
    case kernel::SolidKind::Disk: return "disk";
    case kernel::SolidKind::Torus: return "torus";
    case kernel::SolidKind::Quadric: return "quadric";
    case kernel::SolidKind::Implicit: return "implicit surface";
    case kernel::SolidKind::Sphere: return "sphere (solid)";
    case kernel::SolidKind::Csg: return "CSG tree";
    case kernel::SolidKind::Placed: return "transformed solid";
  }
  return "solid";
}

// trace()'s observer (render/whitted.h): writes each ray of the tree as trace() walks it, depth
// first, each child indented under its hit.
class Explainer {
 public:
  Explainer(const RenderScene& scene, const SceneView& s, std::string& out) : scene_(scene), s_(s), out_(out) {}

  void ray(TracedRay kind, int depth, const Ray& r, Real weight) {
    ray_direction_ = r.direction;  // (surface() and split() need it)
    Node node;
    node.depth = depth;
    node.name = stack_.empty() ? "1" : stack_.back().name + (kind == TracedRay::Reflected ? ".R" : ".T");
    if (!stack_.empty()) (kind == TracedRay::Reflected ? stack_.back().reflected_ray : stack_.back().refracted_ray) = true;
    node.kind = kind;
    const char* what = kind == TracedRay::Camera ? "camera ray" : kind == TracedRay::Reflected ? "reflected ray" : "refracted ray";
    line(depth, "ray " + node.name + ": " + what + ", depth " + std::to_string(depth) + ", weight " + num(weight));
    line(depth, "  from " + vec(r.origin) + " along " + vec(r.direction));
    stack_.push_back(node);
  }

  void emitter(int light, const Vec3& radiance) {
    line(here(), "  meets area light " + std::to_string(light) + ": its radiance L = " + vec(radiance));
  }

  void background(const Vec3& color) { line(here(), "  hits nothing: the background " + vec(color)); }

  void surface(const Hit& hit, const SurfacePoint& sp, bool front, const Vec3& n, const Vec3& local) {
    const int d = here();
    Node& node = stack_.back();
    node.surface = true;
    node.local = local;
    node.normal = n;
    node.material = sp.material;
    line(d, "  hits " + object_name(hit, sp) + " at t = " + num(hit.t));
    line(d, "    p = " + vec(sp.p) + ", N = " + vec(n) +
                (front ? " (the ray arrives at the outside)" : " (the ray arrives from inside: N turned towards it)"));
    const Material& m = s_.materials[sp.material];
    const Vec3 c = surface_color(m, sp.texcoord, s_.textures);
    line(d, "    C = " + vec(c) + (m.texture != kNoTexture ? " (from image texture " + std::to_string(m.texture) + ")" : "") +
                ", k_a = " + num(m.ambient) + ", k_d = " + num(m.diffuse) + ", k_s = " + vec(m.specular) +
                ", shininess " + num(m.shininess) + ", k_r = " + num(m.reflectivity) + ", T = " + num(m.transparency) +
                (m.transparency > 0 ? ", ior " + num(m.ior) : std::string()) +
                (m.roughness > 0 ? ", roughness " + num(m.roughness) : std::string()));
    // Each light's share, by the functions local_illumination() calls (its shadow rays traced
    // again here: no random numbers, so the same answers).
    const Vec3 view = -ray_direction_;
    Vec3 sum = ambient_term(s_, m, c);
    line(d, "    ambient (1 − T)·k_a·C·ambient_light = " + vec(sum));
    if (!is_black(m.emission)) {
      sum += m.emission;  // unlit_term()'s sum
      line(d, "    emission E = " + vec(m.emission));
    }
    bool sampled = false;
    RayCounters scratch;
    for (std::uint32_t i = 0; i < s_.light_count; ++i) {
      const Light& light = s_.lights[i];
      std::string text = "    light " + std::to_string(i) + " (" + light_kind_name(light.kind);
      if (light.is_area()) {
        sampled = true;
        line(d, text + ", " + std::to_string(light.samples) + "×" + std::to_string(light.samples) +
                    " samples): sampled with this sample's random numbers, not broken down here");
        continue;
      }
      text += light.kind == LightKind::Directional ? " along " + vec(light.direction) : " at " + vec(light.position);
      if (light.kind == LightKind::Spot)
        text += " towards " + vec(light.direction) + ", angle " + num(light.angle) + "°, falloff " + num(light.falloff) +
                "°, tightness " + num(light.tightness);
      text += ", I = " + vec(light.radiance) + "): ";
      const LightSample ls = sample_light(light, sp.p);
      const Real spot = spot_factor(light, ls.to_light), reach = light_share(light, ls.to_light, ls.distance);
      const Vec3 intensity = light.radiance * reach;
      const Real n_dot_l = dot(n, ls.to_light);
      text += "L = " + vec(ls.to_light) + ", N·L = " + num(n_dot_l);
      if (light.kind == LightKind::Spot) {
        text += ", the spot's share " + num(spot);
        if (!(spot > 0)) {
          line(d, text + ": outside its cone, adds 0");
          continue;
        }
      }
      if (light.fade_power > 0)
        text += ", the fade over " + num(ls.distance) + " (fade_distance " + num(light.fade_distance) +
                ", fade_power " + num(light.fade_power) + "): " + num(fade_factor(light, ls.distance));
      if (!(reach > 0)) {  // a fade that underflows: as local_illumination(), no shadow ray
        line(d, text + ": no light reaches it, adds 0");
        continue;
      }
      if (light.shaped()) text += " (I = " + vec(intensity) + ")";
      if (n_dot_l <= 0) {
        line(d, text + ": behind the surface, adds 0");
        continue;
      }
      KnownLight known;
      known.sample = ls;
      known.transmittance = transmittance(s_, shadow_ray(sp, ls.to_light), ls.distance);
      known.n_dot_h = dot(n, normalize(ls.to_light + view));
      const Vec3 share =
          shade_from(s_, sp, n, view, c, m, ls.to_light, ls.distance, intensity, scratch, &known);
      sum += share;
      line(d, text);
      if (is_black(known.transmittance)) {
        line(d, "      the shadow ray is blocked: adds 0");
        continue;
      }
      line(d, std::string(known.transmittance == Vec3(1) ? "      the shadow ray reaches it"
                                                         : "      the shadow ray passes transparent objects: S = " +
                                                               vec(known.transmittance)) +
                  "; N·H = " + num(known.n_dot_h) + ": S·I·[(1 − T)·k_d·C·N·L + k_s·(N·H)^shininess] = " + vec(share));
    }
    // Without area lights the shares above are local's own terms, added in its order.
    if (sampled) line(d, "    the area lights' samples add local − the terms above = " + vec(local - sum));
    line(d, std::string("    local = ") + (!sampled && sum == local ? (is_black(m.emission) ? "ambient + lights = " : "ambient + E + lights = ") : "") + vec(local));
  }

  void split(Real kr, Real kt, bool reflects, Real n1, Real n2) {
    const int d = here();
    Node& node = stack_.back();
    node.kr = kr;
    node.kt = kt;
    node.split = true;
    const Material& m = s_.materials[node.material];
    if (m.transparency > 0) {
      // Snell's law (lecture 1.5): n_1·sin θ_1 = n_2·sin θ_2, θ_1 between −d and N.
      const Real cos1 = -dot(ray_direction_, node.normal);
      const Real sin2 = n1 / n2 * std::sqrt(std::fmax(Real(0), 1 - cos1 * cos1));
      line(d, "    refraction n_1 = " + num(n1) + " → n_2 = " + num(n2) + ": cos θ_1 = −d·N = " + num(cos1) +
                  ", sin θ_2 = (n_1/n_2)·sin θ_1 = " + num(sin2) + (sin2 > 1 ? " > 1" : ""));
    }
    std::string text = "    k_r = " + num(kr) + ", T = " + num(kt);
    if (m.transparency > 0 && !(kt > 0)) text += " (total internal reflection: T moved to k_r)";
    else if (m.transparency > 0 && m.fresnel) text += " (Fresnel: Schlick's share of T moved to k_r)";
    if (kr > 0 && !reflects) text += "; the reflected ray is not traced (its weight is below min_weight, or the ray budget is spent)";
    line(d, text);
  }

  void done(int depth, const Vec3& color) {
    Node node = stack_.back();
    stack_.pop_back();
    std::string text = "  ray " + node.name + " brings " + vec(color);
    if (node.surface) {
      if (!node.split) {
        text += " = local (max_depth " + std::to_string(s_.settings.max_depth) + " reached: no further rays)";
      } else if (node.reflected_ray || node.refracted_ray) {
        text += " = local " + vec(node.local);
        if (node.reflected_ray) text += " + k_r·" + vec(node.reflected);
        if (node.refracted_ray) {
          const Material& m = s_.materials[node.material];
          text += std::string(" + T·") + (m.filter ? "C·" : "") + vec(node.refracted);
        }
      } else {
        text += " = local";
      }
      if (node.split && node.kt > 0 && !node.refracted_ray)
        text += " (the refracted ray is not traced: its weight is below min_weight, or the ray budget is spent)";
    }
    line(depth, text);
    if (!stack_.empty()) (node.kind == TracedRay::Reflected ? stack_.back().reflected : stack_.back().refracted) = color;
  }

 private:
  struct Node {
    int depth = 1;
    std::string name;
    TracedRay kind = TracedRay::Camera;
    bool surface = false, split = false, reflected_ray = false, refracted_ray = false;
    std::uint32_t material = 0;
    Vec3 local, normal, reflected, refracted;
    Real kr = 0, kt = 0;
  };

  int here() const { return stack_.back().depth; }

  void line(int depth, const std::string& text) {
    out_.append(std::size_t(2 * (depth - 1)), ' ');
    out_ += text;
    out_ += '\n';
  }

  // What the ray hit, with the object id `--aov id` writes (compile() gives every object its own
  // material slot: the groups' shapes first, then the `objects` list).
  std::string object_name(const Hit& hit, const SurfacePoint& sp) const {
    std::string kind;
    switch (hit.kind) {
      case ShapeKind::Sphere: kind = "a sphere"; break;
      case ShapeKind::Plane: kind = "a plane"; break;
      case ShapeKind::Triangle: kind = "a triangle"; break;
      case ShapeKind::Solid: kind = std::string("a ") + solid_name(s_.solids[hit.index].kind); break;
      case ShapeKind::MovingSphere: kind = "a moving sphere"; break;
      case ShapeKind::MovingTriangle: kind = "a moving triangle"; break;
      case ShapeKind::MovingSolid: kind = "a moving solid"; break;
      case ShapeKind::Instance:
        kind = group_shape(s_.instances[hit.index].group, hit.prim) + ", in instance record " + std::to_string(hit.index);
        break;
      case ShapeKind::MovingInstance:
        kind = group_shape(s_.moving_instances[hit.index].instance.group, hit.prim) + ", in moving instance record " +
               std::to_string(hit.index);
        break;
      case ShapeKind::None: break;
    }
    return kind + " (object id " + std::to_string(sp.material) + ")";
  }

  // Primitive `prim` of group `group`'s structure (spheres, triangles, then solids), and the
  // group's name: the scene's, or what the compiler made the group for (scene/instances.h).
  std::string group_shape(std::uint32_t group, std::uint32_t prim) const {
    if (group >= scene_.groups.size()) return "a shape of a group";
    const PrimitiveSet prims = scene_.groups[group].primitives();
    const std::string shape = prims.is_sphere(prim)  ? "a sphere"
                              : prims.is_solid(prim) ? std::string("a ") + solid_name(prims.solid(prim).kind)
                                                     : "a triangle";
    if (group < scene_.group_nesting.size() && scene_.group_nesting[group].placeable)
      return shape + " of group '" + scene_.group_nesting[group].name + "'";
    return shape + (group < scene_.group_nesting.size() ? " moving in its group" : " that turns");
  }

  const RenderScene& scene_;
  const SceneView& s_;
  std::string& out_;
  std::vector<Node> stack_;
  Vec3 ray_direction_;
};

}  // namespace

std::string explain_refusal(const SceneView& s) {
  if (s.settings.integrator == IntegratorKind::Whitted) return {};
  return std::string("explain shows Whitted's ray tree; this scene renders with integrator: ") +
         integrator_name(s.settings.integrator);
}

PixelExplanation explain_pixel(const RenderScene& scene, int x, int row, std::uint32_t index) {
  return explain_pixel(scene, scene.view(), scene.sampling, x, row, index);
}

PixelExplanation explain_pixel(const RenderScene& scene, const SceneView& s, const SamplingSettings& sampling, int x,
                               int row, std::uint32_t index) {
  const Camera& cam = s.camera;
  if (x < 0 || x >= cam.nx || row < 0 || row >= cam.ny)
    throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(row) + ") is outside the image of " +
                std::to_string(cam.nx) + "×" + std::to_string(cam.ny) + " pixels");
  if (const std::string why = explain_refusal(s); !why.empty()) throw Error(why);
  PixelExplanation out;
  // The sample as the renderer takes it (render/pixel.h), its ray tree told to the Explainer.
  std::string tree;
  Explainer explainer(scene, s, tree);
  CameraSample cs;
  out.radiance = pixel_sample(s, pixel_sequence(s, make_pixel_sampler(sampling), x, row), index, cs, out.rays,
                              &explainer);
  const RayCounters& counters = out.rays;
  std::string& t = out.text;
  t += "pixel (" + std::to_string(x) + ", " + std::to_string(row) + ") of " + std::to_string(cam.nx) + "×" +
       std::to_string(cam.ny) + " (x from the left, row from the top), sample " + std::to_string(index) + " of its " +
       sampler_name(sampling.sampler) + " sequence\n";
  t += "camera: e = " + vec(cam.eye) + ", u = " + vec(cam.basis.u) + ", v = " + vec(cam.basis.v) + ", w = " +
       vec(cam.basis.w) + "\n";
  t += "        l = " + num(cam.l) + ", r = " + num(cam.r) + ", b = " + num(cam.b) + ", t = " + num(cam.t) +
       ", d = " + num(cam.d) + ", n_x = " + std::to_string(cam.nx) + ", n_y = " + std::to_string(cam.ny) + "\n";
  const Real su = cam.l + (cam.r - cam.l) * cs.film_x / cam.nx;
  const Real sv = cam.b + (cam.t - cam.b) * cs.film_y / cam.ny;
  t += "film position (x, y) = (" + num(cs.film_x) + ", " + num(cs.film_y) + ") (y from the bottom row): s_u = l + (r − l)·x/n_x = " +
       num(su) + ", s_v = b + (t − b)·y/n_y = " + num(sv) + "\n";
  t += "direction = normalize(s_u·u + s_v·v − d·w) = " + vec(cam.generate_ray(cs.film_x, cs.film_y).direction) + "\n";
  const Ray ray = cam.generate_ray(cs);
  if (cam.lens_radius > 0)
    t += "through the thin lens (radius " + num(cam.lens_radius) + ", in focus at distance " + num(cam.focus_distance) +
         "): from " + vec(ray.origin) + " along " + vec(ray.direction) + "\n";
  if (cam.shutter_close != cam.shutter_open && s.moving_count() > 0) t += "time " + num(ray.time) + " (the shutter's)\n";
  t += tree;
  if (counters.invalid_samples > 0) t += "the radiance is not finite: the film takes it as black\n";
  t += "radiance " + vec(out.radiance) + " (linear) from " + std::to_string(counters.total()) + " rays: " +
       std::to_string(counters.camera) + " camera, " + std::to_string(counters.shadow) + " shadow, " +
       std::to_string(counters.reflection) + " reflection, " + std::to_string(counters.refraction) + " refraction\n";
  return out;
}

}  // namespace strahl
