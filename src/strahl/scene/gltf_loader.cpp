#include "strahl/scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "strahl/math/transform.h"
#include "strahl/scene/file_materials.h"
#include "strahl/scene/gltf_data.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/scene.h"
#include "strahl/util/cancel.h"
#include "strahl/util/error.h"

namespace strahl {

namespace {

using nlohmann::json;

// MeshData indexes vertices, normals and texture coordinates with 32-bit signed numbers.
constexpr std::uint64_t kMaxElements = 0x7fffffff;
constexpr std::uint64_t kMaxInteger = std::uint64_t(1) << 53;

// glTF's componentType codes and their sizes in bytes (0: not a glTF component type).
enum Component : int { Byte = 5120, UnsignedByte = 5121, Short = 5122, UnsignedShort = 5123, UnsignedInt = 5125, Float = 5126 };
int component_size(std::uint64_t type) {
  switch (type) {
    case Byte: case UnsignedByte: return 1;
    case Short: case UnsignedShort: return 2;
    case UnsignedInt: case Float: return 4;
    default: return 0;
  }
}

// One component, little-endian, as glTF defines normalized integers (signed: max(c / 127, −1)).
Real component(const unsigned char* p, int type, bool normalized) {
  const std::uint32_t u16 = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8;
  switch (type) {
    case Byte: return normalized ? std::max(Real(static_cast<std::int8_t>(p[0])) / 127, Real(-1)) : static_cast<std::int8_t>(p[0]);
    case UnsignedByte: return normalized ? Real(p[0]) / 255 : p[0];
    case Short: return normalized ? std::max(Real(static_cast<std::int16_t>(u16)) / 32767, Real(-1)) : static_cast<std::int16_t>(u16);
    case UnsignedShort: return normalized ? Real(u16) / 65535 : u16;
    default: break;
  }
  const std::uint32_t u32 = u16 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
  if (type == UnsignedInt) return u32;
  float f;
  std::memcpy(&f, &u32, sizeof f);
  return f;
}

constexpr const char* kTypeNames[5] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};

// An accessor checked against its bufferView and buffer: reading it touches only `bytes`.
struct Accessor {
  std::string where;  // "accessors[3]"
  int component = 0, size = 0, width = 0;
  bool normalized = false;
  std::uint64_t count = 0;
  std::string_view bytes;  // from the first element; data() == nullptr: no bufferView (zeros)
  std::size_t stride = 0;
  std::uint64_t sparse_count = 0;  // sparse substitution: indices and tightly packed values
  int sparse_index_type = 0;
  std::string_view sparse_indices, sparse_values;
};

// Where a node places its meshes: p' = m·p + t.
struct Placement {
  Mat3 m;
  Vec3 t{0, 0, 0};
};

// A mesh's primitive that holds triangles.
struct Primitive {
  std::string where;
  int mode = 4;           // 4 triangles, 5 strip, 6 fan
  std::int32_t material = -1;  // into MeshData::materials (with materials read), −1 none
  Accessor position;
  std::optional<Accessor> normal, texcoord, indices;
  std::uint64_t triangles = 0;
};

struct Draw {
  std::size_t mesh;
  Placement at;
};

std::string item(const char* array, std::size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

class GltfReader {
 public:
  GltfReader(std::string_view bytes, const std::string& name, std::filesystem::path dir, bool materials,
             std::uint64_t max_triangles)
      : name_(name), dir_(std::move(dir)), file_size_(bytes.size()), max_triangles_(std::min(max_triangles, kMaxElements)),
        read_materials_(materials) {
    container_ = gltf::split_container(bytes, name);
    parse_json();
  }

  MeshData read() {
    check_extensions();
    const std::vector<Draw> draws = scene_draws();
    std::uint64_t vertices = 0, faces = 0;
    for (const Draw& d : draws)
      for (const Primitive& p : primitives(d.mesh)) {
        vertices += p.position.count;
        faces += p.triangles;
        if (vertices > kMaxElements || faces > max_triangles_)
          fail("", "the scene holds more than " + std::to_string(faces > max_triangles_ ? max_triangles_ : kMaxElements) +
                       (faces > max_triangles_ ? " triangles" : " vertices") + " (a mesh counts once for each node that draws it)");
      }
    if (faces == 0) fail("", "the scene holds no triangles");
    MeshData mesh;
    mesh.positions.reserve(vertices);
    mesh.faces.reserve(faces);
    if (read_materials_) mesh.face_materials.reserve(faces);
    for (const Draw& d : draws)
      for (const Primitive& p : primitives(d.mesh)) add(p, d.at, mesh);
    mesh.materials = std::move(materials_);
    return mesh;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw Error(FileLoc{name_}, where.empty() ? what : where + ": " + what);
  }

  void parse_json() {
    const std::string_view text = container_.json;
    try {
      root_ = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
      // nlohmann's message: "[json.exception.parse_error.101] parse error at line 1, column 5: …".
      std::string what = e.what();
      if (const std::size_t c = what.find("column "); c != std::string::npos)
        if (const std::size_t colon = what.find(": ", c); colon != std::string::npos) what = what.substr(colon + 2);
      int line = 1, column = 1;
      for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
        if (text[i] == '\n') ++line, column = 1;
        else ++column;
      }
      if (container_.binary)
        throw Error(FileLoc{name_}, "JSON chunk, line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what);
      throw Error(FileLoc{name_, line, column}, what);
    } catch (const json::exception& e) {
      // Others while parsing, without a place: "[json.exception.out_of_range.406] number overflow parsing '1e999'".
      const std::string what = e.what();
      const std::size_t tag = what.find("] ");
      fail("", "JSON: " + (tag == std::string::npos ? what : what.substr(tag + 2)));
    }
    if (!root_.is_object()) fail("", "the JSON text is not an object");
    const json* asset = member(root_, "asset");
    if (!asset || !asset->is_object()) fail("", "no 'asset' object: not a glTF file");
    const json* version = member(*asset, "version");
    if (!version || !version->is_string()) fail("asset", "no version");
    const std::string& v = version->get_ref<const std::string&>();
    if (v.rfind("2.", 0) != 0) fail("asset.version", "'" + v + "' (strahl reads glTF 2)");
    buffers_.resize(array("buffers").size());
    material_slots_.assign(array("materials").size(), -1);
    images_.resize(array("images").size());
  }

  static const json* member(const json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  const json& required(const json& object, const char* key, const std::string& where) const {
    const json* m = member(object, key);
    if (!m) fail(where, std::string("has no '") + key + "'");
    return *m;
  }

  // A top-level array (empty where the file has none).
  const json& array(const char* key) const {
    static const json empty = json::array();
    const json* a = member(root_, key);
    if (!a) return empty;
    if (!a->is_array()) fail(key, "must be a list");
    return *a;
  }

  const json& object(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "must be an object");
    return j;
  }

  std::uint64_t integer(const json& j, const std::string& where) const {
    if (j.is_number_unsigned()) {
      if (j.get<std::uint64_t>() > kMaxInteger) fail(where, "is too large");
      return j.get<std::uint64_t>();
    }
    if (j.is_number_float()) {
      const double d = j.get<double>();
      if (d >= 0 && d <= double(kMaxInteger) && d == std::floor(d)) return std::uint64_t(d);
    }
    if (j.is_number() && j.get<double>() < 0) fail(where, "must not be negative");
    fail(where, "must be a whole number");
  }

  std::uint64_t integer_or(const json& object, const char* key, const std::string& where, std::uint64_t otherwise) const {
    const json* m = member(object, key);
    return m ? integer(*m, where + "." + key) : otherwise;
  }

  // An index into the top-level array `into`.
  std::size_t index(const json& j, const std::string& where, const char* into) const {
    const std::uint64_t i = integer(j, where);
    const std::size_t n = array(into).size();
    if (i >= n) fail(where, "refers to " + item(into, i) + ", but the file has " + std::to_string(n));
    return std::size_t(i);
  }

  Real number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "must be a number");
    const Real x = j.get<double>();
    if (!std::isfinite(x)) fail(where, "must be finite");
    return x;
  }

