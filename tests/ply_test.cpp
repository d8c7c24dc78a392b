// The PLY reader: the same mesh as ascii PLY, binary PLY (both byte orders) and OBJ loads to the
// same MeshData and renders the same image; every scalar type parses; every malformed file is a
// strahl::Error naming the file (and the line where there is one); truncated and mutated files
// never crash.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "strahl/scene/obj_loader.h"
#include "strahl/scene/ply_loader.h"
#include "strahl/strahl.h"
#include "test_helpers.h"

namespace ply_test {
namespace {

namespace fs = std::filesystem;
using strahl::MeshData;

// A scratch directory per test, removed afterwards.
class PlyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("strahl-ply-test-" + std::to_string(std::random_device{}()) + "-" + std::string(info->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const std::string& name, const std::string& bytes) const {
    const fs::path p = dir_ / name;
    // A new file rather than a truncated one: ext4 flushes files truncated and rewritten on close.
    std::error_code ec;
    fs::remove(p, ec);
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return p;
  }
  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// The test mesh: a pyramid on a rhombus. The base is a quad whose diagonal 0–2 is the shorter one,
// so the OBJ reader (which splits convex quads along the shorter diagonal) and the PLY reader's fan
// (0, 1, 2), (0, 2, 3) triangulate it alike. Coordinates are exact in float and in decimal.

struct TestMesh {
  std::vector<std::array<double, 3>> v, n;
  std::vector<std::vector<int>> faces;
};

const TestMesh kPyramid = {
    {{0, 0, -0.5}, {1, 0, 0}, {0, 0, 0.5}, {-1, 0, 0}, {0, 1, 0}},
    {{0, -0.5, -1}, {1, -0.5, 0}, {0, -0.5, 1}, {-1, -0.5, 0}, {0, 1, 0}},
    {{0, 1, 2, 3}, {1, 0, 4}, {2, 1, 4}, {3, 2, 4}, {0, 3, 4}}};

std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string obj_text(const TestMesh& m) {
  std::string s = "# test pyramid\n";
  for (const auto& v : m.v) s += "v " + num(v[0]) + " " + num(v[1]) + " " + num(v[2]) + "\n";
  for (const auto& n : m.n) s += "vn " + num(n[0]) + " " + num(n[1]) + " " + num(n[2]) + "\n";
  for (const auto& f : m.faces) {
    s += "f";
    for (int i : f) s += " " + std::to_string(i + 1) + "//" + std::to_string(i + 1);
    s += "\n";
  }
  return s;
}

// With extra vertex properties, an extra element with a list between vertex and face, a skipped
// list before the face's index list and a property after it.
std::string ply_header(const std::string& format, const TestMesh& m, const std::string& eol = "\n") {
  std::string h;
  for (const std::string& line :
       {std::string("ply"), "format " + format + " 1.0", std::string("comment made by ply_test.cpp"),
        std::string("obj_info anything at all"), "element vertex " + std::to_string(m.v.size()),
        std::string("property float x"), std::string("property float32 y"), std::string("property float z"),
        std::string("property uchar red"), std::string("property float nx"), std::string("property float ny"),
        std::string("property float nz"), std::string("property double quality"), std::string("element edge 2"),
        std::string("property int vertex1"), std::string("property int32 vertex2"),
        std::string("property list uchar int extra"), "element face " + std::to_string(m.faces.size()),
        std::string("property list uchar float texcoord"), std::string("property list uchar int vertex_indices"),
        std::string("property uchar flags"), std::string("end_header")})
    h += line + eol;
  return h;
}

std::string ascii_ply(const TestMesh& m, const std::string& eol = "\n") {
  std::string s = ply_header("ascii", m, eol);
  for (std::size_t i = 0; i < m.v.size(); ++i)
    s += num(m.v[i][0]) + " " + num(m.v[i][1]) + "\t" + num(m.v[i][2]) + " 200 " + num(m.n[i][0]) + " " +
         num(m.n[i][1]) + " " + num(m.n[i][2]) + " 0.75" + eol;
  s += "0 1 3 7 8 9" + eol + "  2 3 0" + eol;  // edges: the second has an empty list
  for (const auto& f : m.faces) {
    s += "2 0.5 0.25 " + std::to_string(f.size());
    for (int i : f) s += " " + std::to_string(i);
    s += " 1" + eol;
  }
  return s;
}

class Bin {
 public:
  explicit Bin(bool big_endian) : swap_(big_endian != (std::endian::native == std::endian::big)) {}
  template <class T>
  Bin& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (swap_) std::reverse(b, b + sizeof(T));
    bytes.append(reinterpret_cast<const char*>(b), sizeof(T));
    return *this;
  }
  std::string bytes;

 private:
  bool swap_;
};

std::string binary_ply(const TestMesh& m, bool big_endian) {
  Bin b(big_endian);
  b.bytes = ply_header(big_endian ? "binary_big_endian" : "binary_little_endian", m);
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    b.put(float(m.v[i][0])).put(float(m.v[i][1])).put(float(m.v[i][2])).put(std::uint8_t(200));
    b.put(float(m.n[i][0])).put(float(m.n[i][1])).put(float(m.n[i][2])).put(0.75);
  }
  b.put(std::int32_t(0)).put(std::int32_t(1)).put(std::uint8_t(3)).put(7).put(8).put(9);
  b.put(std::int32_t(2)).put(std::int32_t(3)).put(std::uint8_t(0));
  for (const auto& f : m.faces) {
    b.put(std::uint8_t(2)).put(0.5f).put(0.25f).put(std::uint8_t(f.size()));
    for (int i : f) b.put(std::int32_t(i));
    b.put(std::uint8_t(1));
  }
  return b.bytes;
}

void expect_same_mesh(const MeshData& a, const MeshData& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) EXPECT_TRUE(a.positions[i] == b.positions[i]) << "position " << i;
  ASSERT_EQ(a.normals.size(), b.normals.size());
  for (std::size_t i = 0; i < a.normals.size(); ++i) EXPECT_TRUE(a.normals[i] == b.normals[i]) << "normal " << i;
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t i = 0; i < a.faces.size(); ++i) {
    EXPECT_EQ(a.faces[i].v, b.faces[i].v) << "face " << i;
    EXPECT_EQ(a.faces[i].n, b.faces[i].n) << "face " << i;
    // Same corners in the same order: the same triangle in space.
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_TRUE(a.positions[a.faces[i].v[k]] == b.positions[b.faces[i].v[k]]) << "face " << i << " corner " << k;
  }
}

