// The POV-Ray importer's objects (pov_parser.h): shapes, CSG, meshes (mesh, mesh2,
// smooth_triangle), isosurfaces, and their modifiers (transforms, textures, flags).

#include "strahl/scene/pov/pov_parser.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace strahl::pov {
namespace {

// The functions of strahl's expression language that a POV-Ray function may use as they are.
bool is_function_name(const std::string& n) {
  static const std::set<std::string> kNames = {"sin", "cos", "tan", "asin", "acos", "atan", "exp", "log", "sqrt",
                                               "abs", "floor", "atan2", "pow", "mod", "min", "max"};
  return kNames.count(n) > 0;
}

// Whether a mesh's smooth_triangle has one normal at its three corners (their unit vectors within
// POV-Ray's EPSILON, 1e-10, in squared distance): POV-Ray draws such a triangle flat.
bool equal_normals(const std::array<Vector, 3>& n) {
  std::array<Vector, 3> u{};
  for (std::size_t i = 0; i < 3; ++i) {
    const double l = length(n[i]);
    u[i] = l > 0 ? Vector{n[i][0] / l, n[i][1] / l, n[i][2] / l} : n[i];
  }
  const Vector d1 = minus(u[0], u[1]), d2 = minus(u[0], u[2]);
  return dot(d1, d1) <= 1e-10 && dot(d2, d2) <= 1e-10;
}

}  // namespace

bool is_shape(const std::string& keyword) {
  static const std::set<std::string> kShapes = {"sphere",   "plane", "box",  "cylinder", "cone",  "torus",
                                                "disc",     "triangle", "smooth_triangle", "mesh", "mesh2",
                                                "isosurface", "quadric", "union", "intersection", "difference",
                                                "merge",    "object"};
  return kShapes.count(keyword) > 0;
}

Object Parser::object(const Token& kw) {
  const Nesting nest(*this, kw);
  Object o;
  o.loc = loc(kw);
  expect_symbol("{", ("after " + kw.text).c_str());
  const std::string& n = kw.text;
  if (n == "object") {
    const Token t = next();
    if (is_shape(t.text)) {
      o = object(t);
    } else {
      const auto it = symbols_.find(t.text);
      if (t.kind != TokenKind::Identifier || it == symbols_.end() || it->second.kind != Value::Kind::Object)
        throw Error(loc(t), "object { … } needs a declared object or a shape, found " + describe(t));
      o = *it->second.object;
    }
    o.loc = loc(kw);
  } else if (n == "sphere") {
    o.type = "sphere";
    const Vector c = vector();
    expect_symbol(",", "after the sphere's centre");
    o.keys = ", center: " + yaml_vector(c) + ", radius: " + yaml_number(real());
  } else if (n == "plane") {
    o.type = "plane";
    const Vector v = vector();
    expect_symbol(",", "after the plane's normal");
    const double d = real(), l = length(v);
    o.keys = ", normal: " + yaml_vector(l > 0 ? Vector{v[0] / l, v[1] / l, v[2] / l} : v) + ", distance: " + yaml_number(d);
  } else if (n == "box") {
    o.type = "box";
    const Vector a = vector();
    expect_symbol(",", "after the box's first corner");
    o.keys = ", corners: [" + yaml_vector(a) + ", " + yaml_vector(vector()) + "]";
  } else if (n == "cylinder" || n == "cone") {
    o.type = n;
    const Vector base = vector();
    expect_symbol(",", "after the base");
    std::string base_radius;
    if (n == "cone") {
      base_radius = yaml_number(real());
      expect_symbol(",", "after the base radius");
    }
    const Vector cap = vector();
    expect_symbol(",", "after the cap");
    const double r = real();
    o.keys = ", base: " + yaml_vector(base) + ", cap: " + yaml_vector(cap) +
             (n == "cone" ? ", base_radius: " + base_radius + ", cap_radius: " + yaml_number(r) : ", radius: " + yaml_number(r));
  } else if (n == "torus") {
    o.type = "torus";
    const double major = real();
    expect_symbol(",", "after the torus's major radius");
    o.keys = ", center: [0, 0, 0], major_radius: " + yaml_number(major) + ", minor_radius: " + yaml_number(real());
  } else if (n == "disc") {
    o.type = "disk";
    const Vector c = vector();
    expect_symbol(",", "after the disc's centre");
    const Vector nn = vector();
    expect_symbol(",", "after the disc's normal");
    o.keys = ", center: " + yaml_vector(c) + ", normal: " + yaml_vector(nn) + ", radius: " + yaml_number(real());
    if (accept_symbol(",") && real() != 0) throw Error(loc(kw), "a disc with a hole is not supported by strahl's POV-Ray importer");
  } else if (n == "triangle") {
    o.type = "triangle";
    const Vector a = vector();
    expect_symbol(",", "after a vertex");
    const Vector b = vector();
    expect_symbol(",", "after a vertex");
    o.keys = ", vertices: [" + yaml_vector(a) + ", " + yaml_vector(b) + ", " + yaml_vector(vector()) + "]";
  } else if (n == "quadric") {
    // quadric { <A, B, C>, <D, E, F>, <G, H, I>, J }: strahl's ten coefficients in this order.
    o.type = "quadric";
    std::string c;
    for (int i = 0; i < 3; ++i) {
      const Vector v = vector();
      expect_symbol(",", "after the quadric's coefficients");
      c += yaml_number(v[0]) + ", " + yaml_number(v[1]) + ", " + yaml_number(v[2]) + ", ";
    }
    o.keys = ", coefficients: [" + c + yaml_number(real()) + "]";
  } else if (n == "smooth_triangle" || n == "mesh" || n == "mesh2") {
    o = mesh(kw);
  } else if (n == "isosurface") {
    o = isosurface(kw);
  } else {  // union, intersection, difference, merge
    o.type = n;
    for (;;) {
      const Token t = peek();
      if (is_macro(t)) call_macro(next());  // (its objects are operands)
      else if (t.kind == TokenKind::Identifier && is_shape(t.text)) o.children.push_back(object(next()));
      else break;
    }
    if (o.children.empty()) throw Error(loc(kw), n + " needs at least one object");
  }
  modifiers(o, kw.text);
  return o;
}

