// compile() for CSG trees (scene/csg.h): each operand is compiled as a solid of its own (so its
// values are checked as at the top level), its handle moved from the scene's solids into the
// tree's leaves, and the tree written as a postfix program (geometry/csg_program.h).

#include <algorithm>
#include <cmath>

#include "strahl/render/render_scene.h"
#include "strahl/scene/csg.h"
#include "strahl/scene/move_solid.h"
#include "strahl/scene/place_solid.h"
#include "strahl/scene/solids.h"
#include "strahl/scene/validate.h"

namespace strahl {

const char* csg_operation_name(CsgOperation op) {
  switch (op) {
    case CsgOperation::Union: return "union";
    case CsgOperation::Intersection: return "intersection";
    case CsgOperation::Difference: return "difference";
    case CsgOperation::Merge: return "merge";
    case CsgOperation::Inverse: return "inverse";
  }
  return "csg";
}

namespace {

Bounds infinite_bounds() {
  Bounds b;
  b.extend(Vec3(-kInfinity));
  b.extend(Vec3(kInfinity));
  return b;
}

// A leaf's bounds enlarged by a millionth of its coordinates' size, so that a crossing a leaf
// computes a little outside its exact box (a grazing ray's root) still lies inside it, and no
// ray's result changes; false where the bounds are not finite.
bool padded(const Bounds& b, Bounds& box) {
  const Real size = std::max(max_abs_component(b.lo), max_abs_component(b.hi));
  if (!std::isfinite(size)) return false;
  const Vec3 pad(Real(1e-6) * size);
  box.lo = b.lo - pad;
  box.hi = b.hi + pad;
  return true;
}

// The leaf with its box (geometry/solid_leaf.h, CsgLeaf) where a box test is cheaper than the
// leaf's own crossings and the box is finite.
kernel::CsgLeaf leaf_with_box(const kernel::Solid& handle, const Bounds& b) {
  kernel::CsgLeaf leaf;
  leaf.solid = handle;
  using kernel::SolidKind;
  const SolidKind kind = handle.kind;
  const bool costly = kind == SolidKind::Cone || kind == SolidKind::Torus || kind == SolidKind::Placed;
  if (costly && padded(b, leaf.box)) leaf.boxed = 1;
  return leaf;
}

// Groups of a node's steps (geometry/csg_program.h): at least this many steps to a group.
constexpr std::size_t kMinCsgGroup = 4;

// What an operand's compilation gives: the bounds of its set (for the tree's bounds) and, where a
// ray's range that misses a box finds the operand's list plain outside (no crossing, outside all
// along), that box: a leaf with a finite box that is a sphere, a box or boxed (CsgLeaf), or a
// node whose operands all have one and that is no `inverse` (union, merge, intersection and
// difference of operands outside everywhere are outside everywhere).
struct Operand {
  Bounds bounds;
  bool boxed = false;
  Bounds box;
};

struct TreeBuilder {
  RenderScene& out;
  kernel::Csg& tree;
  std::uint32_t material;
  std::uint32_t object_id;

  // The boxes of groups of steps and of node operands, numbered from kMaxCsgLeaves in the Skips
  // until compile_into appends them to the tree's leaves (a leaf's index is its position among
  // the leaves, known only as they are compiled).
  std::vector<Bounds> group_boxes;

  void emit(kernel::CsgOp op, std::uint16_t arg = 0, kernel::CsgRun run = kernel::CsgRun::Intersection,
            std::uint32_t box = kernel::kNoCsgBox) {
    out.csg_code.push_back({op, run, arg, box});
  }

  // One step of a node: its code and its operand (with a box, it may join a group).
  struct Step {
    std::vector<kernel::CsgInstruction> code;
    Operand operand;
  };

  std::uint32_t group_box(const Bounds& box) {
    group_boxes.push_back(box);
    return std::uint32_t(kernel::kMaxCsgLeaves + group_boxes.size() - 1);
  }

  // Emits steps [lo, hi) of a node, under nested group Skips where there are enough of them: each
  // group's box holds its steps' boxes, split where the two halves' boxes have the least surface
  // area for their steps (as a BVH's SAH does; the steps keep their order).
  void emit_steps(const std::vector<Step>& steps, std::size_t lo, std::size_t hi, kernel::CsgRun run) {
    if (hi - lo < kMinCsgGroup) {
      for (std::size_t k = lo; k < hi; ++k) out.csg_code.insert(out.csg_code.end(), steps[k].code.begin(), steps[k].code.end());
      return;
    }
    Bounds all;
    for (std::size_t k = lo; k < hi; ++k) all = merge(all, steps[k].operand.box);
    std::size_t split = lo + 1;
    Real best = kInfinity;
    for (std::size_t s = lo + 1; s < hi; ++s) {
      Bounds left, right;
      for (std::size_t k = lo; k < s; ++k) left = merge(left, steps[k].operand.box);
      for (std::size_t k = s; k < hi; ++k) right = merge(right, steps[k].operand.box);
      const Real cost = surface_area(left) * Real(s - lo) + surface_area(right) * Real(hi - s);
      if (cost < best) {
        best = cost;
        split = s;
      }
    }
    const std::size_t skip = out.csg_code.size();
    emit(kernel::CsgOp::Skip, 0, run, group_box(all));
    emit_steps(steps, lo, split, run);
    emit_steps(steps, split, hi, run);
    out.csg_code[skip].arg = static_cast<std::uint16_t>(out.csg_code.size() - skip - 1);
  }