void expect_pyramid(const MeshData& m) {
  ASSERT_EQ(m.positions.size(), 5u);
  ASSERT_EQ(m.normals.size(), 5u);
  ASSERT_EQ(m.faces.size(), 6u);
  const std::array<std::array<std::uint32_t, 3>, 6> expected = {
      {{0, 1, 2}, {0, 2, 3}, {1, 0, 4}, {2, 1, 4}, {3, 2, 4}, {0, 3, 4}}};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(m.faces[i].v, expected[i]) << "face " << i;
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(m.faces[i].n[k], std::int32_t(expected[i][k]));
  }
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_TRUE(m.positions[i] == strahl::Vec3(kPyramid.v[i][0], kPyramid.v[i][1], kPyramid.v[i][2]));
    EXPECT_TRUE(m.normals[i] == strahl::Vec3(kPyramid.n[i][0], kPyramid.n[i][1], kPyramid.n[i][2]));
  }
}

using strahl::test::error_of;

// ---------------------------------------------------------------------------------------------

TEST_F(PlyTest, AsciiMatchesObj) {
  const MeshData obj = strahl::load_obj(write("pyramid.obj", obj_text(kPyramid)));
  const MeshData ply = strahl::load_ply(write("pyramid.ply", ascii_ply(kPyramid)));
  expect_pyramid(obj);
  expect_pyramid(ply);
  expect_same_mesh(ply, obj);
}

