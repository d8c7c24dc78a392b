// Groups and instances (scene/instances.h).

#include "strahl/scene/instances.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strahl/render/render_scene.h"
#include "strahl/scene/copy_object.h"
#include "strahl/scene/file_materials.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/scene_warnings.h"
#include "strahl/scene/shape_bounds.h"
#include "strahl/scene/validate.h"
#include "strahl/util/cancel.h"

namespace strahl {
namespace {

// A placement of a group's moving shape before its own group is appended (compile_groups).
constexpr std::uint32_t kMovingShapeGroup = 0xffffffffu;

bool identity(const Mat3& m) {
  const Mat3 i;
  return m.row[0] == i.row[0] && m.row[1] == i.row[1] && m.row[2] == i.row[2];
}

bool finite(const Bounds& b) {
  return std::isfinite(b.lo.x) && std::isfinite(b.lo.y) && std::isfinite(b.lo.z) && std::isfinite(b.hi.x) &&
         std::isfinite(b.hi.y) && std::isfinite(b.hi.z);
}

// Does the map keep lengths at every time of the shutter (the same orthonormal linear part at
// both keys, turned by rotations, and an orthonormal post map, if any)?
bool keeps_lengths(const kernel::MovingMap& map) {
  const auto orthonormal = [](const Vec3* rows) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (!(std::fabs(dot(rows[i], rows[j]) - (i == j ? 1 : 0)) <= Real(1e-12))) return false;
    return true;
  };
  for (int i = 0; i < 3; ++i)
    if (!(map.linear0[i] == map.linear1[i])) return false;
  return orthonormal(map.linear0) && (map.post == 0 || orthonormal(map.post_row));
}

// Bounds over the shutter of the stretch and the translation's largest component of `map` after
// a map with those bounds (stretch, shift): ray offsets (geometry/moving_instance.h). Over the
// shutter the linear part's Frobenius norm is at most the larger of the keys' (a norm of a blend;
// a turn keeps it), which bounds the stretch of A(u) and of its product with the placement; the
// translation A(u)·t_placement + t(u) − Rot(u)·c(u) by the same, plus the larger of the keys' |c|
// about a spin's centre (a turn keeps its length). A post map P stretches both by at most its norm
// and adds its translation.
void carry_bounds(const kernel::MovingMap& map, Real& stretch, Real& shift) {
  Real reach = 0, moved = 0, pivot = 0;
  for (int key = 0; key < 2; ++key) {
    reach = std::fmax(reach, kernel::frobenius(key == 0 ? map.linear0 : map.linear1));
    moved = std::fmax(moved, max_abs_component(key == 0 ? map.translate0 : map.translate1));
    if (map.pivot != 0) pivot = std::fmax(pivot, length(key == 0 ? map.pivot0 : map.pivot1));
  }
  moved += pivot;
  Real post = 1, post_shift = 0;
  if (map.post != 0) {
    post = kernel::frobenius(map.post_row);
    post_shift = max_abs_component(map.post_translate);
  }
  stretch = stretch * reach * post;
  const Real sqrt3 = Real(1.7320508075688772);  // |L·t|∞ ≤ ‖L‖_F·|t|₂ ≤ ‖L‖_F·√3·|t|∞
  shift = moved + reach * sqrt3 * shift;
  if (map.post != 0) shift = post * sqrt3 * shift + post_shift;
}

// The instance x (world box w) carried by `map` after its placement, and then by `outer` where
// given: into the motion BVH with the other moving shapes (geometry/moving_instance.h).
void push_moving_instance(RenderScene& out, const kernel::Instance& x, const Bounds& w, const kernel::MovingMap& map,
                          const kernel::MovingMap* outer, const FileLoc& loc) {
  kernel::MovingInstance mi;
  mi.instance = x;
  mi.map = map;
  if (outer != nullptr) {
    mi.outer = *outer;
    mi.two_maps = 1;
  }
  // A map that scales brings the ray to the still instance with a direction of another length:
  // the record must make it a unit one again (instance_ray), as a placement that scales does —
  // the group's spheres are met by a test that takes unit directions.
  if (!keeps_lengths(map) || (outer != nullptr && !keeps_lengths(*outer))) mi.instance.translation_only = false;
  mi.lo = w.lo;
  mi.hi = w.hi;
  mi.stretch = x.stretch;
  mi.shift = x.shift;
  carry_bounds(map, mi.stretch, mi.shift);
  if (outer != nullptr) carry_bounds(*outer, mi.stretch, mi.shift);
  const Bounds swept = kernel::swept_bounds(mi);
  validate::coordinates(swept.lo, loc, "moving instance bounds");
  validate::coordinates(swept.hi, loc, "moving instance bounds");
  out.moving_instances.push_back(mi);
}

// Group g, its shapes all compiled, built with the structure `kind` and appended to out.groups
// (its box to out.group_bounds); returns its box.
Bounds push_group(RenderScene& out, RenderScene&& g, AccelKind kind) {
  g.bounded_solid_count = static_cast<std::uint32_t>(g.solids.size());
  g.accel = build_accel(kind, g.primitives());
  const Bounds b = bounds_of(g.primitives());
  out.groups.push_back(std::move(g));
  out.group_bounds.push_back(b);
  return b;
}

void check_invertible(const Mat3& m, const FileLoc& loc) {
  const Real det = m.determinant();
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) throw Error(loc, "the instance's transform is singular (it flattens the group)");
}

