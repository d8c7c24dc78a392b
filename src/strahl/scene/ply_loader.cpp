// A PLY reader written for strahl: the header is parsed into elements and properties, every
// element count is checked against the bytes left in the file, then one templated walker reads
// the body from either an ascii source (one element per line, std::from_chars) or a bounded
// binary source (little- or big-endian). Nothing reads past the end of the file contents.

#include "strahl/scene/ply_loader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

#include "strahl/scene/mesh_file.h"
#include "strahl/scene/ply_header.h"
#include "strahl/util/cancel.h"
#include "strahl/util/error.h"

namespace strahl {
namespace {

using ply::Element;
using ply::Format;
using ply::Header;
using ply::Parser;
using ply::Property;
using ply::Role;
using ply::Type;
using ply::int_range;
using ply::is_space;
using ply::number_str;
using ply::kVertexRoles;
using ply::size_of;
using ply::type_name;

// An ascii body: one element entry per line (blank lines are skipped), values separated by
// spaces or tabs.
class AsciiSource {
 public:
  AsciiSource(const Parser& parser, std::string_view body, long long first_line)
      : parser_(parser), body_(body), line_(first_line - 1) {}

  void begin(const std::string& what, long long index, long long count) {
    what_ = &what;
    index_ = index;
    for (;;) {
      if (pos_ >= body_.size())
        parser_.fail(line_, "unexpected end of file: the header declares " + std::to_string(count) + " '" + what +
                                "' entries, the file has " + std::to_string(index));
      const std::size_t nl = body_.find('\n', pos_);
      const std::size_t end = nl == std::string_view::npos ? body_.size() : nl;
      cur_ = body_.data() + pos_;
      end_ = body_.data() + end;
      pos_ = nl == std::string_view::npos ? body_.size() : nl + 1;
      ++line_;
      while (cur_ != end_ && is_space(*cur_)) ++cur_;
      if (cur_ != end_) return;
    }
  }

  void end() {
    while (cur_ != end_ && is_space(*cur_)) ++cur_;
    if (cur_ != end_)
      fail("too many values for " + *what_ + " " + std::to_string(index_) + " (the header declares fewer)");
  }

  double number(Type t) { return parse(token(), t); }
  void skip(Type) { token(); }
  void skip_items(Type t, std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) skip(t);
  }
  void need_items(Type, std::uint64_t) {}  // ascii items are read one by one, none allocated ahead

  void finish() {
    for (std::size_t i = pos_; i < body_.size(); ++i) {
      if (body_[i] == '\n') ++line_;
      else if (!is_space(body_[i])) parser_.fail(line_ + 1, "unexpected data after the last element");
    }
  }

  [[noreturn]] void fail(const std::string& message) const { parser_.fail(line_, message); }

 private:
  std::string_view token() {
    while (cur_ != end_ && is_space(*cur_)) ++cur_;
    if (cur_ == end_) fail("too few values for " + *what_ + " " + std::to_string(index_));
    const char* start = cur_;
    while (cur_ != end_ && !is_space(*cur_)) ++cur_;
    return {start, static_cast<std::size_t>(cur_ - start)};
  }

  double parse(std::string_view s, Type t) const {
    const char* b = s.data();
    const char* e = b + s.size();
    if (e - b >= 2 && *b == '+' && b[1] != '-' && b[1] != '+') ++b;  // from_chars takes no '+'
    const auto bad = [&]() {
      fail("'" + std::string(s) + "' is not a valid " + type_name(t) + " (in " + *what_ + " " +
           std::to_string(index_) + ")");
    };
    const auto out_of_range = [&]() {
      fail("value " + std::string(s) + " is out of range for " + type_name(t) + " (in " + *what_ + " " +
           std::to_string(index_) + ")");
    };
    if (t == Type::Float32) {
      float v = 0;
      const auto r = std::from_chars(b, e, v);
      if (r.ec == std::errc::result_out_of_range) out_of_range();
      if (r.ec != std::errc() || r.ptr != e) bad();
      return v;
    }
    double v = 0;
    if (t == Type::Float64) {
      const auto r = std::from_chars(b, e, v);
      if (r.ec == std::errc::result_out_of_range) out_of_range();
      if (r.ec != std::errc() || r.ptr != e) bad();
      return v;
    }
    long long i = 0;
    const auto r = std::from_chars(b, e, i);
    if (r.ec == std::errc() && r.ptr == e) {
      v = static_cast<double>(i);
    } else if (r.ec == std::errc::result_out_of_range) {
      out_of_range();
    } else {
      // Some writers give whole numbers as "3.0".
      const auto rd = std::from_chars(b, e, v);
      if (rd.ec != std::errc() || rd.ptr != e || !std::isfinite(v) || v != std::floor(v)) bad();
    }
    double lo = 0, hi = 0;
    int_range(t, lo, hi);
    if (!(v >= lo && v <= hi)) out_of_range();
    return v;
  }