TEST_F(PlyTest, AsciiWithCrLfLineEnds) {
  expect_pyramid(strahl::load_ply(write("crlf.ply", ascii_ply(kPyramid, "\r\n"))));
}

TEST_F(PlyTest, BinaryLittleEndianMatchesObj) {
  const MeshData obj = strahl::load_obj(write("pyramid.obj", obj_text(kPyramid)));
  const MeshData ply = strahl::load_ply(write("pyramid.ply", binary_ply(kPyramid, false)));
  expect_pyramid(ply);
  expect_same_mesh(ply, obj);
}

TEST_F(PlyTest, BinaryBigEndianMatchesObj) {
  const MeshData obj = strahl::load_obj(write("pyramid.obj", obj_text(kPyramid)));
  const MeshData ply = strahl::load_ply(write("pyramid.ply", binary_ply(kPyramid, true)));
  expect_pyramid(ply);
  expect_same_mesh(ply, obj);
}

TEST_F(PlyTest, PolygonsAreFans) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 2\nproperty list uchar uint vertex_index\nend_header\n"
      "1 0 0\n0.5 0.8 0\n-0.5 0.8 0\n-1 0 0\n0 -1 0\n5 5 5\n5 0 1 2 3 4\n3 5 0 1\n";
  const MeshData m = strahl::load_ply(write("pentagon.ply", text));
  ASSERT_EQ(m.faces.size(), 4u);
  EXPECT_EQ(m.faces[0].v, (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.faces[1].v, (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m.faces[2].v, (std::array<std::uint32_t, 3>{0, 3, 4}));
  EXPECT_EQ(m.faces[3].v, (std::array<std::uint32_t, 3>{5, 0, 1}));
  EXPECT_TRUE(m.normals.empty());
  EXPECT_EQ(m.faces[0].n, (std::array<std::int32_t, 3>{-1, -1, -1}));
}

TEST_F(PlyTest, PartialNormalsAreIgnored) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1 0\n1 0 0 1 0\n0 1 0 1 0\n3 0 1 2";  // no newline at the end
  const MeshData m = strahl::load_ply(write("partial.ply", text));
  EXPECT_TRUE(m.normals.empty());
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.faces[0].n, (std::array<std::int32_t, 3>{-1, -1, -1}));
}

TEST_F(PlyTest, ElementsInAnyOrder) {
  // Faces before vertices, blank lines between entries.
  const std::string text =
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nelement vertex 3\n"
      "property float z\nproperty float y\nproperty float x\nend_header\n3 2 1 0\n\n0 0 1\n0 1 0\n\n1 0 0\n\n";
  const MeshData m = strahl::load_ply(write("order.ply", text));
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_TRUE(m.positions[0] == strahl::Vec3(1, 0, 0));
  EXPECT_TRUE(m.positions[2] == strahl::Vec3(0, 0, 1));
  EXPECT_EQ(m.faces.at(0).v, (std::array<std::uint32_t, 3>{2, 1, 0}));
}

// ---------------------------------------------------------------------------------------------
// Every scalar type, under both of its names, as coordinates, skipped values, list counts and
// indices, in ascii and in both binary byte orders.

struct TypeCase {
  const char* name;
  const char* alias;
  int size;
  bool is_signed;
  bool is_float;
};
const TypeCase kTypes[] = {{"char", "int8", 1, true, false},      {"uchar", "uint8", 1, false, false},
                           {"short", "int16", 2, true, false},    {"ushort", "uint16", 2, false, false},
                           {"int", "int32", 4, true, false},      {"uint", "uint32", 4, false, false},
                           {"float", "float32", 4, true, true},   {"double", "float64", 8, true, true}};

void put_as(Bin& b, const TypeCase& t, double v) {
  if (t.is_float) {
    if (t.size == 4) b.put(float(v));
    else b.put(v);
  } else if (t.is_signed) {
    if (t.size == 1) b.put(std::int8_t(v));
    else if (t.size == 2) b.put(std::int16_t(v));
    else b.put(std::int32_t(v));
  } else {
    if (t.size == 1) b.put(std::uint8_t(v));
    else if (t.size == 2) b.put(std::uint16_t(v));
    else b.put(std::uint32_t(v));
  }
}

