#include "strahl/scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

#include "strahl/util/error.h"
#include "strahl/util/system_error.h"

namespace strahl {

namespace {

// The strict pass. tinyobjloader is lenient: it reads "v 1 abc" as (1, 0, 0), keeps NaN, drops
// faces with fewer than three corners and normal indices out of range without a word. This pass
// reads every line the way the OBJ format defines it and throws at the first problem, with its
// line and column, so that tinyobjloader only ever sees well-formed text.
class ObjChecker {
 public:
  explicit ObjChecker(const std::string& name) : name_(name) {}

  void check(std::string_view text) {
    int line = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
      ++line;
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      check_line(text.substr(pos, end - pos), line);
      pos = end + 1;
    }
    for (int k = 0; k < 3; ++k) {
      const Ref& r = max_ref_[k];
      if (r.index > counts_[k])
        fail(r.line, r.column, std::string("face refers to ") + kKinds[k] + " " + std::to_string(r.index) +
                                   ", but the file has " + std::to_string(counts_[k]));
    }
  }

 private:
  static constexpr const char* kKinds[3] = {"vertex", "texture coordinate", "normal"};
  struct Ref {
    long long index = 0;
    int line = 0, column = 0;
  };

  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw Error(FileLoc{name_, line, column}, message);
  }

  struct Token {
    std::string_view text;
    int column;  // 1-based
  };

  void check_line(std::string_view s, int line) {
    std::vector<Token> tokens;
    std::size_t i = 0;
    while (i < s.size()) {
      const unsigned char c = static_cast<unsigned char>(s[i]);
      if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++i;
        continue;
      }
      if (c == '#') break;  // a comment runs to the end of the line
      const std::size_t start = i;
      while (i < s.size()) {
        const unsigned char d = static_cast<unsigned char>(s[i]);
        if (d == ' ' || d == '\t' || d == '\r' || d == '\f' || d == '\v' || d == '#') break;
        if (d < 0x20 || d == 0x7f) {
          char hex[8];
          std::snprintf(hex, sizeof hex, "0x%02x", d);
          fail(line, int(i) + 1, std::string("not a text file (byte ") + hex + ")");
        }
        ++i;
      }
      tokens.push_back({s.substr(start, i - start), int(start) + 1});
    }
    if (tokens.empty()) return;
    const std::string_view key = tokens[0].text;
    if (key == "v") {
      // x y z, optionally w or an r g b colour
      numbers(tokens, line, 3, 6, "vertex", "x, y and z");
      ++counts_[0];
    } else if (key == "vt") {
      numbers(tokens, line, 1, 3, "texture coordinate", "u");
      ++counts_[1];
    } else if (key == "vn") {
      numbers(tokens, line, 3, 3, "normal", "x, y and z");
      ++counts_[2];
    } else if (key == "f") {
      if (tokens.size() < 4)
        fail(line, tokens.back().column + int(tokens.back().text.size()),
             "face needs at least three corners (got " + std::to_string(tokens.size() - 1) + ")");
      int layout = -1;  // which of v, vt, vn every corner gives (bit mask); must be the same for all
      for (std::size_t t = 1; t < tokens.size(); ++t) {
        const int l = corner(tokens[t], line);
        if (layout >= 0 && l != layout)
          fail(line, tokens[t].column, "face corners mix forms (v, v/vt, v//vn, v/vt/vn): '" +
                                           std::string(tokens[t].text) + "'");
        layout = l;
      }
    }
    // Everything else (o, g, s, usemtl, mtllib, l, p, ...) does not change the triangles.
  }

  void numbers(const std::vector<Token>& tokens, int line, std::size_t lo, std::size_t hi, const char* what,
               const char* needs) const {
    const std::size_t n = tokens.size() - 1;
    if (n < lo)
      fail(line, tokens.back().column + int(tokens.back().text.size()),
           std::string(what) + " needs " + needs + " (got " + std::to_string(n) + " numbers)");
    if (n > hi + (hi == 6 ? 1 : 0))
      fail(line, tokens[hi + 1].column, std::string(what) + " has too many numbers");
    for (std::size_t t = 1; t < tokens.size(); ++t) {
      std::string_view v = tokens[t].text;
      if (v.size() > 1 && v[0] == '+') v.remove_prefix(1);
      double x = 0;
      const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
      if (ec == std::errc::result_out_of_range && p == v.data() + v.size())
        fail(line, tokens[t].column, std::string(what) + ": '" + std::string(tokens[t].text) + "' is out of range");
      if (ec != std::errc() || p != v.data() + v.size())
        fail(line, tokens[t].column, std::string(what) + ": '" + std::string(tokens[t].text) + "' is not a number");
      if (!std::isfinite(x))
        fail(line, tokens[t].column, std::string(what) + ": '" + std::string(tokens[t].text) + "' is not a finite number");
    }
  }

  // One face corner: v, v/vt, v//vn or v/vt/vn. Returns which indices it gives (1 v, 2 vt, 4 vn).
  int corner(const Token& token, int line) {
    std::string_view s = token.text;
    int mask = 0;
    int column = token.column;
    for (int k = 0; k < 3; ++k) {
      const std::size_t slash = s.find('/');
      const std::string_view part = s.substr(0, slash);
      if (!part.empty()) {
        index(part, k, line, column);
        mask |= 1 << k;
      } else if (k == 0) {
        fail(line, column, "face corner '" + std::string(token.text) + "' has no vertex index");
      }
      if (slash == std::string_view::npos) break;
      if (k == 2) fail(line, column + int(slash), "face corner '" + std::string(token.text) + "' has too many parts");
      s.remove_prefix(slash + 1);
      column += int(slash) + 1;
    }
    if (mask == (1 | 2 | 4) || mask == 1 || mask == (1 | 2) || mask == (1 | 4)) return mask;
    fail(line, token.column, "face corner '" + std::string(token.text) + "' is malformed");
  }

  void index(std::string_view s, int kind, int line, int column) {
    long long v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && p == s.data() + s.size() &&
                                                 (v > (1ll << 40) || v < -(1ll << 40))))
      fail(line, column, std::string(kKinds[kind]) + " index '" + std::string(s) + "' is out of range");
    if (ec != std::errc() || p != s.data() + s.size())
      fail(line, column, std::string(kKinds[kind]) + " index '" + std::string(s) + "' is not a whole number");
    if (v == 0) fail(line, column, std::string(kKinds[kind]) + " index 0 (OBJ counts from 1, or from −1 backwards)");
    if (v < 0) {
      // Relative to the elements read so far.
      if (-v > counts_[kind])
        fail(line, column, std::string(kKinds[kind]) + " index " + std::to_string(v) + " reaches before the first of the " +
                               std::to_string(counts_[kind]) + " read so far");
    } else if (v > max_ref_[kind].index) {
      max_ref_[kind] = {v, line, column};  // positive indices are checked against the final count
    }
  }

  const std::string& name_;
  long long counts_[3] = {0, 0, 0};  // v, vt, vn
  Ref max_ref_[3];
};

}  // namespace