// What a group places: `inner`, an instance among group number `index`'s objects, which must
// place an earlier group (and may move: its motion's map, followed by the outer placements when
// an instance unfolds it).
RenderScene::GroupPlacement nested_placement(const Scene& scene, const RenderScene& out, std::uint32_t index,
                                             const Instance& inner) {
  const std::string& name = scene.groups[index].name;
  if (inner.group == index) throw Error(inner.loc, "group '" + name + "' places an instance of itself (a cycle)");
  if (inner.group >= scene.groups.size())
    throw Error(inner.loc, "instance of group number " + std::to_string(inner.group) + ", which the scene does not have");
  const std::string& placed = scene.groups[inner.group].name;
  if (inner.group > index)
    throw Error(inner.loc, "group '" + name + "' places '" + placed + "', which is defined after it (define '" + placed +
                               "' above '" + name + "')");
  validate::finite(inner.placement.translate, inner.loc, "instance translate");
  RenderScene::GroupPlacement p;
  p.group = inner.group;
  p.linear = inner.placement.linear();
  p.translate = inner.placement.translate;
  p.loc = inner.loc;
  check_invertible(p.linear, inner.loc);
  if (inner.motion.moving()) {
    p.moving = true;
    p.motion = moving_map(inner.motion, out.camera, inner.loc, "instance");
  }
  return p;
}

// What carries a record after its placement: nothing (map null), the motion A(u), or A(u) and
// then B(u) (outer).
struct Carried {
  const kernel::MovingMap* map = nullptr;
  const kernel::MovingMap* outer = nullptr;
};

// The instance record of group `group`'s own shapes placed by x ↦ m·x + t (moving as `by` says),
// with its world box.
void place(RenderScene& out, std::uint32_t group, const Mat3& m, const Vec3& t, Carried by, const FileLoc& loc) {
  check_invertible(m, loc);  // (a product of invertible maps may still round to a singular one)
  const Mat3 inv = m.inverse();
  kernel::Instance x;
  for (int i = 0; i < 3; ++i) x.to_object.row[i] = inv.row[i];
  x.to_object.translate = t;
  x.translation_only = identity(m);
  // The Frobenius norm bounds the map's largest stretch.
  x.stretch = kernel::frobenius(m.row);
  x.shift = max_abs_component(t);
  x.group = group;
  const Bounds& b = out.group_bounds[group];
  Bounds w;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
    w.extend(m * corner + t);
  }
  // Widened by a little more than the corners' rounding, so the box holds every transformed point.
  const Real pad = 1e-9 * std::fmax(max_abs_component(w.lo), max_abs_component(w.hi));
  w.lo = w.lo - Vec3(pad);
  w.hi = w.hi + Vec3(pad);
  validate::coordinates(w.lo, loc, "instance bounds");
  validate::coordinates(w.hi, loc, "instance bounds");
  if (by.map == nullptr) {
    out.instances.push_back(x);
    out.instance_bounds.push_back(w);
  } else {
    push_moving_instance(out, x, w, *by.map, by.outer, loc);
  }
}