  // A list of exactly n numbers.
  std::vector<Real> numbers(const json& j, std::size_t n, const std::string& where) const {
    if (!j.is_array() || j.size() != n) fail(where, "must be a list of " + std::to_string(n) + " numbers");
    std::vector<Real> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(number(j[i], where + "[" + std::to_string(i) + "]"));
    return out;
  }

  // Extensions the file says a reader must know: refused unless they leave the geometry alone
  // (material and texture extensions: the base colour is read as the core format defines it) or
  // are read here.
  void check_extensions() const {
    const json& required_list = array("extensionsRequired");
    for (std::size_t i = 0; i < required_list.size(); ++i) {
      const json& e = required_list[i];
      if (!e.is_string()) fail(item("extensionsRequired", i), "must be a string");
      const std::string& s = e.get_ref<const std::string&>();
      const bool known = s == "KHR_mesh_quantization" || s.rfind("KHR_materials_", 0) == 0 ||
                         s.rfind("KHR_texture_", 0) == 0 || s.rfind("EXT_texture_", 0) == 0;
      if (!known) fail(item("extensionsRequired", i), "the file needs extension '" + s + "', which strahl does not read");
    }
  }

  // ---- buffers, views, accessors ----

  // The bytes a buffer's or image's `uri` names: a data: URI's, or a file's beside the glTF file.
  LargeArray<char> uri_bytes(const json& u, const std::string& where) const {
    if (!u.is_string()) fail(where, "must be a string");
    const std::string& uri = u.get_ref<const std::string&>();
    const std::string scheme = gltf::uri_scheme(uri);
    if (!scheme.empty() && scheme != "data") fail(where, "'" + scheme + ":' URIs are not read (only data: URIs and file names)");
    try {
      return scheme == "data" ? gltf::decode_data_uri(uri) : read_mesh_file(dir_ / gltf::decode_percent(uri));
    } catch (const Error& e) {
      fail(where, e.what());
    }
  }