TEST_F(PlyTest, EveryScalarTypeParses) {
  for (const TypeCase& t : kTypes) {
    for (const char* name : {t.name, t.alias}) {
      SCOPED_TRACE(name);
      const double neg = t.is_signed ? -5 : 5;
      const double frac = t.is_float ? 0.25 : 3;
      // The skipped value is the type's extreme, so a wrong size or sign would show.
      const double skip = t.is_float ? -1e30 : (t.is_signed ? -(std::ldexp(1.0, 8 * t.size - 1)) : std::ldexp(1.0, 8 * t.size) - 1);
      const std::vector<std::array<double, 3>> v = {{1, 2, 3}, {4, neg, 6}, {7, frac, 100}};
      const std::string n = name;
      const std::string body_header = "element vertex 3\nproperty " + n + " x\nproperty " + n + " y\nproperty " + n +
                                      " z\nproperty " + n + " skipped\nelement face 1\nproperty list " + n + " " + n +
                                      " vertex_indices\nproperty " + n + " skipped_too\nend_header\n";
      const auto check = [&](const MeshData& m) {
        ASSERT_EQ(m.positions.size(), 3u);
        for (std::size_t i = 0; i < 3; ++i)
          EXPECT_TRUE(m.positions[i] == strahl::Vec3(v[i][0], v[i][1], v[i][2])) << "vertex " << i;
        ASSERT_EQ(m.faces.size(), 1u);
        EXPECT_EQ(m.faces[0].v, (std::array<std::uint32_t, 3>{2, 0, 1}));
      };
      std::string ascii = "ply\nformat ascii 1.0\n" + body_header;
      for (const auto& p : v) ascii += num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + " " + num(skip) + "\n";
      ascii += "3 2 0 1 " + num(skip) + "\n";
      check(strahl::load_ply(write("ascii.ply", ascii)));
      for (bool big : {false, true}) {
        Bin b(big);
        b.bytes = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" +
                  body_header;
        for (const auto& p : v) {
          for (double c : p) put_as(b, t, c);
          put_as(b, t, skip);
        }
        for (double c : {3, 2, 0, 1}) put_as(b, t, c);
        put_as(b, t, skip);
        check(strahl::load_ply(write(big ? "big.ply" : "little.ply", b.bytes)));
      }
    }
  }
}

// Binary faces with nothing but the index list, and vertices of scalars only, take the reader's
// fast paths: every integer count and index type, both byte orders, polygons of 3 to 5 corners.
std::string plain_binary(const TypeCase& count, const TypeCase& index, bool big) {
  Bin b(big);
  b.bytes = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
            " 1.0\nelement vertex 6\nproperty double x\nproperty float y\nproperty short z\nproperty uchar w\n"
            "element face 3\nproperty list " + count.name + " " + index.alias + " vertex_indices\nend_header\n";
  for (int i = 0; i < 6; ++i) b.put(double(i) * 0.5).put(float(-i)).put(std::int16_t(i * 100)).put(std::uint8_t(9));
  const std::vector<std::vector<int>> faces = {{0, 1, 2}, {5, 4, 3, 2}, {1, 2, 3, 4, 5}};
  for (const auto& f : faces) {
    put_as(b, count, double(f.size()));
    for (int i : f) put_as(b, index, i);
  }
  return b.bytes;
}

