#include "strahl/scene/obj_loader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <system_error>

#include "strahl/scene/file_materials.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/mtl_loader.h"
#include "strahl/scene/polygon.h"
#include "strahl/scene/scene.h"
#include "strahl/util/cancel.h"
#include "strahl/util/error.h"
#include "strahl/util/large_array.h"

namespace strahl {

namespace {

// One strict pass over the text. It reads every line the way the OBJ format defines it and throws
// at the first problem, with its line and column (tinyobjloader, used before, read "v 1 abc" as
// (1, 0, 0), kept NaN, dropped bad faces without a word, and stored at most 255 corners per
// polygon). Triangles go straight into the mesh; larger polygons are kept as corner lists and
// split by polygon.h once all vertices are read (a face may refer to vertices defined after it).
class ObjReader {
 public:
  // With `dir`, the faces' materials too (mtllib files looked for in dir; MeshData::materials).
  ObjReader(const std::string& name, MeshData& mesh, const std::filesystem::path* dir)
      : name_(name), mesh_(mesh), dir_(dir) {}

  void read(std::string_view text) {
    reserve(text);
    int line = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
      ++line;
      if (((line - 1) & 0xfff) == 0) check_cancelled("obj");
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
    split_polygons();
    if (dir_) resolve_materials();
  }

 private:
  static constexpr const char* kKinds[3] = {"vertex", "texture coordinate", "normal"};
  struct Ref {
    long long index = 0;
    int line = 0, column = 0;
  };

  // Room for the vertices and triangles the lines that start with "v " and "f " give, so that the
  // arrays are not copied as they grow (a hint: lines with leading blanks are not counted).
  void reserve(std::string_view text) {
    std::size_t v = 0, f = 0;
    for (std::size_t pos = 0; pos + 1 < text.size();) {
      if (text[pos + 1] == ' ' || text[pos + 1] == '\t') {
        v += text[pos] == 'v';
        f += text[pos] == 'f';
      }
      const std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) break;
      pos = end + 1;
    }
    mesh_.positions.reserve(v);
    mesh_.faces.reserve(f);
  }

  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw Error(FileLoc{name_, line, column}, message);
  }

  struct Token {
    std::string_view text;
    int column;  // 1-based
  };