// What follows a shape's own values: transforms, textures, flags, to the closing '}'.
void Parser::modifiers(Object& o, const std::string& what) {
  while (!accept_symbol("}")) {
    const Token t = next();
    const std::string& n = t.text;
    if (t.kind == TokenKind::End) throw Error(o.loc, "this " + what + " is never closed (the file ends before its '}')");
    if (t.kind != TokenKind::Identifier) throw Error(loc(t), "expected a modifier of " + what + " or '}', found " + describe(t));
    if (n == "translate") o.steps.push_back("{translate: " + yaml_vector(vector()) + "}");
    else if (n == "rotate") o.steps.push_back("{rotate: " + yaml_vector(vector()) + "}");
    else if (n == "scale") o.steps.push_back("{scale: " + yaml_vector(vector()) + "}");
    else if (n == "matrix") o.steps.push_back(matrix_step());
    else if (n == "inverse") o.inverse = !o.inverse;
    else if (n == "open") {
      if (o.type != "cylinder" && o.type != "cone") unsupported(t, what);
      if (o.keys.find(", open: true") == std::string::npos) o.keys += ", open: true";
    } else if (n == "sturm" || n == "hollow" || n == "smooth") {
      if (n == "hollow" && starts_value(peek())) real();
    } else if (n == "no_shadow" || n == "no_reflection" || n == "no_image" || n == "double_illuminate") {
      warn(loc(t), n + " is left out");
    } else if (n == "clipped_by" && o.type == "quadric") {
      expect_symbol("{", "after clipped_by");
      const Token box = next();
      if (!is_word(box, "box")) throw Error(loc(box), "strahl clips a quadric by a box only, found " + describe(box));
      expect_symbol("{", "after box");
      const Vector a = vector();
      expect_symbol(",", "after the box's first corner");
      o.keys += ", clipped_by: {type: box, corners: [" + yaml_vector(a) + ", " + yaml_vector(vector()) + "]}";
      expect_symbol("}", "to close the box");
      expect_symbol("}", "to close clipped_by");
    } else if (n == "photons" || n == "bounded_by") {
      warn(loc(t), n + " { … } is left out");
      skip_block();
    } else if (n == "pigment" || n == "finish" || n == "interior" || n == "texture" || n == "normal") {
      if (!o.texture.given()) o.texture = out_.default_texture, o.texture.has_pigment = o.texture.has_finish = false;
      if (n == "pigment" || n == "texture") o.texture_steps = o.steps.size();  // later transforms move it
      texture_item(t, o.texture);
    } else if (const auto it = symbols_.find(n); it != symbols_.end() && it->second.kind == Value::Kind::Texture) {
      o.texture = it->second.texture;
      o.texture_steps = o.steps.size();
    } else {
      unsupported(t, what);
    }
  }
}