TEST_F(PlyTest, BinaryFastPaths) {
  const std::array<std::array<std::uint32_t, 3>, 6> expected = {
      {{0, 1, 2}, {5, 4, 3}, {5, 3, 2}, {1, 2, 3}, {1, 3, 4}, {1, 4, 5}}};
  for (const TypeCase& count : kTypes)
    for (const TypeCase& index : kTypes)
      for (bool big : {false, true}) {
        SCOPED_TRACE(std::string(count.name) + " " + index.name + (big ? " big" : " little"));
        const MeshData m = strahl::parse_ply(plain_binary(count, index, big), "plain.ply");
        ASSERT_EQ(m.positions.size(), 6u);
        for (int i = 0; i < 6; ++i) EXPECT_TRUE(m.positions[std::size_t(i)] == strahl::Vec3(i * 0.5, -i, i * 100));
        ASSERT_EQ(m.faces.size(), expected.size());
        for (std::size_t f = 0; f < expected.size(); ++f) EXPECT_EQ(m.faces[f].v, expected[f]) << "face " << f;
      }
  // Their errors name the entry and the byte.
  std::string bad = plain_binary(kTypes[1], kTypes[4], false);
  bad[bad.size() - 4] = 6;  // the last corner of the last face: vertex 6 of 6
  const std::string message = error_of([&] { strahl::parse_ply(bad, "plain.ply"); });
  EXPECT_NE(message.find("plain.ply: face 2 refers to vertex 6, but the file has 6 vertices (numbered from 0) (at byte"),
            std::string::npos)
      << message;
}

