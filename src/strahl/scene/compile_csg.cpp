// compile() for CSG trees (scene/csg.h): each operand is compiled as a solid of its own (so its
// values are checked as at the top level), its handle moved from the scene's solids into the
// tree's leaves, and the tree written as a postfix program (geometry/csg_program.h).

#include <algorithm>
#include <cmath>

#include "strahl/render/render_scene.h"
#include "strahl/scene/csg.h"
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

// The leaf with its box (geometry/solid_leaf.h, CsgLeaf) where a box test is cheaper than the
// leaf's own crossings and the box is finite: enlarged by a millionth of its coordinates' size, so
// that a crossing a leaf computes a little outside its exact box (a grazing ray's root) still
// lies inside it, and no ray's result changes.
kernel::CsgLeaf leaf_with_box(const kernel::Solid& handle, const Bounds& b) {
  kernel::CsgLeaf leaf;
  leaf.solid = handle;
  using kernel::SolidKind;
  const SolidKind kind = handle.kind;
  const bool costly = kind == SolidKind::Cone || kind == SolidKind::Torus || kind == SolidKind::Placed;
  const Real size = std::max(max_abs_component(b.lo), max_abs_component(b.hi));
  if (costly && std::isfinite(size)) {
    const Vec3 pad(Real(1e-6) * size);
    leaf.boxed = 1;
    leaf.box.lo = b.lo - pad;
    leaf.box.hi = b.hi + pad;
  }
  return leaf;
}

struct TreeBuilder {
  RenderScene& out;
  kernel::Csg& tree;
  std::uint32_t material;
  std::uint32_t object_id;

  void emit(kernel::CsgOp op, std::uint16_t arg = 0) { out.csg_code.push_back({op, 0, arg}); }

  // A solid operand: compiled alone, its handle taken out of the scene's solids.
  Bounds leaf(const SceneObject& o, const Csg& parent, const Affine* to_world) {
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
    kernel::Solid handle;
    if (const auto* s = dynamic_cast<const Sphere*>(&o)) {
      if (s->motion.moving()) throw Error(s->loc, "a sphere in a CSG cannot move");
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
    const Bounds b = kernel::bounds(out.shapes(), handle);
    out.csg_leaves.push_back(leaf_with_box(handle, b));
    emit(kernel::CsgOp::Leaf, std::uint16_t(tree.leaf_count++));
    return b;
  }

  Bounds operand(const SceneObject& o, const Csg& parent, int depth, const Affine* to_world) {
    if (const auto* c = dynamic_cast<const Csg*>(&o)) return node(*c, depth + 1, to_world);
    return leaf(o, parent, to_world);
  }

  // `outer`: the transforms of the nodes around this one (nullptr: none).
  Bounds node(const Csg& c, int depth, const Affine* outer) {
    const char* name = csg_operation_name(c.operation);
    if (depth > kMaxCsgDepth)
      throw Error(c.loc, std::string(name) + " is nested too deeply: CSG nodes may be nested at most " +
                             std::to_string(kMaxCsgDepth) + " levels deep");
    if (c.motion.moving()) throw Error(c.loc, std::string(name) + " cannot move (motion is for spheres, triangles and meshes)");
    if (c.children.empty()) throw Error(c.loc, std::string("empty ") + name + ": it needs at least one operand");
    if (c.operation == CsgOperation::Inverse && c.children.size() != 1)
      throw Error(c.loc, "inverse takes exactly one operand (got " + std::to_string(c.children.size()) + ")");
    Affine placed;
    const Affine* to_world = outer;
    if (c.placed()) {
      placed = outer ? compose(*outer, affine_of(c.placement)) : affine_of(c.placement);
      to_world = &placed;
    }
    Bounds b = operand(*c.children[0], c, depth, to_world);
    if (c.operation == CsgOperation::Inverse) {
      emit(kernel::CsgOp::Inverse);
      return infinite_bounds();
    }
    for (std::size_t i = 1; i < c.children.size(); ++i) {
      // Before an intersection's other operand: Skip over it and the step where the list so far
      // is empty (geometry/csg_program.h); its length is known once both are emitted.
      const bool intersects = c.operation == CsgOperation::Intersection || c.operation == CsgOperation::Difference;
      const std::size_t skip = out.csg_code.size();
      if (intersects) emit(kernel::CsgOp::Skip);
      const Bounds k = operand(*c.children[i], c, depth, to_world);
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
      if (intersects) out.csg_code[skip].arg = static_cast<std::uint16_t>(out.csg_code.size() - skip - 1);
    }
    return b;
  }
};

}  // namespace

void Csg::compile_into(RenderScene& out, std::uint32_t material_index, std::uint32_t object_id) const {
  kernel::Csg tree;
  tree.first_instruction = static_cast<std::uint32_t>(out.csg_code.size());
  tree.first_leaf = static_cast<std::uint32_t>(out.csg_leaves.size());
  TreeBuilder builder{out, tree, material_index, object_id};
  const Bounds b = builder.node(*this, 1, nullptr);
  tree.instruction_count = static_cast<std::uint32_t>(out.csg_code.size()) - tree.first_instruction;
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
}

}  // namespace strahl