  const Parser& parser_;
  std::string_view body_;
  std::size_t pos_ = 0;
  long long line_;
  const char* cur_ = nullptr;
  const char* end_ = nullptr;
  const std::string* what_ = nullptr;
  long long index_ = 0;
};

template <class T>
T load_raw(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// A binary body, read through a cursor that never passes the end of the file contents.
class BinarySource {
 public:
  BinarySource(const Parser& parser, std::string_view data, std::size_t offset, bool big_endian)
      : parser_(parser),
        begin_(reinterpret_cast<const unsigned char*>(data.data())),
        p_(begin_ + offset),
        end_(begin_ + data.size()),
        swap_(big_endian != (std::endian::native == std::endian::big)) {}

  void begin(const std::string& what, long long index, long long count) {
    what_ = &what;
    index_ = index;
    count_ = count;
    entry_ = p_;
  }
  void end() {}

  double number(Type t) {
    const std::size_t n = size_of(t);
    need(n);
    const double v = load(p_, t);
    p_ += n;
    return v;
  }
  void skip(Type t) {
    const std::size_t n = size_of(t);
    need(n);
    p_ += n;
  }
  void need_items(Type t, std::uint64_t n) {
    if (n > static_cast<std::uint64_t>(end_ - p_) / size_of(t)) truncated();
  }
  void skip_items(Type t, std::uint64_t n) {
    need_items(t, n);
    p_ += n * size_of(t);
  }
  void finish() {}  // bytes after the last element are ignored

  // For the fast paths, which read whole entries (or a whole element) at once.
  // The size of one entry of an element of scalars only; 0 if it has a list.
  static std::uint64_t fixed_stride(const Element& e) {
    std::uint64_t stride = 0;
    for (const Property& p : e.properties) {
      if (p.list) return 0;
      stride += size_of(p.type);
    }
    return stride;
  }
  // The next n bytes, or a truncation error.
  const unsigned char* take(std::uint64_t n) {
    if (n > static_cast<std::uint64_t>(end_ - p_)) truncated();
    const unsigned char* p = p_;
    p_ += n;
    return p;
  }
  const unsigned char* take_items(Type t, std::uint64_t n) {
    need_items(t, n);
    return take(n * size_of(t));
  }
  // Which entry a later fail() names.
  void at(long long index, const unsigned char* entry) {
    index_ = index;
    entry_ = entry;
  }
  const unsigned char* position() const { return p_; }
  double value(const unsigned char* p, Type t) const { return load(p, t); }
  // An integer type's value.
  std::int64_t integer(const unsigned char* p, Type t) const {
    switch (t) {
      case Type::Int8: return load_raw<std::int8_t>(p, swap_);
      case Type::UInt8: return load_raw<std::uint8_t>(p, swap_);
      case Type::Int16: return load_raw<std::int16_t>(p, swap_);
      case Type::UInt16: return load_raw<std::uint16_t>(p, swap_);
      case Type::Int32: return load_raw<std::int32_t>(p, swap_);
      case Type::UInt32: return load_raw<std::uint32_t>(p, swap_);
      case Type::Float32:
      case Type::Float64: break;
    }
    return -1;
  }

  [[noreturn]] void fail(const std::string& message) const {
    parser_.fail(message + " (at byte " + std::to_string(entry_ - begin_) + ")");
  }

 private:
  void need(std::size_t n) {
    if (static_cast<std::size_t>(end_ - p_) < n) truncated();
  }
  [[noreturn]] void truncated() const {
    parser_.fail("unexpected end of file at byte " + std::to_string(end_ - begin_) + ": the header declares " +
                 std::to_string(count_) + " '" + *what_ + "' entries, the file ends in entry " +
                 std::to_string(index_));
  }
  double load(const unsigned char* p, Type t) const {
    switch (t) {
      case Type::Int8: return load_raw<std::int8_t>(p, swap_);
      case Type::UInt8: return load_raw<std::uint8_t>(p, swap_);
      case Type::Int16: return load_raw<std::int16_t>(p, swap_);
      case Type::UInt16: return load_raw<std::uint16_t>(p, swap_);
      case Type::Int32: return load_raw<std::int32_t>(p, swap_);
      case Type::UInt32: return load_raw<std::uint32_t>(p, swap_);
      case Type::Float32: return static_cast<double>(load_raw<float>(p, swap_));
      case Type::Float64: return load_raw<double>(p, swap_);
    }
    return 0;
  }

  const Parser& parser_;
  const unsigned char* begin_;
  const unsigned char* p_;
  const unsigned char* end_;
  bool swap_;
  const unsigned char* entry_ = nullptr;
  const std::string* what_ = nullptr;
  long long index_ = 0, count_ = 0;
};

// The length of a list: a whole number ≥ 0 whatever its type.
template <class Source>
std::uint64_t list_length(Source& src, const Property& p) {
  const double n = src.number(p.count_type);
  if (!(n >= 0 && n <= 4294967295.0) || n != std::floor(n))
    src.fail("list '" + p.name + "' has length " + number_str(n) + " (a whole number from 0 to 4294967295 is needed)");
  return static_cast<std::uint64_t>(n);
}

template <class Source>
void skip_element(Source& src, const Element& e) {
  if constexpr (std::is_same_v<Source, BinarySource>) {
    // Scalars only: skipped in one step.
    if (const std::uint64_t stride = BinarySource::fixed_stride(e)) {
      src.begin(e.name, 0, e.count);
      src.take(static_cast<std::uint64_t>(e.count) * stride);  // cannot overflow: check_sizes() passed
      return;
    }
  }
  for (long long i = 0; i < e.count; ++i) {
    if ((i & 0xfff) == 0) check_cancelled("ply");
    src.begin(e.name, i, e.count);
    for (const Property& p : e.properties) {
      if (p.list) src.skip_items(p.type, list_length(src, p));
      else src.skip(p.type);
    }
    src.end();
  }
}

// Checks and stores vertex i: v holds x, y, z, nx, ny, nz, u, v (by Role).
template <class Source>
void store_vertex(Source& src, long long i, const double (&v)[kVertexRoles], const Header& h, MeshData& mesh) {
  if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    src.fail("vertex " + std::to_string(i) + " has a coordinate that is not a finite number");
  mesh.positions.emplace_back(v[0], v[1], v[2]);  // entries come in order: i == size()
  if (h.normals) {
    if (!std::isfinite(v[3]) || !std::isfinite(v[4]) || !std::isfinite(v[5]))
      src.fail("vertex " + std::to_string(i) + " has a normal that is not finite");
    mesh.normals.emplace_back(v[3], v[4], v[5]);
  }
  if (h.texcoords) {
    if (!std::isfinite(v[6]) || !std::isfinite(v[7]))
      src.fail("vertex " + std::to_string(i) + " has a texture coordinate that is not finite");
    mesh.texcoords.push_back({v[6], v[7]});
  }
}

template <class Source>
void read_vertices(Source& src, const Element& e, const Header& h, MeshData& mesh) {
  if constexpr (std::is_same_v<Source, BinarySource>) {
    // Scalars only (the usual case): fixed offsets in entries of a fixed size.
    if (const std::uint64_t stride = BinarySource::fixed_stride(e)) {
      struct Field {
        std::size_t offset;
        Type type;
        int slot;
      };
      Field fields[kVertexRoles];
      int used = 0;
      std::size_t offset = 0;
      for (const Property& p : e.properties) {
        if (p.role != Role::Skip) fields[used++] = {offset, p.type, static_cast<int>(p.role)};
        offset += size_of(p.type);
      }
      src.begin(e.name, 0, e.count);
      const unsigned char* entry = src.take(static_cast<std::uint64_t>(e.count) * stride);
      for (long long i = 0; i < e.count; ++i, entry += stride) {
        if ((i & 0xfff) == 0) check_cancelled("ply");
        double v[kVertexRoles] = {};
        for (int f = 0; f < used; ++f) v[fields[f].slot] = src.value(entry + fields[f].offset, fields[f].type);
        src.at(i, entry);
        store_vertex(src, i, v, h, mesh);
      }
      return;
    }
  }
  for (long long i = 0; i < e.count; ++i) {
    if ((i & 0xfff) == 0) check_cancelled("ply");
    src.begin(e.name, i, e.count);
    double v[kVertexRoles] = {};
    for (const Property& p : e.properties) {
      if (p.list) src.skip_items(p.type, list_length(src, p));
      else if (p.role == Role::Skip) src.skip(p.type);
      else v[static_cast<int>(p.role)] = src.number(p.type);
    }
    src.end();
    store_vertex(src, i, v, h, mesh);
  }
}

// A fan around the first corner: (0, 1, 2), (0, 2, 3), … (normals and texture coordinates are per
// vertex).
void add_fan(const std::vector<std::uint32_t>& corners, const Header& h, MeshData& mesh) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    MeshData::Face f;
    f.v = {corners[0], corners[k], corners[k + 1]};
    if (h.normals)
      for (std::size_t c = 0; c < 3; ++c) f.n[c] = static_cast<std::int32_t>(f.v[c]);
    if (h.texcoords)
      for (std::size_t c = 0; c < 3; ++c) f.t[c] = static_cast<std::int32_t>(f.v[c]);
    mesh.faces.push_back(f);
  }
}

bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

template <class Source>
[[noreturn]] void bad_corner(Source& src, long long face, const std::string& index, long long vertex_count) {
  src.fail("face " + std::to_string(face) + " refers to vertex " + index + ", but the file has " +
           std::to_string(vertex_count) + " vertices (numbered from 0)");
}

template <class Source>
void read_faces(Source& src, const Element& e, long long vertex_count, const Header& h, MeshData& mesh) {
  std::vector<std::uint32_t> corners;
  if constexpr (std::is_same_v<Source, BinarySource>) {
    // Only an index list of integers (the usual case): no conversions through double.
    if (e.properties.size() == 1 && is_integer(e.properties[0].count_type) && is_integer(e.properties[0].type)) {
      const Property& p = e.properties[0];
      const std::size_t count_size = size_of(p.count_type), index_size = size_of(p.type);
      const auto vertices = static_cast<std::uint64_t>(vertex_count);
      src.begin(e.name, 0, e.count);
      for (long long i = 0; i < e.count; ++i) {
        if ((i & 0xfff) == 0) check_cancelled("ply");
        src.at(i, src.position());
        const std::int64_t n = src.integer(src.take(count_size), p.count_type);
        if (n < 0)
          src.fail("list '" + p.name + "' has length " + std::to_string(n) +
                   " (a whole number from 0 to 4294967295 is needed)");
        if (n < 3)
          src.fail("face " + std::to_string(i) + " has " + std::to_string(n) + " vertices (a face needs at least 3)");
        const unsigned char* q = src.take_items(p.type, static_cast<std::uint64_t>(n));
        corners.resize(static_cast<std::size_t>(n));
        for (std::size_t k = 0; k < corners.size(); ++k, q += index_size) {
          const std::int64_t index = src.integer(q, p.type);
          // A negative index wraps to a huge unsigned one.
          if (static_cast<std::uint64_t>(index) >= vertices) bad_corner(src, i, std::to_string(index), vertex_count);
          corners[k] = static_cast<std::uint32_t>(index);
        }
        add_fan(corners, h, mesh);
      }
      return;
    }
  }
  const double vertices = static_cast<double>(vertex_count);
  for (long long i = 0; i < e.count; ++i) {
    if ((i & 0xfff) == 0) check_cancelled("ply");
    src.begin(e.name, i, e.count);
    for (const Property& p : e.properties) {
      if (!p.list) {
        src.skip(p.type);
        continue;
      }
      const std::uint64_t n = list_length(src, p);
      if (p.role != Role::Indices) {
        src.skip_items(p.type, n);
        continue;
      }
      if (n < 3)
        src.fail("face " + std::to_string(i) + " has " + std::to_string(n) + " vertices (a face needs at least 3)");
      src.need_items(p.type, n);
      corners.clear();
      for (std::uint64_t k = 0; k < n; ++k) {
        const double index = src.number(p.type);
        if (!(index >= 0 && index < vertices) || index != std::floor(index))
          bad_corner(src, i, number_str(index), vertex_count);
        corners.push_back(static_cast<std::uint32_t>(index));
      }
      add_fan(corners, h, mesh);
    }
    src.end();
  }
}