TEST_F(PlyTest, AsciiValuesOutOfRangeForTheirType) {
  const std::pair<const char*, const char*> cases[] = {{"char", "128"},    {"char", "-129"},       {"uchar", "256"},
                                                       {"uchar", "-1"},    {"short", "32768"},     {"ushort", "65536"},
                                                       {"int", "2147483648"}, {"uint", "4294967296"}, {"uint", "-1"},
                                                       {"float", "1e39"},  {"double", "1e400"},    {"int", "1.5"},
                                                       {"float", "abc"}};
  for (const auto& [type, value] : cases) {
    SCOPED_TRACE(std::string(type) + " " + value);
    const std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nproperty " + std::string(type) + " extra\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n"
                             "0 0 0 0\n1 0 0 " + std::string(value) + "\n0 1 0 0\n3 0 1 2\n";
    // Skipped values are not parsed; give the value to the coordinate x as well.
    const fs::path p = write("range.ply", text);
    EXPECT_NO_THROW(strahl::load_ply(p));  // skipped: only the count of values matters
    std::string as_x = text;
    as_x.replace(as_x.find("property float x"), 16, "property " + std::string(type) + " x");
    as_x.replace(as_x.find("1 0 0 "), 1, value);
    const std::string message = error_of([&] { strahl::load_ply(write("range.ply", as_x)); });
    EXPECT_EQ(message.rfind(p.string() + ":12: ", 0), 0u) << message;
  }
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the file and, for the header and ascii bodies, the line.

const std::string kHead =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";  // the body starts on line 10
const std::string kVerts = "0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n";

struct ErrorCase {
  const char* what;
  std::string text;
  int line;  // 0: no line in the message
  const char* says;
};

TEST_F(PlyTest, ErrorsNameFileAndLine) {
  const std::string h2 = "ply\nformat ascii 1.0\n";
  const ErrorCase cases[] = {
      {"empty file", "", 1, "not a PLY file"},
      {"not a PLY file", "solid cube\nfacet normal 0 0 1\n", 1, "not a PLY file"},
      {"obj file", obj_text(kPyramid), 1, "not a PLY file"},
      {"unknown format", "ply\nformat binary_middle_endian 1.0\n", 2, "unknown PLY format 'binary_middle_endian'"},
      {"unknown version", "ply\nformat ascii 2.0\n", 2, "unsupported PLY version '2.0'"},
      {"no format", "ply\nelement vertex 0\nend_header\n", 3, "no 'format' line"},
      {"two formats", h2 + "format ascii 1.0\n", 3, "second 'format'"},
      {"unknown type", h2 + "element vertex 1\nproperty vec3 x\n", 4, "unknown property type 'vec3'"},
      {"unknown list type", h2 + "element face 1\nproperty list uchar long vertex_indices\n", 4,
       "unknown property type 'long'"},
      {"unknown keyword", h2 + "elements vertex 1\n", 3, "unknown header line 'elements'"},
      {"property first", h2 + "property float x\n", 3, "before the first 'element'"},
      {"bad property line", h2 + "element vertex 1\nproperty float\n", 4, "expected 'property"},
      {"negative count", h2 + "element vertex -5\n", 3, "negative count"},
      {"count not a number", h2 + "element vertex many\n", 3, "whole number"},
      {"count too large", h2 + "element vertex 99999999999999999999\n", 3, "too large"},
      {"no end_header", h2 + "element vertex 0\nproperty float x\n", 4, "no 'end_header'"},
      {"missing z",
       h2 + "element vertex 3\nproperty float x\nproperty float y\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n",
       3, "no property 'z'"},
      {"x is a list",
       h2 + "element vertex 3\nproperty list uchar float x\nproperty float y\nproperty float z\nend_header\n", 4,
       "must be a single value"},
      {"no vertex element", h2 + "element face 1\nproperty list uchar int vertex_indices\nend_header\n", 5,
       "no 'vertex' element"},
      {"no face element", h2 + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
       7, "no 'face' element"},
      {"face without list",
       h2 + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
            "property int flags\nend_header\n",
       7, "no list property 'vertex_indices'"},
      {"indices not a list",
       h2 + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
            "property int vertex_indices\nend_header\n",
       8, "must be a list"},
      {"element without properties", h2 + "element material 5\n" + kHead.substr(h2.size()), 3, "no properties"},
      {"count beyond the file",
       h2 + "element vertex 2000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n" + kVerts + "3 0 1 2\n",
       3, "file is too short"},
      {"too few vertices", kHead + "0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n", 11,
       "unexpected end of file: the header declares 3 'vertex' entries, the file has 2"},
      {"too few faces", std::string(kHead).replace(kHead.find("face 1"), 6, "face 2") + kVerts + "3 0 1 2 \n", 13,
       "declares 2 'face' entries, the file has 1"},
      {"too few values", kHead + "0.0 0.0 0.0\n1.0 0.0\n0.0 1.0 0.0\n3 0 1 2\n", 11, "too few values for vertex 1"},
      {"too many values", kHead + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", 11, "too many values for vertex 1"},
      {"index out of range", kHead + kVerts + "3 0 1 3\n", 13, "face 0 refers to vertex 3, but the file has 3 vertices"},
      {"negative index", kHead + kVerts + "3 0 -1 2\n", 13, "refers to vertex -1"},
      {"two corners", kHead + kVerts + "2 0 1\n", 13, "face 0 has 2 vertices (a face needs at least 3)"},
      {"nan coordinate", kHead + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", 11, "vertex 1 has a coordinate that is not a finite"},
      {"inf coordinate", kHead + "0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", 12, "not a finite number"},
      {"bad number", kHead + "0 0 0\n1 0 0\n0 1,5 0\n3 0 1 2\n", 12, "'1,5' is not a valid float"},
      {"data after the end", kHead + kVerts + "3 0 1 2\n\n3 0 1 2\n", 15, "unexpected data after the last element"},
      {"no faces", std::string(kHead).replace(kHead.find("face 1"), 6, "face 0") + kVerts, 0,
       "PLY file contains no faces"},
  };
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.what);
    const fs::path p = write("bad.ply", c.text);
    const std::string message = error_of([&] { strahl::load_ply(p); });
    EXPECT_NE(message.find(c.says), std::string::npos) << message;
    const std::string where = c.line > 0 ? p.string() + ":" + std::to_string(c.line) + ": " : p.string() + ": ";
    EXPECT_EQ(message.rfind(where, 0), 0u) << message;
  }
}

TEST_F(PlyTest, BinaryErrorsNameFileAndByte) {
  const std::string head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  const auto vertices = [](float bad) {
    Bin b(false);
    for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, bad, 0.f}) b.put(c);
    return b.bytes;
  };
  const auto face = [](std::uint32_t n, std::vector<std::int32_t> idx) {
    Bin b(false);
    b.put(n);
    for (std::int32_t i : idx) b.put(i);
    return b.bytes;
  };
  const std::pair<std::string, const char*> cases[] = {
      {head + vertices(1) + face(3, {0, 1, 5}), "face 0 refers to vertex 5, but the file has 3 vertices"},
      {head + vertices(1) + face(3, {0, -2, 1}), "refers to vertex -2"},
      {head + vertices(1) + face(1, {0, 1, 2}), "face 0 has 1 vertices"},
      {head + vertices(std::numeric_limits<float>::quiet_NaN()) + face(3, {0, 1, 2}), "vertex 2 has a coordinate"},
      {head + vertices(std::numeric_limits<float>::infinity()) + face(3, {0, 1, 2}), "vertex 2 has a coordinate"},
      // A list claiming 4 billion items in a tiny file: refused before anything is allocated.
      {head + vertices(1) + face(0xFFFFFFFFu, {0, 1, 2}), "unexpected end of file"},
      {head + vertices(1) + face(4, {0, 1, 2}), "unexpected end of file"},
      {head + vertices(1).substr(0, 20), "file is too short"},
  };
  for (const auto& [bytes, says] : cases) {
    SCOPED_TRACE(says);
    const fs::path p = write("bad.ply", bytes);
    const std::string message = error_of([&] { strahl::load_ply(p); });
    EXPECT_NE(message.find(says), std::string::npos) << message;
    // Body errors name the byte; the size check before the body names the element's header line.
    const std::string where = p.string() + (std::string(says) == "file is too short" ? ":3: " : ": ");
    EXPECT_EQ(message.rfind(where, 0), 0u) << message;
  }
}