// Does the map only translate (a velocity, keys that only translate, followed by a fixed map P:
// x ↦ P(x + d(u)), which is P(x) + P_linear·d(u) — so it moves every point by the same)?
bool translates_only(const kernel::MovingMap& map) {
  for (int i = 0; i < 3; ++i)
    if (!(map.linear0[i] == map.linear1[i])) return false;
  Mat3 linear;
  for (int i = 0; i < 3; ++i) linear.row[i] = map.linear0[i];
  return identity(linear) && map.angle == 0 && map.pivot == 0;
}

// Where such a map moves every point at shutter open (key 0) or close (key 1).
Vec3 displacement(const kernel::MovingMap& map, int key) {
  const Vec3 d = key == 0 ? map.translate0 : map.translate1;
  return map.post == 0 ? d : post_map(map).m * d;
}

// One placement of group `group` by x ↦ m·x + t, moving as `by` says after it (the instance at
// `loc`): the record of its own shapes (when it has any) and, in turn, those of the groups it
// places, each by the composed map m·(m'·x + t') + t — or, where the placement inside moves, by its
// own placement, carried by its motion A(u) and then by x ↦ m·x + t (A's post map), and then by
// what carries this placement: a motion that only translates adds its translation to A's; one that
// turns or scales follows A as B. A record has at most two motions that turn or scale.
void unfold(RenderScene& out, std::uint32_t group, const Mat3& m, const Vec3& t, Carried by, const FileLoc& loc) {
  const RenderScene::GroupNesting& nesting = out.group_nesting[group];
  if (nesting.own) place(out, group, m, t, by, loc);
  for (const RenderScene::GroupPlacement& p : nesting.places) {
    check_cancelled("build");
    if (!p.moving) {
      unfold(out, p.group, m * p.linear, m * p.translate + t, by, loc);
      continue;
    }
    const bool adds = by.map != nullptr && translates_only(*by.map);
    if (by.outer != nullptr && !adds)
      throw Error(loc, "this instance moves, and so does the object at " + p.loc.str() + " in group '" +
                           nesting.name + "', inside a placement that moves too: a placed object has at most two " +
                           "motions that turn or scale (let one of the three only translate)");
    // x ↦ m·x + t after the map's own post map P (a moving mesh's transform), if it has one; and
    // where the motion above is folded into this one (it only translates: x ↦ Q(x + d(u))), its
    // fixed map Q after both (its shift d(u) is added below).
    kernel::MovingMap moved = p.motion;
    Affine post{m, t};
    if (p.motion.post != 0) post = compose(post, post_map(p.motion));
    if (adds && by.map->post != 0) post = compose(post_map(*by.map), post);
    check_invertible(post.m, loc);
    set_post(moved, post);
    if (adds) {
      // The outer motion's translation d(u), taken inside the post map P: P(y) + d = P(y + P⁻¹·d),
      // and d(u) = lerp(d₀, d₁, u) as the map's own translation is.
      for (int key = 0; key < 2; ++key) {
        const Vec3 d = displacement(*by.map, key);
        const Vec3 inside = moved.post == 0 ? d
                                            : Vec3(dot(moved.post_inverse[0], d), dot(moved.post_inverse[1], d),
                                                   dot(moved.post_inverse[2], d));
        (key == 0 ? moved.translate0 : moved.translate1) += inside;
      }
    }
    // (adds: the outer map, if any, stays B; else the motion carrying this placement becomes B)
    unfold(out, p.group, p.linear, p.translate, Carried{&moved, adds ? by.outer : by.map}, loc);
  }
}