template <class Source>
void read_body(Source& src, const Header& h, MeshData& mesh) {
  const long long vertex_count = h.elements[std::size_t(h.vertex)].count;
  for (std::size_t i = 0; i < h.elements.size(); ++i) {
    const Element& e = h.elements[i];
    if (int(i) == h.vertex) read_vertices(src, e, h, mesh);
    else if (int(i) == h.face) read_faces(src, e, vertex_count, h, mesh);
    else skip_element(src, e);
  }
  src.finish();
}

}  // namespace

MeshData load_ply(const std::filesystem::path& path) {
  const LargeArray<char> bytes = read_mesh_file(path);
  return parse_ply(std::string_view(bytes.data(), bytes.size()), path.string());
}

MeshData parse_ply(std::string_view bytes, const std::string& name) {
  const Parser parser(name, bytes);
  const Header h = parser.header();

  MeshData mesh;
  // The counts passed check_sizes(): these allocations are bounded by the file's size.
  const auto vertex_count = static_cast<std::size_t>(h.elements[std::size_t(h.vertex)].count);
  const auto face_count = static_cast<std::size_t>(h.elements[std::size_t(h.face)].count);
  mesh.positions.reserve(vertex_count);
  if (h.normals) mesh.normals.reserve(vertex_count);
  if (h.texcoords) mesh.texcoords.reserve(vertex_count);
  mesh.faces.reserve(face_count);
  if (h.format == Format::Ascii) {
    AsciiSource src(parser, bytes.substr(h.body_offset), h.body_line);
    read_body(src, h, mesh);
  } else {
    BinarySource src(parser, bytes, h.body_offset, h.format == Format::BinaryBigEndian);
    read_body(src, h, mesh);
  }
  if (mesh.faces.empty()) parser.fail("PLY file contains no faces");
  return mesh;
}

}  // namespace strahl