TEST_F(PlyTest, MissingFileOrDirectory) {
  const std::string m1 = error_of([&] { strahl::load_ply(dir_ / "nope.ply"); });
  EXPECT_NE(m1.find("nope.ply: cannot open mesh file"), std::string::npos) << m1;
  fs::create_directories(dir_ / "dir.ply");
  const std::string m2 = error_of([&] { strahl::load_ply(dir_ / "dir.ply"); });
  EXPECT_NE(m2.find("cannot open mesh file"), std::string::npos) << m2;
}

// Every truncation of a valid file is an error (the ascii file may lose its last newline).
TEST_F(PlyTest, EveryTruncationIsAnError) {
  for (const std::string& full : {ascii_ply(kPyramid), binary_ply(kPyramid, false), binary_ply(kPyramid, true)}) {
    const bool ascii = full.find("format ascii") != std::string::npos;
    for (std::size_t n = 0; n + (ascii ? 1 : 0) < full.size(); ++n) {
      EXPECT_THROW(strahl::parse_ply(std::string_view(full).substr(0, n), "cut.ply"), strahl::Error)
          << (ascii ? "ascii" : "binary") << " cut at " << n;
    }
    EXPECT_NO_THROW(strahl::parse_ply(std::string_view(full).substr(0, full.size() - (ascii ? 1 : 0)), "cut.ply"));
    EXPECT_NO_THROW(strahl::load_ply(write("cut.ply", full.substr(0, full.size() - (ascii ? 1 : 0)))));
  }
}