  void check_line(std::string_view s, int line) {
    std::vector<Token>& tokens = tokens_;
    tokens.clear();
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
      const Vec3 p = numbers(tokens, line, 3, 6, "vertex", "x, y and z");
      mesh_.positions.push_back(p);
      ++counts_[0];
    } else if (key == "vt") {
      const Vec3 uvw = numbers(tokens, line, 1, 3, "texture coordinate", "u");  // (v 0 where left out; w unused)
      mesh_.texcoords.push_back({uvw.x, uvw.y});
      ++counts_[1];
    } else if (key == "vn") {
      mesh_.normals.push_back(numbers(tokens, line, 3, 3, "normal", "x, y and z"));
      ++counts_[2];
    } else if (key == "f") {
      if (tokens.size() < 4)
        fail(line, tokens.back().column + int(tokens.back().text.size()),
             "face needs at least three corners (got " + std::to_string(tokens.size() - 1) + ")");
      int layout = -1;  // which of v, vt, vn every corner gives (bit mask); must be the same for all
      corners_.clear();
      for (std::size_t t = 1; t < tokens.size(); ++t) {
        Corner c;
        const int l = corner(tokens[t], line, c);
        if (layout >= 0 && l != layout)
          fail(line, tokens[t].column, "face corners mix forms (v, v/vt, v//vn, v/vt/vn): '" +
                                           std::string(tokens[t].text) + "'");
        layout = l;
        corners_.push_back(c);
      }
      if (corners_.size() == 3) {
        MeshData::Face f;
        for (std::size_t k = 0; k < 3; ++k) {
          f.v[k] = std::uint32_t(corners_[k].v);
          f.n[k] = corners_[k].n;
          f.t[k] = corners_[k].t;
        }
        mesh_.faces.push_back(f);
        if (dir_) mesh_.face_materials.push_back(material_);
      } else {
        polygons_.push_back({polygon_corners_.size(), corners_.size(), mesh_.faces.size(), line, material_});
        polygon_corners_.insert(polygon_corners_.end(), corners_.begin(), corners_.end());
      }
    } else if (key == "mtllib" && dir_) {
      if (tokens.size() < 2) fail(line, tokens[0].column + 6, "mtllib needs a file name");
      for (std::size_t t = 1; t < tokens.size(); ++t) {
        std::vector<MtlMaterial> library;
        try {
          library = load_mtl(*dir_ / std::string(tokens[t].text));
        } catch (const Error& e) {
          fail(line, tokens[t].column, std::string("mtllib: ") + e.what());
        }
        library_.insert(library_.end(), library.begin(), library.end());
      }
      ++libraries_;
    } else if (key == "usemtl" && dir_) {
      if (tokens.size() != 2) fail(line, tokens[0].column, "usemtl needs one material name");
      const std::string n(tokens[1].text);
      const auto [it, fresh] = slots_.try_emplace(n, std::int32_t(slots_.size()));
      if (fresh) slot_uses_.push_back({n, line, tokens[1].column});
      material_ = it->second;
    }
    // Everything else (o, g, s, l, p, ...; without `dir`, usemtl and mtllib) does not change the triangles.
  }

  // The materials usemtl named, in order of first use, from the mtllib files (map_Kd pictures
  // read once each, times Kd).
  void resolve_materials() {
    std::map<std::filesystem::path, std::shared_ptr<const Image>> pictures;
    for (const SlotUse& use : slot_uses_) {
      const MtlMaterial* found = nullptr;
      for (const MtlMaterial& m : library_)
        if (m.name == use.name) {
          found = &m;
          break;
        }
      if (!found)
        fail(use.line, use.column, "usemtl '" + use.name + "': no such material in " +
                                       (libraries_ ? "the mtllib files" : "the file (it names no mtllib)"));
      FileMaterial f;
      f.name = found->name;
      f.color = found->kd;
      if (!found->map_kd.empty()) {
        auto [it, fresh] = pictures.try_emplace(found->map_kd, nullptr);
        if (fresh) {
          try {
            it->second = read_texture_image(found->map_kd);
          } catch (const Error& e) {
            throw Error(FileLoc{found->file, found->map_kd_line}, std::string("map_Kd: ") + e.what());
          }
        }
        f.image = tinted(it->second, found->kd);
      }
      mesh_.materials.push_back(std::move(f));
    }
  }

  // Checks the numbers of a v, vt or vn line and returns the first three (0 where there are fewer).
  Vec3 numbers(const std::vector<Token>& tokens, int line, std::size_t lo, std::size_t hi, const char* what,
               const char* needs) const {
    double xyz[3] = {0, 0, 0};
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
      if (t <= 3) xyz[t - 1] = x;
    }
    return Vec3(Real(xyz[0]), Real(xyz[1]), Real(xyz[2]));
  }

  struct Corner {
    long long v = 0;      // position index from 0
    std::int32_t n = -1;  // normal index from 0, −1 for none
    std::int32_t t = -1;  // texture-coordinate index from 0, −1 for none
  };
  struct Polygon {
    std::size_t first, count;  // in polygon_corners_
    std::size_t at;            // the number of faces before it
    int line;
    std::int32_t material;     // its usemtl slot (−1: none)
  };
  struct SlotUse {
    std::string name;
    int line, column;  // where usemtl first names it
  };

  // One face corner: v, v/vt, v//vn or v/vt/vn. Returns which indices it gives (1 v, 2 vt, 4 vn).
  int corner(const Token& token, int line, Corner& out) {
    std::string_view s = token.text;
    int mask = 0;
    int column = token.column;
    for (int k = 0; k < 3; ++k) {
      const std::size_t slash = s.find('/');
      const std::string_view part = s.substr(0, slash);
      if (!part.empty()) {
        const long long i = index(part, k, line, column);
        if (k == 0) out.v = i;
        if (k == 1) out.t = std::int32_t(i);
        if (k == 2) out.n = std::int32_t(i);
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

  // Checks an index and returns it counted from 0 (negative ones are relative to the elements read so far).
  long long index(std::string_view s, int kind, int line, int column) {
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
      return counts_[kind] + v;
    }
    if (v > max_ref_[kind].index) max_ref_[kind] = {v, line, column};  // checked against the final count
    return v - 1;
  }

  // Polygons of more than three corners into triangles (polygon.h), each in its place in file order.
  void split_polygons() {
    if (polygons_.empty()) return;
    LargeArray<MeshData::Face> faces;
    faces.reserve(mesh_.faces.size() + polygon_corners_.size() - 2 * polygons_.size());
    LargeArray<std::int32_t> materials;  // (parallel to faces, with materials read)
    if (dir_) materials.reserve(faces.capacity());
    std::size_t copied = 0;
    std::vector<Vec3> points;
    std::vector<PolygonTriangle> triangles;
    for (std::size_t p = 0; p < polygons_.size(); ++p) {
      if ((p & 0xfff) == 0) check_cancelled("obj");
      const Polygon& poly = polygons_[p];
      const Corner* c = polygon_corners_.data() + poly.first;
      points.clear();
      for (std::size_t k = 0; k < poly.count; ++k) points.push_back(mesh_.positions[std::size_t(c[k].v)]);
      triangles.clear();
      if (!triangulate_polygon(points, triangles))
        fail(poly.line, 1, "a face of " + std::to_string(poly.count) +
                               " corners with too many reflex (inward) corners to split into triangles in "
                               "reasonable time; split it into smaller polygons");
      faces.insert(faces.end(), mesh_.faces.begin() + std::ptrdiff_t(copied), mesh_.faces.begin() + std::ptrdiff_t(poly.at));
      if (dir_)
        materials.insert(materials.end(), mesh_.face_materials.begin() + std::ptrdiff_t(copied),
                         mesh_.face_materials.begin() + std::ptrdiff_t(poly.at));
      copied = poly.at;
      for (const PolygonTriangle& t : triangles) {
        MeshData::Face f;
        for (std::size_t k = 0; k < 3; ++k) {
          f.v[k] = std::uint32_t(c[t[k]].v);
          f.n[k] = c[t[k]].n;
          f.t[k] = c[t[k]].t;
        }
        faces.push_back(f);
        if (dir_) materials.push_back(poly.material);
      }
    }
    faces.insert(faces.end(), mesh_.faces.begin() + std::ptrdiff_t(copied), mesh_.faces.end());
    mesh_.faces = std::move(faces);
    if (dir_) {
      materials.insert(materials.end(), mesh_.face_materials.begin() + std::ptrdiff_t(copied), mesh_.face_materials.end());
      mesh_.face_materials = std::move(materials);
    }
  }

  const std::string& name_;
  MeshData& mesh_;
  long long counts_[3] = {0, 0, 0};  // v, vt, vn
  Ref max_ref_[3];
  std::vector<Token> tokens_;    // of the current line
  std::vector<Corner> corners_;  // of the current face
  std::vector<Polygon> polygons_;
  std::vector<Corner> polygon_corners_;
  const std::filesystem::path* dir_;   // nullptr: materials are not read
  std::vector<MtlMaterial> library_;   // every mtllib file's materials, in order
  int libraries_ = 0;                  // mtllib lines read
  std::map<std::string, std::int32_t> slots_;  // usemtl names → their index in MeshData::materials
  std::vector<SlotUse> slot_uses_;
  std::int32_t material_ = -1;         // the current usemtl's slot
};

}  // namespace

MeshData parse_obj(std::string_view text, const std::string& name) {
  MeshData mesh;
  ObjReader(name, mesh, nullptr).read(text);
  if (mesh.faces.empty()) throw Error(FileLoc{name}, "OBJ file contains no faces");
  return mesh;
}

MeshData parse_obj(std::string_view text, const std::string& name, const std::filesystem::path& dir) {
  MeshData mesh;
  ObjReader(name, mesh, &dir).read(text);
  if (mesh.faces.empty()) throw Error(FileLoc{name}, "OBJ file contains no faces");
  return mesh;
}

MeshData load_obj(const std::filesystem::path& path, bool materials) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(FileLoc{path.string()}, "cannot open mesh file (no such file)");
  if (std::filesystem::is_directory(path, ec)) throw Error(FileLoc{path.string()}, "is a directory, not a mesh file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(FileLoc{path.string()}, "is not a regular file (a FIFO, device or socket), not a mesh file");
  const LargeArray<char> text = read_mesh_file(path);
  const std::string_view view(text.data(), text.size());
  return materials ? parse_obj(view, path.string(), path.parent_path()) : parse_obj(view, path.string());
}

}  // namespace strahl