  // A solid operand: compiled alone, its handle taken out of the scene's solids.
  Operand leaf(const SceneObject& o, const Csg& parent, const Affine* to_world) {
    const char* refusal = nullptr;
    if (dynamic_cast<const Plane*>(&o)) refusal = "a plane";
    else if (dynamic_cast<const Triangle*>(&o)) refusal = "a triangle";
    else if (dynamic_cast<const Mesh*>(&o)) refusal = "a mesh";
    else if (dynamic_cast<const Disk*>(&o)) refusal = "a disk";
    if (refusal)
      throw Error(o.loc.file.empty() ? parent.loc : o.loc,
                  std::string(refusal) + " cannot be an operand of " + csg_operation_name(parent.operation) +
                      " (operands are closed solids: box, cylinder, cone, torus, unclipped quadric, implicit, "
                      "sphere, or CSG)");
    if (tree.leaf_count >= std::uint32_t(kernel::kMaxCsgLeaves))
      throw Error(o.loc, "CSG tree has more than " + std::to_string(kernel::kMaxCsgLeaves) + " solids");
    if (o.motion.moving())
      throw Error(o.loc.file.empty() ? parent.loc : o.loc,
                  "an operand of " + std::string(csg_operation_name(parent.operation)) +
                      " cannot move on its own (give the motion to the outermost CSG node)");
    kernel::Solid handle;
    if (const auto* s = dynamic_cast<const Sphere*>(&o)) {
      validate::coordinates(s->center, s->loc, "sphere center");
      validate::positive(s->radius, s->loc, "sphere radius");
      validate::length(s->radius, s->loc, "sphere radius");
      validate::resolvable(s->radius, max_abs_component(s->center), s->loc, "sphere radius");
      out.solid_spheres.push_back({s->center, s->radius, material});
      handle = {kernel::SolidKind::Sphere, std::uint32_t(out.solid_spheres.size() - 1), material};
      if (s->placed()) {
        out.solids.push_back(handle);
        place_last_solid(out, affine_of(s->placement), s->loc);
        handle = out.solids.back();
        out.solids.pop_back();
      }
    } else {
      const std::size_t before = out.solids.size();
      o.compile_into(out, material, object_id);
      if (out.solids.size() != before + 1) throw Error(o.loc, "internal: a CSG operand compiled to no solid");
      handle = out.solids.back();
      out.solids.pop_back();
      if (!kernel::closed(out.shapes(), handle)) {
        const char* what = handle.kind == kernel::SolidKind::Cone ? "an open cylinder or cone"
                                                                  : "a quadric clipped by a box";
        throw Error(o.loc, std::string(what) + " has no inside: it cannot be an operand of " +
                               csg_operation_name(parent.operation) + " (remove `open` or `clipped_by`)");
      }
    }
    if (to_world) {  // the enclosing CSG nodes' transforms, after the operand's own
      out.solids.push_back(handle);
      place_last_solid(out, *to_world, parent.loc);
      handle = out.solids.back();
      out.solids.pop_back();
    }
    Operand result;
    result.bounds = kernel::bounds(out.shapes(), handle);
    const kernel::CsgLeaf leaf = leaf_with_box(handle, result.bounds);
    out.csg_leaves.push_back(leaf);
    emit(kernel::CsgOp::Leaf, std::uint16_t(tree.leaf_count++));
    const kernel::SolidKind kind = handle.kind;
    result.box = leaf.box;
    result.boxed = leaf.boxed || ((kind == kernel::SolidKind::Sphere || kind == kernel::SolidKind::Box) &&
                                  padded(result.bounds, result.box));
    return result;
  }

  Operand operand(const SceneObject& o, const Csg& parent, int depth, const Affine* to_world) {
    if (const auto* c = dynamic_cast<const Csg*>(&o)) return node(*c, depth + 1, to_world);
    return leaf(o, parent, to_world);
  }