// matrix <a, b, c, d, e, f, g, h, i, j, k, l>: POV-Ray's rows act on row vectors,
// p' = (x, y, z, 1) · M; strahl's matrix acts on columns: its rows are M's columns.
std::string Parser::matrix_step() {
  expect_symbol("<", "after matrix");
  std::array<double, 12> m{};
  ++in_vector_;
  for (std::size_t i = 0; i < 12; ++i) {
    if (i > 0) expect_symbol(",", "between matrix entries");
    m[i] = real();
  }
  --in_vector_;
  expect_symbol(">", "to close the matrix (12 numbers)");
  std::string s = "{matrix: [";
  for (std::size_t r = 0; r < 3; ++r)
    s += std::string(r ? ", " : "") + "[" + yaml_number(m[r]) + ", " + yaml_number(m[3 + r]) + ", " + yaml_number(m[6 + r]) + ", " + yaml_number(m[9 + r]) + "]";
  return s + "]}";
}

Object Parser::mesh(const Token& kw) {
  Object o;
  o.type = "mesh";
  o.loc = loc(kw);
  MeshData data;
  const bool in_mesh = kw.text == "mesh";
  auto add_triangle = [&](const Token& t, bool smooth) {
    std::array<Vector, 3> v{}, nn{};
    for (std::size_t i = 0; i < 3; ++i) {
      if (i > 0) expect_symbol(",", "between a triangle's vertices");
      v[i] = vector();
      if (smooth) {
        expect_symbol(",", "after a vertex");
        nn[i] = vector();
      }
    }
    (void)t;
    if (smooth && in_mesh && equal_normals(nn)) smooth = false;
    MeshData::Face f;
    for (std::size_t i = 0; i < 3; ++i) {
      f.v[i] = std::uint32_t(data.positions.size());
      data.positions.push_back(Vec3(v[i][0], v[i][1], v[i][2]));
      if (smooth) {
        f.n[i] = std::int32_t(data.normals.size());
        data.normals.push_back(Vec3(nn[i][0], nn[i][1], nn[i][2]));
      }
    }
    data.faces.push_back(f);
  };
  if (kw.text == "smooth_triangle") {
    add_triangle(kw, true);
  } else if (kw.text == "mesh") {
    while (is_word(peek(), "triangle") || is_word(peek(), "smooth_triangle")) {
      const Token t = next();
      expect_symbol("{", ("after " + t.text).c_str());
      add_triangle(t, t.text == "smooth_triangle");
      while (!accept_symbol("}")) {
        const Token x = next();
        if (x.text == "texture") {
          warn(loc(x), "a mesh triangle's own texture is left out");
          skip_block();
        } else if (x.text == "uv_vectors") {
          triangle_uvs(data);
        } else unsupported(x, t.text);
      }
    }
    zero_missing_uvs(data);
  } else {
    mesh2(kw, data);
  }
  if (data.faces.empty()) throw Error(loc(kw), kw.text + " has no triangles");
  o.mesh = int(out_.meshes.size());
  out_.meshes.push_back(std::move(data));
  return o;
}

// uv_vectors <a>, <b>, <c> of a mesh's triangle (its last face): its corners' UVs.
void Parser::triangle_uvs(MeshData& data) {
  MeshData::Face& f = data.faces.back();
  for (std::size_t i = 0; i < 3; ++i) {
    if (i > 0) expect_symbol(",", "between a triangle's uv_vectors");
    f.t[i] = std::int32_t(data.texcoords.size());
    data.texcoords.push_back(uv_vector());
  }
}

// A mesh's triangles without uv_vectors, where others have them, are at <0, 0> (POV-Ray's UVs there).
void Parser::zero_missing_uvs(MeshData& data) {
  if (data.texcoords.empty()) return;
  const auto zero = std::int32_t(data.texcoords.size());
  bool used = false;
  for (MeshData::Face& f : data.faces)
    if (f.t[0] < 0) f.t = {zero, zero, zero}, used = true;
  if (used) data.texcoords.push_back(Texcoord{});
}

// A UV: <u, v> (a float is <f, f>).
Texcoord Parser::uv_vector() {
  const Num n = expression();
  return Texcoord{Real(n.c[0]), Real(n.dim == 1 ? n.c[0] : n.c[1])};
}

