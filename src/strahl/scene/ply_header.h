#pragma once
// The PLY reader's header (ply_loader.h is the interface): the property types, the elements and
// properties a header declares, and the parser that reads and checks it — every element count
// against the bytes left in the file, before anything is allocated. ply_loader.cpp reads the body.

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/util/error.h"

namespace strahl::ply {

enum class Type : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

inline const char* type_name(Type t) {
  switch (t) {
    case Type::Int8: return "char";
    case Type::UInt8: return "uchar";
    case Type::Int16: return "short";
    case Type::UInt16: return "ushort";
    case Type::Int32: return "int";
    case Type::UInt32: return "uint";
    case Type::Float32: return "float";
    case Type::Float64: return "double";
  }
  return "?";
}

inline std::size_t size_of(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 1;
}

// The range of an integer type (as doubles, which hold every 32-bit integer exactly).
inline void int_range(Type t, double& lo, double& hi) {
  switch (t) {
    case Type::Int8: lo = -128, hi = 127; return;
    case Type::UInt8: lo = 0, hi = 255; return;
    case Type::Int16: lo = -32768, hi = 32767; return;
    case Type::UInt16: lo = 0, hi = 65535; return;
    case Type::Int32: lo = -2147483648.0, hi = 2147483647.0; return;
    case Type::UInt32: lo = 0, hi = 4294967295.0; return;
    case Type::Float32:
    case Type::Float64: break;
  }
  lo = -HUGE_VAL, hi = HUGE_VAL;
}

// What the reader does with a property.
enum class Role : std::uint8_t { X, Y, Z, NX, NY, NZ, U, V, Indices, Skip };
inline constexpr int kVertexRoles = 8;  // X … V: the slots of one vertex's values

struct Property {
  std::string name;
  Type type = Type::Float32;  // the item type of a list
  bool list = false;
  Type count_type = Type::UInt8;
  long long line = 0;
  Role role = Role::Skip;
};

struct Element {
  std::string name;
  long long count = 0;
  long long line = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // the first byte after the end_header line
  long long body_line = 0;      // the line number of the first body line
  int vertex = -1;  // indices into elements
  int face = -1;
  bool normals = false;  // the vertex element has nx, ny and nz
  bool texcoords = false;  // … and u, v (or s, t; texture_u, texture_v; texture_s, texture_t)
};

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// A number in a message: whole numbers without a fraction.
std::string number_str(double v);

// Reads the header of the PLY file `data` (named `file` in errors); its fail() is the reader's
// one way to report an error with the file's name and a line.
class Parser {
 public:
  Parser(std::string file, std::string_view data) : file_(std::move(file)), data_(data) {}

  [[noreturn]] void fail(long long line, const std::string& message) const {
    throw Error(FileLoc{file_, static_cast<int>(std::clamp<long long>(line, 0, INT_MAX))}, message);
  }
  [[noreturn]] void fail(const std::string& message) const { throw Error(FileLoc{file_}, message); }

  // The header, checked: a vertex element with x, y and z, a face element with vertex indices,
  // and counts the bytes after the header can hold.
  Header header() const;

 private:
  long long element_count(std::string_view s, const std::string& name, long long line) const;
  void assign_vertex_roles(Header& h, Element& e, int index) const;
  void assign_face_roles(Header& h, Element& e, int index) const;
  static std::uint64_t min_entry_bytes(const Header& h, const Element& e);
  void check_sizes(const Header& h) const;

  std::string file_;
  std::string_view data_;
};

}  // namespace strahl::ply