  // `outer`: the transforms of the nodes around this one (nullptr: none).
  Operand node(const Csg& c, int depth, const Affine* outer) {
    const char* name = csg_operation_name(c.operation);
    if (depth > kMaxCsgDepth)
      throw Error(c.loc, std::string(name) + " is nested too deeply: CSG nodes may be nested at most " +
                             std::to_string(kMaxCsgDepth) + " levels deep");
    if (depth > 1 && c.motion.moving())
      throw Error(c.loc, "an operand of a CSG cannot move on its own (give the motion to the outermost CSG node)");
    if (c.children.empty()) throw Error(c.loc, std::string("empty ") + name + ": it needs at least one operand");
    if (c.operation == CsgOperation::Inverse && c.children.size() != 1)
      throw Error(c.loc, "inverse takes exactly one operand (got " + std::to_string(c.children.size()) + ")");
    Affine placed;
    const Affine* to_world = outer;
    if (c.placed()) {
      placed = outer ? compose(*outer, affine_of(c.placement)) : affine_of(c.placement);
      to_world = &placed;
    }
    Operand result = operand(*c.children[0], c, depth, to_world);
    Bounds& b = result.bounds;
    if (c.operation == CsgOperation::Inverse) {
      emit(kernel::CsgOp::Inverse);
      return {infinite_bounds(), false, {}};
    }
    const bool intersects = c.operation == CsgOperation::Intersection || c.operation == CsgOperation::Difference;
    const kernel::CsgRun run = c.operation == CsgOperation::Intersection ? kernel::CsgRun::Intersection
                               : c.operation == CsgOperation::Difference ? kernel::CsgRun::Difference
                                                                          : kernel::CsgRun::Union;
    std::vector<Step> steps;
    const std::size_t steps_begin = out.csg_code.size();
    for (std::size_t i = 1; i < c.children.size(); ++i) {
      // Before an intersection's other operand: Skip over it and the step where the list so far
      // is empty or where the ray misses the operand's box (geometry/csg_program.h): a boxed
      // leaf's own, a node's in an entry of its own; its length is known once both are emitted.
      const std::size_t begin = out.csg_code.size();
      if (intersects) emit(kernel::CsgOp::Skip, 0, run);
      Step step;
      step.operand = operand(*c.children[i], c, depth, to_world);
      const Bounds& k = step.operand.bounds;
      if (intersects && dynamic_cast<const Csg*>(c.children[i].get())) {
        if (step.operand.boxed) out.csg_code[begin].box = group_box(step.operand.box);
      } else if (intersects && out.csg_leaves.back().boxed) {
        out.csg_code[begin].box = tree.leaf_count - 1;
      }
      result.boxed = result.boxed && step.operand.boxed;
      result.box = merge(result.box, step.operand.box);
      switch (c.operation) {
        case CsgOperation::Union:
        case CsgOperation::Merge:
          emit(c.operation == CsgOperation::Union ? kernel::CsgOp::Union : kernel::CsgOp::Merge);
          b.extend(k.lo);
          b.extend(k.hi);
          break;
        case CsgOperation::Intersection:
          emit(kernel::CsgOp::Intersection);
          b.lo = max(b.lo, k.lo);
          b.hi = min(b.hi, k.hi);
          break;
        case CsgOperation::Difference:  // A ∩ inverse(B): within A's bounds
          emit(kernel::CsgOp::Inverse);
          emit(kernel::CsgOp::Intersection);
          break;
        case CsgOperation::Inverse: break;
      }
      if (intersects) out.csg_code[begin].arg = static_cast<std::uint16_t>(out.csg_code.size() - begin - 1);
      step.code.assign(out.csg_code.begin() + std::ptrdiff_t(begin), out.csg_code.end());
      steps.push_back(std::move(step));
    }
    // The steps again, runs of enough grouped ones under group Skips.
    out.csg_code.resize(steps_begin);
    for (std::size_t lo = 0; lo < steps.size();) {
      std::size_t hi = lo + 1;
      if (steps[lo].operand.boxed)
        while (hi < steps.size() && steps[hi].operand.boxed) ++hi;
      emit_steps(steps, lo, hi, run);
      lo = hi;
    }
    return result;
  }
};

}  // namespace

void Csg::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const {
  kernel::Csg tree;
  tree.first_instruction = static_cast<std::uint32_t>(out.csg_code.size());
  tree.first_leaf = static_cast<std::uint32_t>(out.csg_leaves.size());
  TreeBuilder builder{out, tree, material_index, object_id, {}};
  const Bounds b = builder.node(*this, 1, nullptr).bounds;
  tree.instruction_count = static_cast<std::uint32_t>(out.csg_code.size()) - tree.first_instruction;
  // The groups' boxes after the leaves (entries that no Leaf instruction runs).
  for (std::uint32_t i = tree.first_instruction; i < out.csg_code.size(); ++i) {
    std::uint32_t& box = out.csg_code[i].box;
    if (out.csg_code[i].op == kernel::CsgOp::Skip && box != kernel::kNoCsgBox && box >= std::uint32_t(kernel::kMaxCsgLeaves))
      box = box - std::uint32_t(kernel::kMaxCsgLeaves) + tree.leaf_count;
  }
  for (const Bounds& group : builder.group_boxes) {
    kernel::CsgLeaf entry;
    entry.boxed = 1;
    entry.box = group;
    out.csg_leaves.push_back(entry);
  }
  if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)) {
    // An intersection of operands whose bounds do not overlap: nothing to render.
    out.warnings.push_back(loc.str() + (loc.file.empty() ? "" : ": ") + csg_operation_name(operation) +
                           " is empty (its operands do not overlap): it is not rendered");
    return;
  }
  tree.lo = b.lo;
  tree.hi = b.hi;
  out.csgs.push_back(tree);
  out.solids.push_back({kernel::SolidKind::Csg, static_cast<std::uint32_t>(out.csgs.size() - 1), material_index});
  if (motion.moving()) move_last_solid(out, motion, loc);
}

}  // namespace strahl