// Compiles `object` (which does not move) into g, group `name`'s shapes: only static, bounded
// shapes may be there.
void compile_group_object(RenderScene& out, RenderScene& g, const SceneObject& object, const std::string& name,
                          std::uint32_t object_id) {
  add_texture_warning(object, out);
  const std::uint32_t material_index = add_object_materials(object, out);
  // (A group keeps only its static shapes: whatever else an object compiles to is refused.)
  const auto placed = [&] { return g.instances.size() + g.moving_instances.size(); };
  const auto moving = [&] { return g.moving_spheres.size() + g.moving_triangles.size() + g.moving_solids.size(); };
  const std::size_t planes = g.planes.size(), solids = g.solids.size(), instances = placed(), moved = moving();
  object.compile_into(g, material_index, object_id);
  if (g.planes.size() != planes)
    throw Error(object.loc, "a plane cannot be part of group '" + name + "': it is unbounded (place it in objects)");
  if (!g.groups.empty() || placed() != instances || moving() != moved)  // (moving objects are taken apart)
    throw Error(object.loc, "group '" + name + "' holds an object that moves");
  for (std::size_t i = solids; i < g.solids.size(); ++i) {
    const kernel::Solid& k = g.solids[i];
    const bool unbounded = (k.kind == kernel::SolidKind::Quadric && !g.quadrics[k.index].clipped) ||
                           !finite(kernel::bounds(g.shapes(), k));
    if (unbounded)
      throw Error(object.loc, "an unbounded solid (an unclipped quadric, an inverse) cannot be part of group '" + name + "'");
  }
}

// A moving shape of group `name`: compiled still into `still` (a group of its own), and placed in
// its group by its motion's map — after its own placement, as at the top level, or, for a mesh,
// whose keys act in its own coordinates, before its transform (the map's post map). The group
// number is set once `still` is appended (compile_groups).
RenderScene::GroupPlacement moving_shape(RenderScene& out, RenderScene& still, const SceneObject& object,
                                         const std::string& name, std::uint32_t object_id) {
  std::unique_ptr<SceneObject> copy = copy_object(object);
  if (!copy) throw Error(object.loc, "objects of group '" + name + "' of this kind cannot move");
  copy->motion = Motion{};
  RenderScene::GroupPlacement p;
  p.group = kMovingShapeGroup;
  p.moving = true;
  p.loc = object.loc;
  validate_motion(object.motion, object.loc);
  if (auto* mesh = dynamic_cast<Mesh*>(copy.get())) {
    const Affine post = mesh_motion_post(mesh->transform, object.loc);
    mesh->transform = Transform{};
    p.motion = moving_map(object.motion, out.camera, object.loc, "mesh", &post);
  } else {
    const bool sphere = dynamic_cast<const Sphere*>(copy.get()) != nullptr;
    const bool triangle = dynamic_cast<const Triangle*>(copy.get()) != nullptr;
    p.motion = moving_map(object.motion, out.camera, object.loc, sphere ? "sphere" : triangle ? "triangle" : "solid");
  }
  compile_group_object(out, still, *copy, name, object_id);
  return p;
}

}  // namespace