// mesh2's UVs of its faces: uv_indices, or without them face_indices (POV-Ray's rule).
void Parser::mesh2_uvs(MeshData& data, const std::vector<std::array<std::int64_t, 3>>& uv_faces,
                       const FileLoc& uv_where, const FileLoc& faces_where) {
  if (data.texcoords.empty()) {
    if (!uv_faces.empty()) throw Error(uv_where, "uv_indices without uv_vectors");
    return;
  }
  if (!uv_faces.empty() && uv_faces.size() != data.faces.size())
    throw Error(uv_where, "uv_indices needs one entry per face (" + std::to_string(uv_faces.size()) + " for " +
                              std::to_string(data.faces.size()) + " faces)");
  for (std::size_t i = 0; i < data.faces.size(); ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const std::int64_t k = uv_faces.empty() ? std::int64_t(data.faces[i].v[j]) : uv_faces[i][j];
      if (std::size_t(k) >= data.texcoords.size())
        throw Error(uv_faces.empty() ? faces_where : uv_where,
                    std::string(uv_faces.empty() ? "face_indices" : "uv_indices") + ": index " + std::to_string(k) +
                        " is past the uv_vectors (" + std::to_string(data.texcoords.size()) + ")" +
                        (uv_faces.empty() ? "; without uv_indices the face indices index the uv_vectors" : ""));
      data.faces[i].t[j] = std::int32_t(k);
    }
}

void Parser::mesh2(const Token& kw, MeshData& data) {
  std::vector<std::array<std::int64_t, 3>> normal_faces, uv_faces;
  FileLoc uv_where = loc(kw), faces_where = loc(kw);
  auto count = [&](const char* what) {
    const double c = real();
    if (!(c >= 0 && c <= 1e8) || c != std::floor(c)) throw Error(loc(kw), std::string(what) + " needs a whole count");
    return std::size_t(c);
  };
  while (true) {
    const Token& t = peek();
    if (t.kind != TokenKind::Identifier) break;
    const std::string n = t.text;
    if (n == "vertex_vectors" || n == "normal_vectors") {
      next();
      expect_symbol("{", ("after " + n).c_str());
      const std::size_t k = count(n.c_str());
      for (std::size_t i = 0; i < k; ++i) {
        expect_symbol(",", ("in " + n).c_str());
        const Vector v = vector();
        (n == "vertex_vectors" ? data.positions : data.normals).push_back(Vec3(v[0], v[1], v[2]));
      }
      accept_symbol(",");
      expect_symbol("}", ("to close " + n + " (more entries than its count?)").c_str());
    } else if (n == "uv_vectors") {
      next();
      expect_symbol("{", "after uv_vectors");
      const std::size_t k = count(n.c_str());
      for (std::size_t i = 0; i < k; ++i) {
        expect_symbol(",", "in uv_vectors");
        data.texcoords.push_back(uv_vector());
      }
      accept_symbol(",");
      expect_symbol("}", "to close uv_vectors (more entries than its count?)");
    } else if (n == "face_indices" || n == "normal_indices" || n == "uv_indices") {
      next();
      const FileLoc where = loc(t);
      (n == "uv_indices" ? uv_where : faces_where) = where;
      expect_symbol("{", ("after " + n).c_str());
      const std::size_t k = count(n.c_str());
      for (std::size_t i = 0; i < k; ++i) {
        expect_symbol(",", ("in " + n).c_str());
        const Vector v = vector();
        std::array<std::int64_t, 3> f{};
        for (std::size_t j = 0; j < 3; ++j) {
          if (!(v[j] >= 0 && v[j] < 4e9) || v[j] != std::floor(v[j])) throw Error(where, n + ": an index is not a whole number ≥ 0");
          f[j] = std::int64_t(v[j]);
        }
        while (is_symbol(peek(), ",") && pos_ + 1 < tokens_.size() && tokens_[pos_ + 1].kind == TokenKind::Number) {
          next();
          next();  // texture indices: left out
        }
        if (n == "face_indices") {
          MeshData::Face face;
          for (std::size_t j = 0; j < 3; ++j) {
            if (std::size_t(f[j]) >= data.positions.size()) throw Error(where, "face_indices: index " + std::to_string(f[j]) + " is past the vertex_vectors");
            face.v[j] = std::uint32_t(f[j]);
          }
          data.faces.push_back(face);
        } else {
          (n == "uv_indices" ? uv_faces : normal_faces).push_back(f);
        }
      }
      accept_symbol(",");
      expect_symbol("}", ("to close " + n + " (more entries than its count?)").c_str());
    } else if (n == "texture_list" || n == "inside_vector") {
      next();
      if (n == "inside_vector") vector();
      else skip_block();
    } else {
      break;
    }
  }
  mesh2_uvs(data, uv_faces, uv_where, faces_where);
  if (!normal_faces.empty()) {
    if (normal_faces.size() != data.faces.size()) throw Error(loc(kw), "normal_indices needs one entry per face");
    for (std::size_t i = 0; i < normal_faces.size(); ++i)
      for (std::size_t j = 0; j < 3; ++j) {
        if (std::size_t(normal_faces[i][j]) >= data.normals.size()) throw Error(loc(kw), "normal_indices: an index is past the normal_vectors");
        data.faces[i].n[j] = std::int32_t(normal_faces[i][j]);
      }
  } else if (!data.normals.empty()) {
    if (data.normals.size() != data.positions.size()) throw Error(loc(kw), "normal_vectors needs one normal per vertex (or normal_indices)");
    for (MeshData::Face& f : data.faces)
      for (std::size_t j = 0; j < 3; ++j) f.n[j] = std::int32_t(f.v[j]);
  }
  for (MeshData::Face& f : data.faces) {
    if (f.n[0] < 0) continue;
    std::array<Vector, 3> n{};
    for (std::size_t j = 0; j < 3; ++j) {
      const Vec3& v = data.normals[std::size_t(f.n[j])];
      n[j] = {double(v.x), double(v.y), double(v.z)};
    }
    if (equal_normals(n)) f.n = {-1, -1, -1};
  }
}