// Random byte changes, insertions and cuts: parse_ply returns or throws strahl::Error, nothing else.
TEST_F(PlyTest, MutatedFilesNeverCrash) {
  std::mt19937 rng(12345);
  const std::string seeds[] = {ascii_ply(kPyramid), binary_ply(kPyramid, false), binary_ply(kPyramid, true),
                               plain_binary(kTypes[1], kTypes[4], false)};
  const char* interesting[] = {"9", "-", "0", "\n", " ", "4294967295", "2000000000", "nan", "e9", "list"};
  int loaded = 0, refused = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    std::string s = seeds[std::size_t(iter) % std::size(seeds)];
    const int edits = 1 + int(rng() % 4);
    for (int e = 0; e < edits && !s.empty(); ++e) {
      const std::size_t at = rng() % s.size();
      switch (rng() % 4) {
        case 0: s[at] = char(rng() % 256); break;
        case 1: s.insert(at, interesting[rng() % std::size(interesting)]); break;
        case 2: s.erase(at, 1 + rng() % 8); break;
        default: s.resize(at); break;
      }
    }
    try {
      const MeshData m = strahl::parse_ply(s, "mutant.ply");
      for (const MeshData::Face& f : m.faces)
        for (std::uint32_t v : f.v) ASSERT_LT(v, m.positions.size());
      ++loaded;
    } catch (const strahl::Error&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(loaded, 0);
}

// ---------------------------------------------------------------------------------------------
// Scenes: `type: mesh` picks the reader by extension; a .ply renders like the same .obj.

std::string mesh_scene(const std::string& file) {
  return "camera: {position: [1.6, 1.4, 2.6], look_at: [0, 0.4, 0], fov: 45}\n"
         "render: {width: 48, height: 36, background: [0.2, 0.3, 0.4]}\n"
         "lights: [{type: point, position: [3, 5, 4]}]\n"
         "objects:\n"
         "  - {type: plane, normal: [0, 1, 0], distance: -0.01, material: {checker: {size: 0.25}}}\n"
         "  - type: mesh\n"
         "    file: " + file + "\n"
         "    scale: 1.2\n"
         "    rotate: [0, 30, 0]\n"
         "    material: {color: [0.9, 0.4, 0.2], reflectivity: 0.2}\n";
}

strahl::Image render_scene(const std::string& yaml, const fs::path& base_dir) {
  const strahl::Scene scene = strahl::parse_scene(yaml, "scene.yaml", base_dir);
  const strahl::RenderScene rs = strahl::compile(scene);
  return strahl::render(rs, strahl::RenderOptions{1, 16});
}

TEST_F(PlyTest, SceneWithPlyRendersLikeObj) {
  write("pyramid.obj", obj_text(kPyramid));
  write("pyramid.ply", ascii_ply(kPyramid));
  write("pyramid-le.PLY", binary_ply(kPyramid, false));  // the extension is case-insensitive
  write("pyramid-be.ply", binary_ply(kPyramid, true));
  const strahl::Image obj = render_scene(mesh_scene("pyramid.obj"), dir_);
  const strahl::Image ply = render_scene(mesh_scene("pyramid.ply"), dir_);
  ASSERT_EQ(obj.width(), 48);
  EXPECT_TRUE(ply == obj);
  EXPECT_TRUE(render_scene(mesh_scene("pyramid-le.PLY"), dir_) == obj);
  EXPECT_TRUE(render_scene(mesh_scene("pyramid-be.ply"), dir_) == obj);
  // The mesh is in the picture: some pixel differs from the image without it.
  std::string no_mesh = mesh_scene("pyramid.obj");
  no_mesh = no_mesh.substr(0, no_mesh.find("  - type: mesh"));
  EXPECT_FALSE(render_scene(no_mesh, dir_) == obj);
}

TEST_F(PlyTest, SceneMeshErrors) {
  write("pyramid.stl", "solid\n");
  const std::string m1 = error_of([&] { render_scene(mesh_scene("pyramid.stl"), dir_); });
  EXPECT_EQ(m1.rfind("scene.yaml:7:11: mesh: ", 0), 0u) << m1;
  EXPECT_NE(m1.find("unknown mesh format '.stl' (use .obj, .ply, .gltf or .glb)"), std::string::npos) << m1;
  const std::string m2 = error_of([&] { render_scene(mesh_scene("noext"), dir_); });
  EXPECT_NE(m2.find("unknown mesh format ''"), std::string::npos) << m2;
  // A PLY error keeps its own file and line behind the scene's position.
  write("bad.ply", kHead + kVerts + "3 0 1 9\n");
  const std::string m3 = error_of([&] { render_scene(mesh_scene("bad.ply"), dir_); });
  EXPECT_EQ(m3.rfind("scene.yaml:7:11: mesh: " + (dir_ / "bad.ply").string() + ":13: face 0 refers to vertex 9", 0), 0u)
      << m3;
}

}  // namespace
}  // namespace ply_test