MeshData parse_obj(std::string_view text, const std::string& name) {
  ObjChecker(name).check(text);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(std::string(text), std::string(), config)) {
    std::string message = reader.Error();
    while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
    throw Error(FileLoc{name}, "cannot read OBJ: " + (message.empty() ? "parse error" : message));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  MeshData mesh;
  mesh.positions.reserve(attrib.vertices.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    mesh.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
  mesh.normals.reserve(attrib.normals.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.normals.size(); i += 3)
    mesh.normals.emplace_back(attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]);

  const auto vertex_count = static_cast<long>(mesh.positions.size());
  const auto normal_count = static_cast<long>(mesh.normals.size());
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    std::size_t offset = 0;
    for (const unsigned int fv : shape.mesh.num_face_vertices) {
      if (offset + fv > indices.size()) throw Error(FileLoc{name}, "cannot read OBJ: inconsistent face list");
      if (fv == 3) {
        MeshData::Face face;
        for (int k = 0; k < 3; ++k) {
          const tinyobj::index_t& idx = indices[offset + std::size_t(k)];
          if (idx.vertex_index < 0 || idx.vertex_index >= vertex_count)
            throw Error(FileLoc{name}, "face in shape '" + shape.name + "' refers to vertex " +
                                           std::to_string(idx.vertex_index + 1) + " of " + std::to_string(vertex_count));
          face.v[std::size_t(k)] = static_cast<std::uint32_t>(idx.vertex_index);
          face.n[std::size_t(k)] = (idx.normal_index >= 0 && idx.normal_index < normal_count) ? idx.normal_index : -1;
        }
        mesh.faces.push_back(face);
      }
      offset += fv;
    }
  }
  if (mesh.faces.empty()) throw Error(FileLoc{name}, "OBJ file contains no faces");
  return mesh;
}

MeshData load_obj(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(FileLoc{path.string()}, "cannot open mesh file (no such file)");
  if (std::filesystem::is_directory(path, ec)) throw Error(FileLoc{path.string()}, "is a directory, not a mesh file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(FileLoc{path.string()}, "is not a regular file (a FIFO, device or socket), not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(FileLoc{path.string()}, "cannot open mesh file: " + system_reason(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(FileLoc{path.string()}, "cannot read mesh file: " + system_reason(errno));
  return parse_obj(text.str(), path.string());
}

}  // namespace strahl
