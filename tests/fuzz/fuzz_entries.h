#pragma once
// The loaders' fuzz entries, shared by the libFuzzer targets (tests/fuzz/fuzz_*.cpp) and the
// normal test suite (tests/fuzz_regression_test.cpp replays saved inputs through them).
// Each takes arbitrary bytes, loads them and compiles the result into a RenderScene (a scene file's
// also traces one camera sample). A strahl::Error is the expected answer to bad input; anything
// else (a crash, a sanitizer report, another exception escaping, a huge allocation) is a bug.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

#include "strahl/render/explain.h"
#include "strahl/render/pixel.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/scene_hash.h"
#include "strahl/scene/expression_ast.h"
#include "strahl/scene/expression_compiler.h"
#include "strahl/scene/file_materials.h"
#include "strahl/scene/gltf_loader.h"
#include "strahl/scene/mtl_loader.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/ply_loader.h"
#include "strahl/scene/pov/pov_scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "strahl/util/error.h"

namespace strahl::fuzz {

// Whether the input was accepted (compiled) or refused with a strahl::Error.
enum class Outcome { Accepted, Refused };

inline Outcome compile_scene(const Scene& scene) {
  // Resolutions up to 2^28 pixels are legal, but compile() only records them: nothing renders here.
  try {
    (void)compile(scene);
  } catch (const Error&) {
    return Outcome::Refused;
  }
  return Outcome::Accepted;
}

// A scene file's text; mesh paths resolve in a directory that does not exist. An accepted scene
// is also written (scene_to_yaml) and read back: the compiled scenes must be the same (scene_hash),
// as save_scene promises; a scene the writer refuses (a kind of object files do not have) is fine.
inline Outcome read_scene(const Scene& scene);

inline Outcome scene_input(const std::uint8_t* data, std::size_t size) {
  Scene scene;
  try {
    scene = parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml",
                        "/nonexistent-strahl-fuzz-dir");
  } catch (const Error&) {
    return Outcome::Refused;
  }
  return read_scene(scene);
}

// A POV-Ray scene's text (scene/pov/): translated and read as a scene file's, then the same
// checks; #include finds nothing (the directory does not exist). The loop, token and object
// bounds are lowered so that each input is read in bounded time.
inline Outcome pov_input(const std::uint8_t* data, std::size_t size) {
  Scene scene;
  try {
    PovOptions options;
    options.width = 32;
    options.height = 18;
    options.max_loop_iterations = 20'000;  // (bounded time: an input is not a hang for being large)
    options.max_tokens_read = 200'000;
    options.max_objects = 1'000;
    scene = parse_pov_scene(std::string(reinterpret_cast<const char*>(data), size),
                            "/nonexistent-strahl-fuzz-dir/fuzz.pov", options);
  } catch (const Error&) {
    return Outcome::Refused;
  }
  return read_scene(scene);
}

// An accepted scene: compiled, one sample traced, written and read back.
inline Outcome read_scene(const Scene& scene) {
  std::uint64_t hash = 0;
  RenderScene compiled;
  try {
    compiled = compile(scene);
    hash = scene_hash(compiled);
  } catch (const Error&) {
    return Outcome::Refused;
  }
  // One camera sample through the integrator, the centre pixel's: Whitted's with its ray tree
  // explained (render/explain.h), a path tracer's as rendered (it has no ray tree).
  const int x = compiled.camera.nx / 2, row = compiled.camera.ny / 2;
  const SceneView view = compiled.view();
  if (explain_refusal(view).empty()) {
    (void)explain_pixel(compiled, x, row);
  } else {
    CameraSample cs;
    RayCounters counters;
    (void)pixel_sample(view, pixel_sequence(view, make_pixel_sampler(compiled.sampling), x, row), 0, cs, counters);
  }
  // (A mesh is written to a file of its own beside the scene: no round trip in memory.)
  for (const auto& o : scene.objects())
    if (dynamic_cast<const Mesh*>(o.get())) return Outcome::Accepted;
  std::string text;
  try {
    text = scene_to_yaml(scene);
  } catch (const Error&) {
    return Outcome::Accepted;
  }
  // (Throws, which the fuzzer reports, where the text does not read back or compiles otherwise.)
  const Scene back = parse_scene(text, "fuzz-back.yaml", "/nonexistent-strahl-fuzz-dir");
  if (scene_hash(compile(back)) != hash)
    throw std::logic_error("the written scene reads back to another compiled scene:\n" + text);
  return Outcome::Accepted;
}

inline Outcome mesh_outcome(MeshData (*parse)(std::string_view, const std::string&), const char* name,
                            const std::uint8_t* data, std::size_t size) {
  Scene scene;
  try {
    MeshData mesh = parse(std::string_view(reinterpret_cast<const char*>(data), size), name);
    scene.add(Mesh(std::move(mesh), Material{}, Transform{}));
  } catch (const Error&) {
    return Outcome::Refused;
  }
  scene.settings.width = 4;
  scene.settings.height = 4;
  return compile_scene(scene);
}

