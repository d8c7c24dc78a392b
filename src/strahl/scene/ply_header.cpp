// The PLY reader's header (ply_header.h): its lines parsed into elements and properties, the
// roles of the vertex and face properties assigned, and the element counts checked against the
// size of the file.

#include "strahl/scene/ply_header.h"

#include <algorithm>
#include <charconv>
#include <system_error>

namespace strahl::ply {
namespace {

struct TypeName {
  std::string_view name;
  Type type;
};
constexpr TypeName kTypeNames[] = {
    {"char", Type::Int8},     {"int8", Type::Int8},      {"uchar", Type::UInt8},    {"uint8", Type::UInt8},
    {"short", Type::Int16},   {"int16", Type::Int16},    {"ushort", Type::UInt16},  {"uint16", Type::UInt16},
    {"int", Type::Int32},     {"int32", Type::Int32},    {"uint", Type::UInt32},    {"uint32", Type::UInt32},
    {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};

bool parse_type(std::string_view s, Type& t) {
  for (const TypeName& n : kTypeNames)
    if (n.name == s) {
      t = n.type;
      return true;
    }
  return false;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

}  // namespace

std::string number_str(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e18) return std::to_string(static_cast<long long>(v));
  return std::to_string(v);
}

Header Parser::header() const {
  Header h;
  std::size_t pos = 0;
  long long line = 0;
  std::string_view text;
  const auto next_line = [&]() {
    if (pos >= data_.size()) return false;
    const std::size_t nl = data_.find('\n', pos);
    const std::size_t end = nl == std::string_view::npos ? data_.size() : nl;
    text = data_.substr(pos, end - pos);
    pos = nl == std::string_view::npos ? data_.size() : nl + 1;
    ++line;
    return true;
  };
  if (!next_line() || split(text) != std::vector<std::string_view>{"ply"})
    fail(1, "not a PLY file (the first line must be 'ply')");

  bool have_format = false;
  bool ended = false;
  while (!ended && next_line()) {
    // Comments may hold anything: look at the keyword only.
    std::size_t k = 0;
    while (k < text.size() && is_space(text[k])) ++k;
    std::size_t k_end = k;
    while (k_end < text.size() && !is_space(text[k_end])) ++k_end;
    const std::string_view keyword = text.substr(k, k_end - k);
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    const std::vector<std::string_view> t = split(text);
    if (keyword == "format") {
      if (have_format) fail(line, "the header has a second 'format' line");
      if (t.size() != 3) fail(line, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (t[1] == "ascii") h.format = Format::Ascii;
      else if (t[1] == "binary_little_endian") h.format = Format::BinaryLittleEndian;
      else if (t[1] == "binary_big_endian") h.format = Format::BinaryBigEndian;
      else
        fail(line, "unknown PLY format '" + std::string(t[1]) +
                       "' (ascii, binary_little_endian or binary_big_endian)");
      if (t[2] != "1.0" && t[2] != "1") fail(line, "unsupported PLY version '" + std::string(t[2]) + "' (only 1.0)");
      have_format = true;
    } else if (keyword == "element") {
      if (t.size() != 3) fail(line, "expected 'element <name> <count>'");
      Element e;
      e.name = std::string(t[1]);
      e.line = line;
      e.count = element_count(t[2], e.name, line);
      h.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (h.elements.empty()) fail(line, "'property' before the first 'element'");
      Property p;
      p.line = line;
      if (t.size() >= 2 && t[1] == "list") {
        if (t.size() != 5) fail(line, "expected 'property list <count type> <item type> <name>'");
        p.list = true;
        if (!parse_type(t[2], p.count_type)) fail(line, "unknown property type '" + std::string(t[2]) + "'");
        if (!parse_type(t[3], p.type)) fail(line, "unknown property type '" + std::string(t[3]) + "'");
        p.name = std::string(t[4]);
      } else {
        if (t.size() != 3) fail(line, "expected 'property <type> <name>' or 'property list <count type> <item type> <name>'");
        if (!parse_type(t[1], p.type)) fail(line, "unknown property type '" + std::string(t[1]) + "'");
        p.name = std::string(t[2]);
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (keyword == "end_header") {
      if (t.size() != 1) fail(line, "unexpected text after 'end_header'");
      ended = true;
    } else {
      fail(line, "unknown header line '" + std::string(keyword) +
                     "' (expected format, element, property, comment, obj_info or end_header)");
    }
  }
  if (!ended) fail(line, "the header has no 'end_header' line");
  if (!have_format) fail(line, "the header has no 'format' line");
  h.body_offset = pos;
  h.body_line = line + 1;

  if (h.elements.size() > INT_MAX) fail(line, "too many elements");
  for (std::size_t i = 0; i < h.elements.size(); ++i) {
    Element& e = h.elements[i];
    if (e.count > 0 && e.properties.empty())
      fail(e.line, "element '" + e.name + "' has " + std::to_string(e.count) + " entries but no properties");
    if (e.name == "vertex") assign_vertex_roles(h, e, static_cast<int>(i));
    else if (e.name == "face") assign_face_roles(h, e, static_cast<int>(i));
  }
  if (h.vertex < 0) fail(line, "the file has no 'vertex' element");
  if (h.face < 0) fail(line, "the file has no 'face' element (a PLY point cloud cannot be rendered)");
  check_sizes(h);
  return h;
}

long long Parser::element_count(std::string_view s, const std::string& name, long long line) const {
  long long count = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), count);
  if (ec == std::errc::result_out_of_range) fail(line, "element '" + name + "' count " + std::string(s) + " is too large");
  if (ec != std::errc() || ptr != s.data() + s.size())
    fail(line, "element '" + name + "' count must be a whole number (got '" + std::string(s) + "')");
  if (count < 0) fail(line, "element '" + name + "' has a negative count (" + std::string(s) + ")");
  return count;
}

void Parser::assign_vertex_roles(Header& h, Element& e, int index) const {
  if (h.vertex >= 0) fail(e.line, "the header has a second 'vertex' element");
  h.vertex = index;
  if (e.count > INT_MAX) fail(e.line, "too many vertices (" + std::to_string(e.count) + "; at most 2147483647)");
  // Each role's names (texture coordinates go by four pairs of names in the files around).
  static constexpr std::string_view kNames[kVertexRoles][4] = {
      {"x"}, {"y"}, {"z"}, {"nx"}, {"ny"}, {"nz"}, {"u", "s", "texture_u", "texture_s"},
      {"v", "t", "texture_v", "texture_t"}};
  Property* found[kVertexRoles] = {};
  constexpr int kU = int(Role::U), kV = int(Role::V);
  for (Property& p : e.properties)
    for (int i = 0; i < kVertexRoles; ++i)
      for (const std::string_view name : kNames[i])
        if (!name.empty() && p.name == name) {
          if (found[i] && found[i]->name == p.name) fail(p.line, "property '" + p.name + "' appears twice in element 'vertex'");
          if (found[i])
            fail(p.line, "properties '" + found[i]->name + "' and '" + p.name +
                             "' of element 'vertex' both give the texture coordinate " + (i == kU ? "u" : "v"));
          if (p.list) fail(p.line, "property '" + p.name + "' of element 'vertex' must be a single value, not a list");
          found[i] = &p;
        }
  for (int i = 0; i < 3; ++i)
    if (!found[i])
      fail(e.line, "element 'vertex' has no property '" + std::string(kNames[i][0]) + "' (x, y and z are required)");
  for (int i = 0; i < 3; ++i) found[i]->role = static_cast<Role>(i);
  // Normals are used only when all three components are there.
  h.normals = found[3] && found[4] && found[5];
  if (h.normals)
    for (int i = 3; i < 6; ++i) found[i]->role = static_cast<Role>(i);
  // Texture coordinates likewise only as a pair.
  h.texcoords = found[kU] && found[kV];
  if (h.texcoords)
    for (const int i : {kU, kV}) found[i]->role = static_cast<Role>(i);
}

void Parser::assign_face_roles(Header& h, Element& e, int index) const {
  if (h.face >= 0) fail(e.line, "the header has a second 'face' element");
  h.face = index;
  Property* indices = nullptr;
  for (Property& p : e.properties)
    if (p.name == "vertex_indices" || p.name == "vertex_index") {
      if (indices) fail(p.line, "element 'face' has a second list of vertex indices ('" + p.name + "')");
      if (!p.list) fail(p.line, "property '" + p.name + "' of element 'face' must be a list");
      indices = &p;
    }
  if (!indices) fail(e.line, "element 'face' has no list property 'vertex_indices' (or 'vertex_index')");
  indices->role = Role::Indices;
}

// The fewest bytes one entry of `e` can take: binary scalars at their size, lists at their
// count's size (vertex index lists with three items), ascii values at one character and a
// separator each.
std::uint64_t Parser::min_entry_bytes(const Header& h, const Element& e) {
  std::uint64_t bytes = 0, values = 0;
  for (const Property& p : e.properties) {
    const std::uint64_t items = p.role == Role::Indices ? 3 : 0;
    bytes += p.list ? size_of(p.count_type) + items * size_of(p.type) : size_of(p.type);
    values += 1 + (p.list ? items : 0);
  }
  return h.format == Format::Ascii ? 2 * values : bytes;
}

// Before anything is allocated: can the data after the header hold what the header declares?
void Parser::check_sizes(const Header& h) const {
  // An ascii body may lack the last newline: allow one byte more.
  const std::uint64_t body = data_.size() - h.body_offset + (h.format == Format::Ascii ? 1 : 0);
  std::uint64_t used = 0;
  for (const Element& e : h.elements) {
    if (e.count == 0) continue;
    const std::uint64_t per_entry = min_entry_bytes(h, e);  // ≥ 1: e has properties
    const std::uint64_t left = body - used;
    const std::uint64_t fits = left / per_entry;
    if (static_cast<std::uint64_t>(e.count) > fits)
      fail(e.line, "element '" + e.name + "' declares " + std::to_string(e.count) +
                       " entries, but the file is too short for them: " + std::to_string(left) +
                       " bytes of data are left and each entry takes at least " + std::to_string(per_entry) +
                       " (the file is truncated or the count is wrong)");
    used += static_cast<std::uint64_t>(e.count) * per_entry;
  }
}

}  // namespace strahl::ply