Object Parser::isosurface(const Token& kw) {
  Object o;
  o.type = "implicit";
  o.loc = loc(kw);
  std::string function, contained = "{type: box, corners: [[-1, -1, -1], [1, 1, 1]]}";
  double threshold = 0, max_gradient = 1.1, accuracy = 0.001;
  while (true) {
    const Token t = peek();
    if (t.kind != TokenKind::Identifier) break;
    const std::string n = t.text;
    if (n == "function") {
      next();
      function = function_text(t);
    } else if (n == "contained_by") {
      next();
      expect_symbol("{", "after contained_by");
      const Token s = next();
      expect_symbol("{", ("after " + s.text).c_str());
      const Vector a = vector();
      expect_symbol(",", ("in " + s.text).c_str());
      if (s.text == "sphere") contained = "{type: sphere, center: " + yaml_vector(a) + ", radius: " + yaml_number(real()) + "}";
      else if (s.text == "box") contained = "{type: box, corners: [" + yaml_vector(a) + ", " + yaml_vector(vector()) + "]}";
      else throw Error(loc(s), "contained_by needs a sphere or a box");
      expect_symbol("}", ("to close " + s.text).c_str());
      expect_symbol("}", "to close contained_by");
    } else if (n == "threshold") next(), threshold = real();
    else if (n == "max_gradient") next(), max_gradient = real();
    else if (n == "accuracy") next(), accuracy = real();
    else if (n == "open" || n == "evaluate" || n == "max_trace" || n == "all_intersections") {
      next();
      if (n == "evaluate") real(), expect_symbol(",", "in evaluate"), real(), expect_symbol(",", "in evaluate"), real();
      if (n == "max_trace") real();
      warn(loc(t), n + " is left out");
    } else {
      break;
    }
  }
  if (function.empty()) throw Error(loc(kw), "isosurface needs a function { … }");
  if (threshold != 0) function = "(" + function + ") - " + yaml_number(threshold);
  o.keys = ", expression: \"" + function + "\", contained_by: " + contained + ", max_gradient: " + yaml_number(max_gradient) +
           ", accuracy: " + yaml_number(accuracy);
  return o;
}

// function { … } as the text of strahl's expression language (docs/scene-format.md): POV-Ray's
// x, y, z, numbers, operators and functions carry over; declared floats become their values.
std::string Parser::function_text(const Token& kw) {
  expect_symbol("{", "after function");
  std::string s;
  for (int depth = 1;;) {
    const Token t = tokens_[pos_++];
    if (t.kind == TokenKind::End) throw Error(loc(kw), "function { is never closed");
    if (is_symbol(t, "{")) throw Error(loc(t), "'{' inside a function is not supported");
    if (is_symbol(t, "}") && --depth == 0) break;
    if (t.kind == TokenKind::Number) s += yaml_number(t.number);
    else if (t.kind == TokenKind::Symbol) s += t.text == "," ? ", " : " " + t.text + " ";
    else if (t.kind == TokenKind::Identifier) {
      if (t.text == "x" || t.text == "y" || t.text == "z" || is_function_name(t.text)) s += t.text;
      else if (t.text == "pi") s += yaml_number(kPi);
      else if (const auto it = symbols_.find(t.text); it != symbols_.end() && it->second.kind == Value::Kind::Number && it->second.num.dim == 1)
        s += "(" + yaml_number(it->second.num.f()) + ")";
      else throw Error(loc(t), "'" + t.text + "' in a function is not supported by strahl's POV-Ray importer");
    } else {
      throw Error(loc(t), describe(t) + " in a function is not supported");
    }
  }
  return s;
}

}  // namespace strahl::pov