  std::string_view buffer(std::size_t i) {
    if (buffers_[i]) return *buffers_[i];
    const std::string where = item("buffers", i);
    const json& b = object(array("buffers")[i], where);
    const std::uint64_t length = integer(required(b, "byteLength", where), where + ".byteLength");
    std::string_view data;
    if (const json* u = member(b, "uri")) {
      owned_.push_back(uri_bytes(*u, where + ".uri"));
      data = std::string_view(owned_.back().data(), owned_.back().size());
    } else if (container_.binary && i == 0 && container_.bin.data() != nullptr) {
      data = container_.bin;
    } else {
      fail(where, container_.binary ? "has no uri, and the file has no BIN chunk (or this is not the first buffer)"
                                    : "has no uri");
    }
    if (data.size() < length)
      fail(where, "its byteLength is " + std::to_string(length) + ", but its data has " + std::to_string(data.size()) + " bytes");
    buffers_[i] = data.substr(0, std::size_t(length));
    return *buffers_[i];
  }

  // A bufferView's bytes and byteStride (0: tightly packed).
  std::pair<std::string_view, std::size_t> buffer_view(std::size_t i) {
    const std::string where = item("bufferViews", i);
    const json& v = object(array("bufferViews")[i], where);
    const std::string_view data = buffer(index(required(v, "buffer", where), where + ".buffer", "buffers"));
    const std::uint64_t offset = integer_or(v, "byteOffset", where, 0);
    const std::uint64_t length = integer(required(v, "byteLength", where), where + ".byteLength");
    if (offset > data.size() || length > data.size() - offset)
      fail(where, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                      " reach past the end of its buffer (" + std::to_string(data.size()) + " bytes)");
    const std::uint64_t stride = integer_or(v, "byteStride", where, 0);
    if (member(v, "byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0))
      fail(where + ".byteStride", "must be a multiple of 4 from 4 to 252");
    return {data.substr(std::size_t(offset), std::size_t(length)), std::size_t(stride)};
  }

  // `count` elements of `element` bytes, `stride` apart, from `offset` of a bufferView.
  std::string_view elements(std::size_t view, std::uint64_t offset, std::uint64_t count, std::size_t element,
                            std::size_t stride, const std::string& where) {
    const std::string_view bytes = buffer_view(view).first;
    const std::uint64_t end = offset + (count - 1) * stride + element;
    if (offset > bytes.size() || end > bytes.size())
      fail(where, std::to_string(count) + " elements of " + std::to_string(element) + " bytes from byte " +
                      std::to_string(offset) + " reach past the end of " + item("bufferViews", view) + " (" +
                      std::to_string(bytes.size()) + " bytes)");
    return bytes.substr(std::size_t(offset));
  }

  // Accessor i as `use` (a message's words) expects it: `width` components, indices or not.
  Accessor accessor(const json& ref, const std::string& ref_where, const std::string& use, int width, bool indices) {
    const std::size_t i = index(ref, ref_where, "accessors");
    Accessor a;
    a.where = item("accessors", i);
    const json& j = object(array("accessors")[i], a.where);
    const std::uint64_t type_code = integer(required(j, "componentType", a.where), a.where + ".componentType");
    a.size = component_size(type_code);
    if (a.size == 0) fail(a.where + ".componentType", std::to_string(type_code) + " is not a glTF component type");
    a.component = int(type_code);
    if (const json* n = member(j, "normalized")) {
      if (!n->is_boolean()) fail(a.where + ".normalized", "must be true or false");
      a.normalized = n->get<bool>();
    }
    if (a.normalized && (a.component == UnsignedInt || a.component == Float))
      fail(a.where + ".normalized", "only 8- and 16-bit integers can be normalized");
    const json& type = required(j, "type", a.where);
    a.width = width;
    if (!type.is_string() || type.get_ref<const std::string&>() != kTypeNames[width])
      fail(a.where + ".type", "must be " + std::string(kTypeNames[width]) + " for " + use);
    const bool index_type = a.component == UnsignedByte || a.component == UnsignedShort || a.component == UnsignedInt;
    if (indices && (!index_type || a.normalized))
      fail(a.where + ".componentType", use + " must be unsigned integers (5121, 5123 or 5125), not normalized");
    if (!indices && a.component == UnsignedInt) fail(a.where + ".componentType", use + " cannot be 32-bit integers");
    a.count = integer(required(j, "count", a.where), a.where + ".count");
    if (a.count == 0) fail(a.where + ".count", "must be at least 1");
    const std::size_t element = std::size_t(a.size) * std::size_t(width);
    if (const json* v = member(j, "bufferView")) {
      const std::size_t view = index(*v, a.where + ".bufferView", "bufferViews");
      const std::size_t stride = buffer_view(view).second;
      if (stride != 0 && stride < element)
        fail(a.where, "its elements (" + std::to_string(element) + " bytes) are longer than the byteStride of " +
                          item("bufferViews", view) + " (" + std::to_string(stride) + ")");
      a.stride = stride != 0 ? stride : element;
      a.bytes = elements(view, integer_or(j, "byteOffset", a.where, 0), a.count, element, a.stride, a.where);
    } else if (a.count > file_size_) {
      // (All zeros but for sparse values: bounded by the file's size, so that a few bytes cannot
      // ask for gigabytes.)
      fail(a.where, "has no bufferView, and its count " + std::to_string(a.count) +
                        " is larger than the file (an accessor of zeros holds at most one element a byte)");
    }
    if (const json* s = member(j, "sparse")) sparse(*s, a, element);
    return a;
  }

  void sparse(const json& s, Accessor& a, std::size_t element) {
    const std::string where = a.where + ".sparse";
    object(s, where);
    a.sparse_count = integer(required(s, "count", where), where + ".count");
    if (a.sparse_count == 0 || a.sparse_count > a.count)
      fail(where + ".count", "must be from 1 to the accessor's count (" + std::to_string(a.count) + ")");
    const json& ind = object(required(s, "indices", where), where + ".indices");
    const std::uint64_t t = integer(required(ind, "componentType", where + ".indices"), where + ".indices.componentType");
    if (t != UnsignedByte && t != UnsignedShort && t != UnsignedInt)
      fail(where + ".indices.componentType", "must be 5121, 5123 or 5125");
    a.sparse_index_type = int(t);
    const std::size_t index_size = std::size_t(component_size(t));
    a.sparse_indices = elements(index(required(ind, "bufferView", where + ".indices"), where + ".indices.bufferView", "bufferViews"),
                                integer_or(ind, "byteOffset", where + ".indices", 0), a.sparse_count, index_size,
                                index_size, where + ".indices");
    const json& val = object(required(s, "values", where), where + ".values");
    a.sparse_values = elements(index(required(val, "bufferView", where + ".values"), where + ".values.bufferView", "bufferViews"),
                               integer_or(val, "byteOffset", where + ".values", 0), a.sparse_count, element, element,
                               where + ".values");
  }

  // Every element of `a` (then the sparse ones again) as set(i, v), v[0..width): finite numbers.
  template <class Set>
  void read(const Accessor& a, Set&& set) const {
    Real v[4] = {0, 0, 0, 0};
    const auto element = [&](const char* p, std::uint64_t i) {
      for (int k = 0; k < a.width; ++k) {
        v[k] = component(reinterpret_cast<const unsigned char*>(p) + k * a.size, a.component, a.normalized);
        if (!std::isfinite(v[k])) fail(a.where, "element " + std::to_string(i) + " is not finite");
      }
    };
    for (std::uint64_t i = 0; i < a.count; ++i) {
      if ((i & 0xffff) == 0xffff) check_cancelled("gltf");
      if (a.bytes.data() != nullptr) element(a.bytes.data() + i * a.stride, i);
      set(std::size_t(i), v);
    }
    const std::size_t index_size = std::size_t(component_size(std::uint64_t(a.sparse_index_type)));
    for (std::uint64_t k = 0; k < a.sparse_count; ++k) {
      const auto i = std::uint64_t(component(reinterpret_cast<const unsigned char*>(a.sparse_indices.data()) + k * index_size,
                                             a.sparse_index_type, false));
      if (i >= a.count)
        fail(a.where + ".sparse", "index " + std::to_string(i) + " is not below the count " + std::to_string(a.count));
      element(a.sparse_values.data() + k * std::size_t(a.size) * std::size_t(a.width), i);
      set(std::size_t(i), v);
    }
  }

  // ---- meshes ----

  // Mesh m's primitives that hold triangles (points and lines are skipped, as is a primitive
  // without POSITION, which glTF says not to draw), read once however many nodes use the mesh.
  const std::vector<Primitive>& primitives(std::size_t m) {
    if (meshes_.size() <= m) meshes_.resize(array("meshes").size());
    if (meshes_[m]) return *meshes_[m];
    const std::string where = item("meshes", m);
    const json& mesh = object(array("meshes")[m], where);
    const json& list = required(mesh, "primitives", where);
    if (!list.is_array()) fail(where + ".primitives", "must be a list");
    std::vector<Primitive> out;
    for (std::size_t k = 0; k < list.size(); ++k)
      if (std::optional<Primitive> p = primitive(list[k], where + ".primitives[" + std::to_string(k) + "]"))
        out.push_back(std::move(*p));
    meshes_[m] = std::move(out);
    return *meshes_[m];
  }

  std::optional<Primitive> primitive(const json& j, const std::string& where) {
    object(j, where);
    Primitive p;
    p.where = where;
    const std::uint64_t mode = integer_or(j, "mode", where, 4);
    if (mode > 6) fail(where + ".mode", std::to_string(mode) + " is not a glTF primitive mode (0 to 6)");
    if (mode < 4) return std::nullopt;  // points and lines: no surface
    p.mode = int(mode);
    const std::string at = where + ".attributes";
    const json& attributes = object(required(j, "attributes", where), at);
    const json* position = member(attributes, "POSITION");
    if (!position) return std::nullopt;
    p.position = accessor(*position, at + ".POSITION", "POSITION", 3, false);
    const auto same_count = [&](const Accessor& a, const char* what) {
      if (a.count != p.position.count)
        fail(at + "." + what, "holds " + std::to_string(a.count) + " elements, but POSITION holds " + std::to_string(p.position.count));
    };
    if (const json* n = member(attributes, "NORMAL")) {
      p.normal = accessor(*n, at + ".NORMAL", "NORMAL", 3, false);
      same_count(*p.normal, "NORMAL");
    }
    if (const json* t = member(attributes, "TEXCOORD_0")) {
      p.texcoord = accessor(*t, at + ".TEXCOORD_0", "TEXCOORD_0", 2, false);
      same_count(*p.texcoord, "TEXCOORD_0");
    }
    std::uint64_t corners = p.position.count;
    if (const json* i = member(j, "indices")) {
      p.indices = accessor(*i, where + ".indices", "indices", 1, true);
      corners = p.indices->count;
    }
    if (const json* m = member(j, "material"); m && read_materials_) p.material = material(*m, where + ".material");
    if (p.mode == 4 && corners % 3 != 0)
      fail(where, "holds " + std::to_string(corners) + " corners of triangles, not a multiple of 3");
    p.triangles = p.mode == 4 ? corners / 3 : corners >= 3 ? corners - 2 : 0;
    return p;
  }

  // A node's own transform: `matrix` (column-major, affine) or translation · rotation · scale.
  Placement local(const json& node, const std::string& where) const {
    Placement p;
    if (const json* m = member(node, "matrix")) {
      if (member(node, "translation") || member(node, "rotation") || member(node, "scale"))
        fail(where, "has both a matrix and translation, rotation or scale");
      const std::vector<Real> c = numbers(*m, 16, where + ".matrix");
      if (c[3] != 0 || c[7] != 0 || c[11] != 0 || c[15] != 1)
        fail(where + ".matrix", "is not affine (its last row must be 0 0 0 1)");
      for (int r = 0; r < 3; ++r) p.m.row[r] = Vec3(c[std::size_t(r)], c[std::size_t(4 + r)], c[std::size_t(8 + r)]);
      p.t = Vec3(c[12], c[13], c[14]);
      return p;
    }
    if (const json* t = member(node, "translation")) {
      const std::vector<Real> c = numbers(*t, 3, where + ".translation");
      p.t = Vec3(c[0], c[1], c[2]);
    }
    if (const json* r = member(node, "rotation")) {
      const std::vector<Real> q = numbers(*r, 4, where + ".rotation");  // x, y, z, w
      const Real len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (!(len > 0)) fail(where + ".rotation", "is not a rotation (a quaternion of length 0)");
      const Real x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
      p.m.row[0] = Vec3(1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w));
      p.m.row[1] = Vec3(2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w));
      p.m.row[2] = Vec3(2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y));
    }
    if (const json* s = member(node, "scale")) {
      const std::vector<Real> c = numbers(*s, 3, where + ".scale");
      p.m = p.m * Mat3::scale(Vec3(c[0], c[1], c[2]));
    }
    return p;
  }

  // The default scene's nodes (`scene`, else the first of `scenes`, else every node that is no
  // node's child), depth first, each with its world placement and mesh.
  std::vector<Draw> scene_draws() {
    const json& nodes = array("nodes");
    std::vector<std::size_t> roots;
    const json& scenes = array("scenes");
    if (const json* s = member(root_, "scene"); s || !scenes.empty()) {
      const std::size_t k = s ? index(*s, "scene", "scenes") : 0;
      const std::string where = item("scenes", k);
      const json& scene = object(scenes[k], where);
      if (const json* list = member(scene, "nodes")) {
        if (!list->is_array()) fail(where + ".nodes", "must be a list");
        for (std::size_t i = 0; i < list->size(); ++i)
          roots.push_back(index((*list)[i], where + ".nodes[" + std::to_string(i) + "]", "nodes"));
      }
    } else {
      std::vector<char> child(nodes.size(), 0);
      for (std::size_t i = 0; i < nodes.size(); ++i)
        if (const json* c = member(object(nodes[i], item("nodes", i)), "children"); c && c->is_array())
          for (std::size_t k = 0; k < c->size(); ++k)
            child[index((*c)[k], item("nodes", i) + ".children[" + std::to_string(k) + "]", "nodes")] = 1;
      for (std::size_t i = 0; i < nodes.size(); ++i)
        if (!child[i]) roots.push_back(i);
    }
    std::vector<Draw> draws;
    std::vector<char> seen(nodes.size(), 0);
    std::vector<std::pair<std::size_t, Placement>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, Placement{}});
    while (!stack.empty()) {
      check_cancelled("gltf");
      const auto [i, parent] = stack.back();
      stack.pop_back();
      const std::string where = item("nodes", i);
      if (seen[i]) fail(where, "is reached twice: the nodes of a scene must form trees");
      seen[i] = 1;
      const json& node = object(nodes[i], where);
      const Placement own = local(node, where);
      const Placement at{parent.m * own.m, parent.m * own.t + parent.t};
      if (const json* m = member(node, "mesh")) draws.push_back({index(*m, where + ".mesh", "meshes"), at});
      if (const json* c = member(node, "children")) {
        if (!c->is_array()) fail(where + ".children", "must be a list");
        for (std::size_t k = c->size(); k-- > 0;)
          stack.push_back({index((*c)[k], where + ".children[" + std::to_string(k) + "]", "nodes"), at});
      }
    }
    return draws;
  }

  // One primitive's vertices and triangles, placed, appended to the mesh. A placement that
  // mirrors turns each triangle's corners round, so that its front stays the side its normals face.
  void add(const Primitive& p, const Placement& at, MeshData& mesh) const {
    check_cancelled("gltf");
    const std::size_t base = mesh.positions.size();
    mesh.positions.resize(base + std::size_t(p.position.count));
    read(p.position, [&](std::size_t i, const Real* v) {
      const Vec3 x = at.m * Vec3(v[0], v[1], v[2]) + at.t;
      if (!is_finite(x)) fail(p.where, "a vertex placed by its node's transform is not finite");
      mesh.positions[base + i] = x;
    });
    const Real det = at.m.determinant();
    std::int32_t normal_base = -1, texcoord_base = -1;
    if (p.normal) {
      // Normals by the inverse transpose, as its cofactor matrix (defined for a flat placement too).
      Mat3 cof;
      cof.row[0] = cross(at.m.row[1], at.m.row[2]);
      cof.row[1] = cross(at.m.row[2], at.m.row[0]);
      cof.row[2] = cross(at.m.row[0], at.m.row[1]);
      const Real sign = det < 0 ? -1 : 1;
      normal_base = std::int32_t(mesh.normals.size());
      mesh.normals.resize(mesh.normals.size() + std::size_t(p.normal->count));
      read(*p.normal, [&](std::size_t i, const Real* v) {
        const Vec3 n = sign * (cof * Vec3(v[0], v[1], v[2]));
        mesh.normals[std::size_t(normal_base) + i] = length_squared(n) > 0 && is_finite(n) ? normalize(n) : n;
      });
    }
    if (p.texcoord) {
      // glTF's v runs down the image from its top edge; strahl's (as OBJ's) up from the bottom.
      texcoord_base = std::int32_t(mesh.texcoords.size());
      mesh.texcoords.resize(mesh.texcoords.size() + std::size_t(p.texcoord->count));
      read(*p.texcoord, [&](std::size_t i, const Real* v) { mesh.texcoords[std::size_t(texcoord_base) + i] = {v[0], 1 - v[1]}; });
    }
    std::vector<std::uint32_t> corner;
    if (p.indices) {
      corner.resize(std::size_t(p.indices->count));
      read(*p.indices, [&](std::size_t i, const Real* v) {
        if (v[0] >= Real(p.position.count))
          fail(p.where + ".indices", "element " + std::to_string(i) + " is vertex " + std::to_string(std::uint64_t(v[0])) +
                                        ", but POSITION holds " + std::to_string(p.position.count));
        corner[i] = std::uint32_t(v[0]);
      });
    }
    const auto vertex = [&](std::uint64_t k) { return p.indices ? corner[std::size_t(k)] : std::uint32_t(k); };
    for (std::uint64_t f = 0; f < p.triangles; ++f) {
      // glTF's orders: a strip's odd triangles turn round ({v_i, v_i+2, v_i+1}), a fan's are {v_i+1, v_i+2, v_0}.
      std::uint64_t k[3] = {3 * f, 3 * f + 1, 3 * f + 2};
      if (p.mode == 5) k[0] = f, k[1] = f + 1 + (f & 1), k[2] = f + 2 - (f & 1);
      if (p.mode == 6) k[0] = f + 1, k[1] = f + 2, k[2] = 0;
      if (det < 0) std::swap(k[1], k[2]);
      MeshData::Face face;
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = vertex(k[c]);
        face.v[std::size_t(c)] = std::uint32_t(base) + v;
        if (normal_base >= 0) face.n[std::size_t(c)] = normal_base + std::int32_t(v);
        if (texcoord_base >= 0) face.t[std::size_t(c)] = texcoord_base + std::int32_t(v);
      }
      mesh.faces.push_back(face);
      if (read_materials_) mesh.face_materials.push_back(p.material);
    }
  }

  // ---- materials (read only when asked for) ----

  // The FileMaterial of materials[i] (its slot in materials_, made at its first use): the base
  // colour factor (linear RGB; alpha is not used) and the base colour texture, the picture
  // times the factor, where it reads TEXCOORD_0.
  std::int32_t material(const json& ref, const std::string& ref_where) {
    const std::size_t i = index(ref, ref_where, "materials");
    if (material_slots_[i] >= 0) return material_slots_[i];
    const std::string where = item("materials", i);
    const json& m = object(array("materials")[i], where);
    FileMaterial out;
    if (const json* n = member(m, "name"); n && n->is_string()) out.name = n->get<std::string>();
    if (const json* pbr = member(m, "pbrMetallicRoughness")) {
      const std::string at = where + ".pbrMetallicRoughness";
      object(*pbr, at);
      if (const json* f = member(*pbr, "baseColorFactor")) {
        const std::vector<Real> c = numbers(*f, 4, at + ".baseColorFactor");
        for (std::size_t k = 0; k < 4; ++k)
          if (c[k] < 0 || c[k] > 1) fail(at + ".baseColorFactor", "must hold numbers from 0 to 1");
        out.color = Vec3(c[0], c[1], c[2]);
      }
      if (const json* t = member(*pbr, "baseColorTexture")) {
        object(*t, at + ".baseColorTexture");
        if (integer_or(*t, "texCoord", at + ".baseColorTexture", 0) == 0)
          texture(required(*t, "index", at + ".baseColorTexture"), at + ".baseColorTexture.index", out);
      }
    }
    materials_.push_back(std::move(out));
    material_slots_[i] = std::int32_t(materials_.size() - 1);
    return material_slots_[i];
  }

  // textures[i]'s picture (decoded once, then times the material's colour) and its sampler's
  // magnification filter (NEAREST: the nearest pixel; else bilinear).
  void texture(const json& ref, const std::string& ref_where, FileMaterial& out) {
    const std::size_t i = index(ref, ref_where, "textures");
    const std::string where = item("textures", i);
    const json& t = object(array("textures")[i], where);
    const json* source = member(t, "source");
    if (!source) return;  // (a texture whose picture is in an extension's format: the colour alone)
    const std::size_t k = index(*source, where + ".source", "images");
    if (const json* s = member(t, "sampler")) {
      const std::size_t si = index(*s, where + ".sampler", "samplers");
      const std::string sw = item("samplers", si);
      const json& sampler = object(array("samplers")[si], sw);
      out.bilinear = integer_or(sampler, "magFilter", sw, 9729) != 9728;  // 9728 NEAREST, 9729 LINEAR
    }
    out.image = tinted(image(k), out.color);
  }

  // images[k]: a PNG or JPEG in a file, a data: URI or a bufferView, decoded from sRGB.
  std::shared_ptr<const Image> image(std::size_t k) {
    if (images_[k]) return images_[k];
    const std::string where = item("images", k);
    const json& im = object(array("images")[k], where);
    std::string_view bytes;
    LargeArray<char> held;
    if (const json* u = member(im, "uri")) {
      held = uri_bytes(*u, where + ".uri");
      bytes = std::string_view(held.data(), held.size());
    } else if (const json* v = member(im, "bufferView")) {
      bytes = buffer_view(index(*v, where + ".bufferView", "bufferViews")).first;
    } else {
      fail(where, "has neither uri nor bufferView");
    }
    try {
      images_[k] = decode_texture_image(bytes, where);
    } catch (const Error& e) {
      fail("", e.what());
    }
    return images_[k];
  }

  std::string name_;
  std::filesystem::path dir_;
  std::uint64_t file_size_;
  std::uint64_t max_triangles_;
  gltf::Container container_;
  json root_;
  std::deque<LargeArray<char>> owned_;                    // decoded data: URIs and buffer files
  std::vector<std::optional<std::string_view>> buffers_;  // each buffer's bytes, once read
  std::vector<std::optional<std::vector<Primitive>>> meshes_;
  bool read_materials_;
  std::vector<FileMaterial> materials_;             // those the drawn primitives use, in order of use
  std::vector<std::int32_t> material_slots_;        // materials[i]'s index in materials_, −1 not yet
  std::vector<std::shared_ptr<const Image>> images_;  // decoded pictures, once each
};

}  // namespace

MeshData load_gltf(const std::filesystem::path& path, bool materials) {
  const LargeArray<char> bytes = read_mesh_file(path);
  return parse_gltf(std::string_view(bytes.data(), bytes.size()), path.string(), path.parent_path(), materials);
}

MeshData parse_gltf(std::string_view bytes, const std::string& name, const std::filesystem::path& dir, bool materials,
                    std::uint64_t max_triangles) {
  return GltfReader(bytes, name, dir, materials, max_triangles).read();
}

}  // namespace strahl