void compile_groups(const Scene& scene, RenderScene& out) {
  // The scene's structure inside each group; Embree (no visitor traversal, float) gets the BVH.
  AccelKind kind = scene.settings.accel;
#if defined(STRAHL_HAVE_EMBREE)
  if (kind == AccelKind::Embree) {
    kind = AccelKind::Bvh;
    if (!scene.groups.empty())
      out.warnings.push_back(scene.settings.loc.str() + (scene.settings.loc.file.empty() ? "" : ": ") +
                             "accel embree: the groups of instances are built as bvh");
  }
#endif
  // A moving shape of a group: held still in a group of its own (appended after the scene's
  // groups, so their numbers stay the scene's) and placed in its group by a moving instance.
  struct MovingShape {
    std::size_t group, place;  // out.group_nesting[group].places[place] places it
    RenderScene still;
  };
  std::vector<MovingShape> moving_shapes;
  for (const ObjectGroup& group : scene.groups) {
    check_cancelled("build");
    if (group.objects.empty()) throw Error(group.loc, "group '" + group.name + "' has no objects");
    RenderScene g;
    g.camera = out.camera;
    std::uint32_t object_id = 0;
    const auto index = static_cast<std::uint32_t>(out.groups.size());
    RenderScene::GroupNesting nesting;
    nesting.name = group.name;
    for (const auto& object : group.objects) {
      if (const auto* inner = dynamic_cast<const Instance*>(object.get())) {
        nesting.places.push_back(nested_placement(scene, out, index, *inner));
        continue;
      }
      if (object->motion.moving()) {
        MovingShape shape{index, nesting.places.size(), {}};
        shape.still.camera = out.camera;
        nesting.places.push_back(moving_shape(out, shape.still, *object, group.name, object_id++));
        moving_shapes.push_back(std::move(shape));
        continue;
      }
      compile_group_object(out, g, *object, group.name, object_id++);
    }
    nesting.own = !g.spheres.empty() || !g.triangles.empty() || !g.solids.empty();  // (a group's solids are bounded)
    nesting.unfolded = nesting.own ? 1 : 0;
    for (const RenderScene::GroupPlacement& p : nesting.places)
      nesting.unfolded = std::min(nesting.unfolded + (p.group == kMovingShapeGroup ? 1 : out.group_nesting[p.group].unfolded),
                                  kMaxInstanceRecords + 1);
    push_group(out, std::move(g), kind);
    out.group_nesting.push_back(std::move(nesting));
  }
  for (MovingShape& shape : moving_shapes) {
    out.group_nesting[shape.group].places[shape.place].group = static_cast<std::uint32_t>(out.groups.size());
    push_group(out, std::move(shape.still), kind);
    RenderScene::GroupNesting still;
    still.placeable = false;  // (an instance names only the scene's groups)
    still.unfolded = 1;
    out.group_nesting.push_back(std::move(still));
  }
}

void Instance::compile_into(RenderScene& out, std::uint32_t, std::uint32_t) const {
  // (group_nesting: the scene's groups, then its groups' moving shapes'; out.groups may hold
  // turning shapes' after them)
  if (group >= out.group_nesting.size() || !out.group_nesting[group].placeable)
    throw Error(loc, "instance of group number " + std::to_string(group) + ", which the scene does not have");
  validate::finite(placement.translate, loc, "instance translate");
  const Mat3 m = placement.linear();
  check_invertible(m, loc);
  const std::uint64_t records = out.instances.size() + out.moving_instances.size() + out.group_nesting[group].unfolded;
  if (records > kMaxInstanceRecords) {
    const std::uint64_t unfolded = out.group_nesting[group].unfolded;
    throw Error(loc, "too many instances: this one unfolds into " +
                         (unfolded > kMaxInstanceRecords ? "more than " + std::to_string(kMaxInstanceRecords)
                                                         : std::to_string(unfolded)) +
                         " records through nested groups, and a scene holds at most " +
                         std::to_string(kMaxInstanceRecords));
  }
  if (!motion.moving()) {
    unfold(out, group, m, placement.translate, Carried{}, loc);
    return;
  }
  // Moving (geometry/moving_instance.h): every record carried by the motion's map after its
  // placement, in the motion BVH with the other moving shapes.
  const kernel::MovingMap map = moving_map(motion, out.camera, loc, "instance");
  unfold(out, group, m, placement.translate, Carried{&map, nullptr}, loc);
}

void move_by_instance(RenderScene& out, RenderScene&& group, const kernel::MovingMap& map, const FileLoc& loc) {
  kernel::Instance x;  // in place: the identity
  x.translation_only = true;
  x.group = static_cast<std::uint32_t>(out.groups.size());
  const Bounds b = push_group(out, std::move(group), AccelKind::Bvh);
  push_moving_instance(out, x, b, map, nullptr, loc);
}

void build_instance_bvh(RenderScene& out) {
  if (!out.instances.empty()) out.instance_bvh = build_index_tree(out.instance_bounds);
}

}  // namespace strahl