// An OBJ file (also read with its materials, whose mtllib files are not found, and read as an
// MTL file: both must refuse or accept cleanly).
inline Outcome obj_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)parse_obj(text, "fuzz.obj", "/nonexistent-strahl-fuzz-dir");
  } catch (const Error&) {
  }
  try {
    (void)parse_mtl(text, "fuzz.mtl", "/nonexistent-strahl-fuzz-dir");
  } catch (const Error&) {
  }
  MeshData (*const plain)(std::string_view, const std::string&) = &parse_obj;
  return mesh_outcome(plain, "fuzz.obj", data, size);
}
inline Outcome ply_input(const std::uint8_t* data, std::size_t size) {
  return mesh_outcome(&parse_ply, "fuzz.ply", data, size);
}
// A .gltf's text or a .glb's bytes, read with its materials (their pictures decoded) and drawn in
// them; buffer and image files are looked for in a directory that does not exist. At most 2^20
// triangles (bounded memory and time: a few bytes of nodes can draw a mesh many times).
inline Outcome gltf_input(const std::uint8_t* data, std::size_t size) {
  Scene scene;
  try {
    MeshData mesh = parse_gltf(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.gltf",
                               "/nonexistent-strahl-fuzz-dir", true, std::uint64_t(1) << 20);
    use_file_materials(scene, scene.add(Mesh(std::move(mesh), Material{}, Transform{})));
  } catch (const Error&) {
    return Outcome::Refused;
  }
  scene.settings.width = 4;
  scene.settings.height = 4;
  return compile_scene(scene);
}

// ---- the expression compiler and evaluator (implicit surfaces) ----

// The parse tree evaluated directly, node by node, with the kernel's operations: what the folded,
// reordered postfix program must reproduce bit for bit.
inline bool reads_coordinates(const expression::Tree& t, int i) {
  const expression::Node& n = t.nodes[std::size_t(i)];
  if (n.op == kernel::Op::X || n.op == kernel::Op::Y || n.op == kernel::Op::Z) return true;
  for (int k = 0; k < kernel::op_arity(n.op); ++k)
    if (reads_coordinates(t, n.child[k])) return true;
  return false;
}

inline Real walk(const expression::Tree& t, int i, const Vec3& p) {
  using kernel::Op;
  const expression::Node& n = t.nodes[std::size_t(i)];
  switch (n.op) {
    case Op::X: return p.x;
    case Op::Y: return p.y;
    case Op::Z: return p.z;
    case Op::Const: return n.value;
    case Op::Clamp: return kernel::apply_clamp(walk(t, n.child[0], p), walk(t, n.child[1], p), walk(t, n.child[2], p));
    case Op::Pow: {
      const Real base = walk(t, n.child[0], p), e = walk(t, n.child[1], p);
      if (!reads_coordinates(t, n.child[1]) && (e == 2 || e == 3)) return e == 2 ? base * base : base * base * base;
      return std::pow(base, e);
    }
    default: break;
  }
  if (kernel::op_arity(n.op) == 1) return kernel::apply_unary(n.op, walk(t, n.child[0], p));
  return kernel::apply_binary(n.op, walk(t, n.child[0], p), walk(t, n.child[1], p));
}

// The program's own bounds, checked by simulating its stack (evaluate() trusts them).
inline void check_program(const kernel::Expression& e) {
  if (e.length < 1 || e.length > kernel::kMaxExpressionLength) throw std::logic_error("program length out of bounds");
  if (e.constant_count > kernel::kMaxExpressionConstants) throw std::logic_error("too many constants");
  int depth = 0, deepest = 0;
  for (int i = 0; i < e.length; ++i) {
    const kernel::Instruction in = e.code[i];
    if (in.op == kernel::Op::Const && in.arg >= e.constant_count) throw std::logic_error("constant index out of range");
    const int arity = kernel::op_arity(in.op);
    if (depth < arity) throw std::logic_error("stack underflow");
    depth += arity == 0 ? 1 : 1 - arity;
    deepest = depth > deepest ? depth : deepest;
  }
  if (depth != 1 || deepest != e.stack_depth || deepest > kernel::kMaxExpressionStack)
    throw std::logic_error("stack depth differs from the program's claim");
}

// An expression's text: compiled with two parameters (a, b); when accepted, the program must keep
// its bounds and agree with the parse tree at a few points, some extreme.
inline Outcome expression_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const ExpressionParameters parameters = {{"a", 1.5}, {"b", -2}};
  kernel::Expression e;
  try {
    e = compile_expression(text, parameters);
  } catch (const Error&) {
    return Outcome::Refused;
  }
  check_program(e);
  const expression::Tree tree = expression::parse(text, parameters);
  const Vec3 points[] = {Vec3(0), Vec3(1, -2, 0.5), Vec3(-0.0, 1e-300, -1e300), Vec3(3.25, 7, -11)};
  for (const Vec3& p : points) {
    const Real got = kernel::evaluate(e, p), want = walk(tree, tree.root, p);
    if (!(std::isnan(got) && std::isnan(want)) && std::memcmp(&got, &want, sizeof got) != 0)
      throw std::logic_error("compiled program and parse tree disagree");
  }
  return Outcome::Accepted;
}

}  // namespace strahl::fuzz
