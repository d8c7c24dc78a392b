// The glTF 2.0 reader (scene/gltf_loader.h, gltf_data.h): files built here, in memory, with the
// values known; each check is of what the glTF specification defines (accessors, node transforms,
// primitive modes, texture coordinates' origin) or of an error's words and place.

#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "strahl/render/render_scene.h"
#include "strahl/render/scene_hash.h"
#include "strahl/scene/gltf_data.h"
#include "strahl/scene/file_materials.h"
#include "strahl/scene/gltf_loader.h"
#include "strahl/scene/mesh_file.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "test_helpers.h"
#include "test_picture.h"

namespace strahl {
namespace {

using nlohmann::json;
using test::error_of;
using test::kPpm;
using test::srgb_code;

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = std::uint32_t(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= std::uint32_t(static_cast<unsigned char>(bytes[i + 2]));
    out += digits[v >> 18 & 63];
    out += digits[v >> 12 & 63];
    out += i + 1 < bytes.size() ? digits[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

void put32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s += static_cast<char>(v >> (8 * k) & 0xff);
}

// A glTF file under construction: the JSON by nlohmann, every accessor's values in one buffer.
struct Gltf {
  json doc = {{"asset", {{"version", "2.0"}}}, {"accessors", json::array()}, {"bufferViews", json::array()},
              {"meshes", json::array()}, {"nodes", json::array()}};
  std::string bin;

  // Values as a bufferView of their own and an accessor of `type` over it; its index.
  template <class T>
  int accessor(const std::vector<T>& values, int component, const char* type, int width, bool normalized = false) {
    while (bin.size() % 4) bin += '\0';
    const std::size_t offset = bin.size();
    bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
    json a = {{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", component}, {"type", type},
              {"count", values.size() / std::size_t(width)}};
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size() - 1);
  }
  int positions(const std::vector<float>& xyz) { return accessor(xyz, 5126, "VEC3", 3); }
  int indices(const std::vector<std::uint16_t>& i) { return accessor(i, 5123, "SCALAR", 1); }

  // A mesh of one primitive; its index.
  int mesh(const json& primitive) {
    doc["meshes"].push_back({{"primitives", json::array({primitive})}});
    return int(doc["meshes"].size() - 1);
  }
  int node(const json& n) {
    doc["nodes"].push_back(n);
    return int(doc["nodes"].size() - 1);
  }

  // The .gltf text with the buffer as a data: URI (or at `uri`, written by the caller).
  std::string text(const std::string& uri = "") const {
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", bin.size()},
                                 {"uri", uri.empty() ? "data:application/octet-stream;base64," + base64(bin) : uri}}});
    return d.dump(1);
  }
  // The .glb bytes: JSON chunk, BIN chunk.
  std::string glb() const {
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string j = d.dump(), b = bin;
    while (j.size() % 4) j += ' ';
    while (b.size() % 4) b += '\0';
    std::string out = "glTF";
    put32(out, 2);
    put32(out, std::uint32_t(12 + 8 + j.size() + 8 + b.size()));
    put32(out, std::uint32_t(j.size()));
    out += "JSON";
    out += j;
    put32(out, std::uint32_t(b.size()));
    out += std::string("BIN\0", 4);
    out += b;
    return out;
  }
};

MeshData parse(const std::string& bytes) { return parse_gltf(bytes, "t.gltf", "/nonexistent-strahl-test-dir"); }
std::string error(const std::string& bytes) { return error_of([&] { parse(bytes); }); }

// A unit right triangle in z = 0 with normals and texture coordinates, drawn by one node.
Gltf triangle() {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int n = g.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, 5126, "VEC3", 3);
  const int t = g.accessor(std::vector<float>{0, 0, 1, 0, 0.25f, 1}, 5126, "VEC2", 2);
  const int i = g.indices({0, 1, 2});
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}}, {"indices", i}})}});
  return g;
}

TEST(Gltf, ReadsPositionsNormalsAndTexcoords) {
  const MeshData m = parse(triangle().text());
  ASSERT_EQ(m.positions.size(), 3u);
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(m.positions[2], Vec3(0, 1, 0));
  EXPECT_EQ(m.normals[2], Vec3(0, 0, 1));
  // glTF's v runs down from the image's top edge: (0.25, 1) is strahl's (0.25, 0).
  EXPECT_EQ(m.texcoords[0], (Texcoord{0, 1}));
  EXPECT_EQ(m.texcoords[2], (Texcoord{0.25, 0}));
  const MeshData::Face& f = m.faces[0];
  EXPECT_EQ(f.v, (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(f.n, (std::array<std::int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(f.t, (std::array<std::int32_t, 3>{0, 1, 2}));
}

bool same(const MeshData& a, const MeshData& b) {
  if (a.positions.size() != b.positions.size() || a.normals.size() != b.normals.size() ||
      a.texcoords.size() != b.texcoords.size() || a.faces.size() != b.faces.size())
    return false;
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    if (!(a.positions[i] == b.positions[i])) return false;
  for (std::size_t i = 0; i < a.normals.size(); ++i)
    if (!(a.normals[i] == b.normals[i])) return false;
  for (std::size_t i = 0; i < a.texcoords.size(); ++i)
    if (!(a.texcoords[i] == b.texcoords[i])) return false;
  for (std::size_t i = 0; i < a.faces.size(); ++i)
    if (a.faces[i].v != b.faces[i].v || a.faces[i].n != b.faces[i].n || a.faces[i].t != b.faces[i].t) return false;
  return true;
}

TEST(Gltf, GlbAndBufferFilesReadTheSame) {
  const Gltf g = triangle();
  const MeshData embedded = parse(g.text());
  EXPECT_TRUE(same(parse_gltf(g.glb(), "t.glb", "/nonexistent-strahl-test-dir"), embedded));
  // A .gltf whose buffer is a file beside it, its name percent-encoded; through load_mesh.
  test::TempDir dir;
  test::write_text(dir / "my mesh.bin", g.bin);
  test::write_text(dir / "model.GLTF", g.text("my%20mesh.bin"));
  test::write_text(dir / "model.glb", g.glb());
  EXPECT_TRUE(same(load_mesh(dir / "model.GLTF"), embedded));
  EXPECT_TRUE(same(load_mesh(dir / "model.glb"), embedded));
  // The file is missing: the buffer, the URI and the system's reason are named.
  std::filesystem::remove(dir / "my mesh.bin");
  const std::string e = error_of([&] { load_mesh(dir / "model.GLTF"); });
  EXPECT_NE(e.find("model.GLTF: buffers[0].uri: " + (dir / "my mesh.bin").string() + ": cannot open mesh file"),
            std::string::npos) << e;
}

// Node hierarchy: the child's placement is its parent's after its own (T·R·S each), and a mesh
// drawn by two nodes is copied twice.
TEST(Gltf, NodesPlaceTheirMeshesByTheirWorldTransforms) {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int m = g.mesh({{"attributes", {{"POSITION", p}}}});
  const Real h = std::sqrt(Real(0.5));
  // child: scale 2, then its parent: rotation 90° about z, then translation (10, 0, 0).
  g.node({{"mesh", m}, {"scale", {2, 2, 2}}});
  g.node({{"mesh", m}, {"children", {0}}, {"translation", {10, 0, 0}}, {"rotation", {0, 0, h, h}}});
  g.doc["scenes"] = json::array({{{"nodes", {1}}}});
  g.doc["scene"] = 0;
  const MeshData mesh = parse(g.text());
  ASSERT_EQ(mesh.positions.size(), 6u);
  ASSERT_EQ(mesh.faces.size(), 2u);
  // The parent's copy first (depth first, the node before its children).
  EXPECT_TRUE(test::vec_near(mesh.positions[1], Vec3(10, 1, 0), 1e-15));
  EXPECT_TRUE(test::vec_near(mesh.positions[2], Vec3(9, 0, 0), 1e-15));
  EXPECT_TRUE(test::vec_near(mesh.positions[4], Vec3(10, 2, 0), 1e-15));
  EXPECT_TRUE(test::vec_near(mesh.positions[5], Vec3(8, 0, 0), 1e-15));
  EXPECT_EQ(mesh.faces[1].v, (std::array<std::uint32_t, 3>{3, 4, 5}));
  // The same placement as a column-major matrix gives the same points.
  Gltf by_matrix = g;
  by_matrix.doc["nodes"][1].erase("translation");
  by_matrix.doc["nodes"][1].erase("rotation");
  by_matrix.doc["nodes"][1]["matrix"] = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1};
  const MeshData m2 = parse(by_matrix.text());
  for (std::size_t i = 0; i < 6; ++i) EXPECT_TRUE(test::vec_near(m2.positions[i], mesh.positions[i], 1e-15)) << i;
  // Without `scene`, the first of `scenes`; without scenes, every node that is no node's child.
  g.doc.erase("scene");
  EXPECT_TRUE(same(parse(g.text()), mesh));
  g.doc.erase("scenes");
  EXPECT_TRUE(same(parse(g.text()), mesh));
  // A scene of only the child.
  g.doc["scenes"] = json::array({{{"nodes", {0}}}});
  EXPECT_EQ(parse(g.text()).faces.size(), 1u);
}

// A mirroring node turns the corners round, so that the triangle's front (its normals' side, by
// the right-hand rule) stays the front; normals go by the inverse transpose of the placement.
TEST(Gltf, MirrorsAndStretchesKeepNormalsOnTheFront) {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 1});
  const Vec3 n0 = normalize(cross(Vec3(1, 0, 0), Vec3(0, 1, 1)));
  const int n = g.accessor(std::vector<float>{float(n0.x), float(n0.y), float(n0.z), float(n0.x), float(n0.y),
                                              float(n0.z), float(n0.x), float(n0.y), float(n0.z)},
                           5126, "VEC3", 3);
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}})}, {"scale", {-1, 3, 0.5}}});
  const MeshData m = parse(g.text());
  const MeshData::Face& f = m.faces[0];
  EXPECT_EQ(f.v, (std::array<std::uint32_t, 3>{0, 2, 1}));
  const Vec3 front = normalize(cross(m.positions[f.v[1]] - m.positions[f.v[0]], m.positions[f.v[2]] - m.positions[f.v[0]]));
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(test::vec_near(m.normals[std::size_t(f.n[std::size_t(c)])], front, 1e-7)) << c;
  // Without the turn, the corners in the file's order would face away from the normals.
  const Vec3 unturned = cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]);
  EXPECT_LT(dot(unturned, m.normals[0]), 0);
}

// Strips and fans in glTF's vertex orders; points and lines are no surface and are skipped.
TEST(Gltf, StripsFansPointsAndLines) {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0});
  json prims = json::array();
  for (int mode : {0, 1, 5, 6, 2, 3}) prims.push_back({{"attributes", {{"POSITION", p}}}, {"mode", mode}});
  g.doc["meshes"].push_back({{"primitives", prims}});
  g.node({{"mesh", 0}});
  const MeshData m = parse(g.text());
  ASSERT_EQ(m.faces.size(), 6u);
  using F = std::array<std::uint32_t, 3>;
  EXPECT_EQ(m.faces[0].v, (F{0, 1, 2}));  // strip: {v_i, v_i+1, v_i+2}, odd ones {v_i, v_i+2, v_i+1}
  EXPECT_EQ(m.faces[1].v, (F{1, 3, 2}));
  EXPECT_EQ(m.faces[2].v, (F{2, 3, 4}));
  EXPECT_EQ(m.faces[3].v, (F{6, 7, 5}));  // fan (its vertices from 5 on): {v_i+1, v_i+2, v_0}
  EXPECT_EQ(m.faces[4].v, (F{7, 8, 5}));
  EXPECT_EQ(m.faces[5].v, (F{8, 9, 5}));
}

// KHR_mesh_quantization's normalized integers, and a sparse accessor over one without data.
TEST(Gltf, NormalizedIntegersAndSparseAccessors) {
  Gltf g;
  g.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  const int p = g.accessor(std::vector<std::int16_t>{0, 0, 0, 0, 32767, 0, 0, 0, 0, -32768, 0, 0}, 5122, "VEC3", 3, true);
  g.doc["accessors"][std::size_t(p)]["byteOffset"] = 0;
  g.doc["bufferViews"][g.doc["accessors"][std::size_t(p)]["bufferView"].get<std::size_t>()]["byteStride"] = 8;
  g.doc["accessors"][std::size_t(p)]["count"] = 3;
  const int t = g.accessor(std::vector<std::uint8_t>{0, 255, 51, 0, 255, 255, 0}, 5121, "VEC2", 2, true);
  g.doc["accessors"][std::size_t(t)]["count"] = 3;
  // Indices: three zeros but for the sparse values 1 and 2 at elements 1 and 2.
  const int si = g.accessor(std::vector<std::uint8_t>{1, 2}, 5121, "SCALAR", 1);
  const int sv = g.accessor(std::vector<std::uint32_t>{1, 2}, 5125, "SCALAR", 1);
  const auto view = [&](int a) { return g.doc["accessors"][std::size_t(a)]["bufferView"]; };
  g.doc["accessors"].push_back({{"componentType", 5125}, {"type", "SCALAR"}, {"count", 3},
                                {"sparse", {{"count", 2}, {"indices", {{"bufferView", view(si)}, {"componentType", 5121}}},
                                            {"values", {{"bufferView", view(sv)}}}}}});
  const int i = int(g.doc["accessors"].size() - 1);
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", t}}}, {"indices", i}})}});
  const MeshData m = parse(g.text());
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[1], Vec3(1, 0, 0));   // 32767 / 32767
  EXPECT_EQ(m.positions[2], Vec3(0, -1, 0));  // max(−32768 / 32767, −1)
  EXPECT_EQ(m.texcoords[1], (Texcoord{Real(51) / 255, 1}));
  EXPECT_EQ(m.faces[0].v, (std::array<std::uint32_t, 3>{0, 1, 2}));
}

// The cube of scenes/meshes as a glTF file (written by tools/make_meshes.py): the same mesh as
// its OBJ twin, and the same compiled scene.
TEST(Gltf, TheExampleCubeIsItsObjTwin) {
  const std::filesystem::path dir = std::filesystem::path(STRAHL_SOURCE_DIR) / "scenes" / "meshes";
  const MeshData obj = load_mesh(dir / "cube-uv.obj"), gltf = load_mesh(dir / "cube-uv.glb");
  ASSERT_EQ(gltf.faces.size(), obj.faces.size());
  EXPECT_TRUE(obj.normals.empty() && gltf.normals.empty());  // (flat shaded)
  for (std::size_t f = 0; f < obj.faces.size(); ++f)
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(gltf.positions[gltf.faces[f].v[c]], obj.positions[obj.faces[f].v[c]]) << f;
      EXPECT_EQ(gltf.texcoords[std::size_t(gltf.faces[f].t[c])], obj.texcoords[std::size_t(obj.faces[f].t[c])]) << f;
    }
  const auto scene = [&](const char* file) {
    return "camera: {position: [3, 2, 4], look_at: [0, 0, 0]}\nrender: {width: 8, height: 8}\n"
           "objects:\n  - {type: mesh, file: " + std::string(file) +
           ", rotate: [0, 20, 0], material: {image: {file: ../textures/grid.png, mapping: uv}}}\n";
  };
  EXPECT_EQ(scene_hash(compile(parse_scene(scene("cube-uv.obj"), "a.yaml", dir))),
            scene_hash(compile(parse_scene(scene("cube-uv.glb"), "a.yaml", dir))));
}

// Two triangles side by side with their materials (a colour; a picture in a bufferView tinted by
// its factor), and a third without one; the second has texture coordinates.
Gltf with_materials(const std::vector<Real>& tint = {1, 0.5, 1, 1}) {
  Gltf g;
  const int p0 = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int p1 = g.positions({2, 0, 0, 3, 0, 0, 2, 1, 0});
  const int p2 = g.positions({4, 0, 0, 5, 0, 0, 4, 1, 0});
  const int t1 = g.accessor(std::vector<float>{0.25f, 0.5f, 0.75f, 0.5f, 0.25f, 0}, 5126, "VEC2", 2);
  const int image = g.accessor(std::vector<char>(kPpm.begin(), kPpm.end()), 5121, "SCALAR", 1);
  g.doc["images"] = json::array({{{"bufferView", g.doc["accessors"][std::size_t(image)]["bufferView"]}, {"mimeType", "image/png"}}});
  g.doc["samplers"] = json::array({{{"magFilter", 9728}}});
  g.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  g.doc["materials"] = json::array({{{"name", "unused"}},
                                    {{"name", "violet"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}}}}},
                                    {{"name", "picture"},
                                     {"pbrMetallicRoughness", {{"baseColorFactor", tint}, {"baseColorTexture", {{"index", 0}}}}}}});
  json prims = json::array({{{"attributes", {{"POSITION", p0}}}, {"material", 1}},
                            {{"attributes", {{"POSITION", p1}, {"TEXCOORD_0", t1}}}, {"material", 2}},
                            {{"attributes", {{"POSITION", p2}}}}});
  g.doc["meshes"].push_back({{"primitives", prims}});
  g.node({{"mesh", 0}});
  return g;
}

TEST(Gltf, MaterialsAreReadWhenAskedFor) {
  const Gltf g = with_materials();
  const MeshData plain = parse(g.text());
  EXPECT_TRUE(plain.materials.empty() && plain.face_materials.empty());
  const MeshData m = parse_gltf(g.text(), "t.gltf", "/nonexistent-strahl-test-dir", true);
  // The materials the faces use, in order of use ("unused" is not read).
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].name, "violet");
  EXPECT_EQ(m.materials[0].color, Vec3(0.5, 0.25, 1));
  EXPECT_EQ(m.materials[0].image, nullptr);
  ASSERT_EQ(m.face_materials.size(), 3u);
  EXPECT_EQ(m.face_materials[0], 0);
  EXPECT_EQ(m.face_materials[1], 1);
  EXPECT_EQ(m.face_materials[2], -1);
  // The picture, decoded from sRGB and times the factor; its sampler says NEAREST.
  const FileMaterial& p = m.materials[1];
  ASSERT_NE(p.image, nullptr);
  ASSERT_EQ(p.image->width(), 2);
  EXPECT_FALSE(p.bilinear);
  EXPECT_FLOAT_EQ(p.image->at(0, 0).r, float(srgb_code(64)));
  EXPECT_FLOAT_EQ(p.image->at(0, 0).g, float(float(srgb_code(128)) * 0.5));
  EXPECT_FLOAT_EQ(p.image->at(1, 0).b, float(srgb_code(32)));
  // Errors name the member.
  Gltf bad = with_materials({1, 2, 1, 1});
  EXPECT_NE(error_of([&] { parse_gltf(bad.text(), "t.gltf", "/", true); })
                .find("t.gltf: materials[2].pbrMetallicRoughness.baseColorFactor: must hold numbers from 0 to 1"),
            std::string::npos);
  bad = with_materials();
  bad.doc["images"][0] = {{"uri", "data:image/png;base64,AAAA"}};
  const std::string e = error_of([&] { parse_gltf(bad.text(), "t.gltf", "/", true); });
  EXPECT_NE(e.find("t.gltf: images[0]: cannot read image"), std::string::npos) << e;
  bad.doc["images"][0] = json::object();
  EXPECT_NE(error_of([&] { parse_gltf(bad.text(), "t.gltf", "/", true); }).find("images[0]: has neither uri nor bufferView"),
            std::string::npos);
}

// `file_materials: true` draws each face in its file material — the scene's material with the
// file's colour or picture — exactly as the same triangles drawn as separate OBJ meshes with
// those materials; inside an instanced group too. Without the key, all in the scene's material.
TEST(Gltf, FileMaterialsRenderAsTheSameMeshesWithThoseMaterials) {
  test::TempDir dir;
  test::write_text(dir / "model.gltf", with_materials({1, 1, 1, 1}).text());
  test::write_text(dir / "t.ppm", kPpm);
  test::write_text(dir / "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  test::write_text(dir / "b.obj", "v 2 0 0\nv 3 0 0\nv 2 1 0\nvt 0.25 0.5\nvt 0.75 0.5\nvt 0.25 1\nf 1/1 2/2 3/3\n");
  test::write_text(dir / "c.obj", "v 4 0 0\nv 5 0 0\nv 4 1 0\nf 1 2 3\n");
  const std::string head =
      "camera: {position: [2.5, 0.5, 4], look_at: [2.5, 0.5, 0], fov: 70}\nrender: {width: 48, height: 16}\n"
      "lights: [{type: point, position: [2, 3, 4]}]\n";
  const std::string look = "specular: 0.3, shininess: 20";
  const auto image_of = [&](const std::string& text) { return test::render_image(parse_scene(text, "s.yaml", dir.path())); };
  const Image gltf = image_of(head + "objects:\n  - {type: mesh, file: model.gltf, file_materials: true, material: {" + look +
                              ", color: [0.2, 0.9, 0.3]}}\n");
  const Image objs = image_of(head + "objects:\n"
                              "  - {type: mesh, file: a.obj, material: {" + look + ", color: [0.5, 0.25, 1]}}\n"
                              "  - {type: mesh, file: b.obj, material: {" + look + ", image: {file: t.ppm, mapping: uv, interpolate: nearest}}}\n"
                              "  - {type: mesh, file: c.obj, material: {" + look + ", color: [0.2, 0.9, 0.3]}}\n");
  EXPECT_EQ(test::max_abs_diff(gltf, objs), 0.0f);
  const Image grouped = image_of(head + "groups: {g: [{type: mesh, file: model.gltf, file_materials: true, material: {" + look +
                                 ", color: [0.2, 0.9, 0.3]}}]}\nobjects:\n  - {type: instance, of: g}\n");
  EXPECT_EQ(test::max_abs_diff(grouped, gltf), 0.0f);
  // The file's materials matter: without the key the picture differs.
  const Image plain = image_of(head + "objects:\n  - {type: mesh, file: model.gltf, material: {" + look +
                               ", color: [0.2, 0.9, 0.3]}}\n");
  EXPECT_GT(test::max_abs_diff(plain, gltf), 0.1f);
  // Only glTF and OBJ files give materials.
  EXPECT_NE(test::compile_error("objects: [{type: mesh, file: x.ply, file_materials: true}]\n")
                .find("bad.yaml:1:53: file_materials: only glTF (.gltf, .glb) and OBJ files give materials"),
            std::string::npos);
  // The scene writer names the glTF file again (by its absolute path), with file_materials.
  const Scene scene = parse_scene(head + "objects:\n  - {type: mesh, file: model.gltf, file_materials: true}\n", "s.yaml", dir.path());
  const std::string yaml = scene_to_yaml(scene);
  EXPECT_NE(yaml.find("file: \"" + (dir / "model.gltf").string() + "\"\n    file_materials: true\n"), std::string::npos) << yaml;
  Scene built;
  built.add(Mesh(parse_gltf(with_materials().text(), "t.gltf", "/", true), Material{}));
  use_file_materials(built, static_cast<Mesh&>(*built.objects().back()));
  EXPECT_NE(error_of([&] { scene_to_yaml(built); }).find("cannot write a mesh in file materials that were not read from a file"),
            std::string::npos);
}

TEST(Gltf, DataHelpers) {
  EXPECT_EQ(gltf::uri_scheme("data:application/octet-stream;base64,AA=="), "data");
  EXPECT_EQ(gltf::uri_scheme("https://x/y.bin"), "https");
  EXPECT_EQ(gltf::uri_scheme("C:/models/y.bin"), "");
  EXPECT_EQ(gltf::uri_scheme("dir/a:b.bin"), "");
  EXPECT_EQ(gltf::uri_scheme("mesh.bin"), "");
  for (const std::string& s : std::vector<std::string>{"", "a", "ab", "abc", "abcd", std::string("\0\xff\x10\x80", 4)}) {
    const LargeArray<char> d = gltf::decode_data_uri("data:application/gltf-buffer;base64," + base64(s));
    EXPECT_EQ(std::string(d.data(), d.size()), s);
  }
  EXPECT_NE(error_of([] { gltf::decode_data_uri("data:text/plain,abc"); }).find("must hold base64"), std::string::npos);
  EXPECT_NE(error_of([] { gltf::decode_data_uri("data:;base64,AB*D"); }).find("character 16"), std::string::npos);
  EXPECT_NE(error_of([] { gltf::decode_data_uri("data:;base64,ABCDE"); }).find("cut short"), std::string::npos);
  EXPECT_EQ(gltf::decode_percent("my%20mesh%2Fx.bin"), "my mesh/x.bin");
  EXPECT_NE(error_of([] { gltf::decode_percent("a%2"); }).find("two hexadecimal digits"), std::string::npos);
  EXPECT_NE(error_of([] { gltf::decode_percent("a%00"); }).find("%00"), std::string::npos);
}

// Each error names the member at fault (or line and column for a syntax error) in words.
TEST(Gltf, ErrorsNameWhereAndWhat) {
  const auto changed = [](const std::function<void(Gltf&)>& change) {
    Gltf g = triangle();
    change(g);
    return error(g.text());
  };
  const auto expect = [](const std::string& got, const std::string& want) {
    EXPECT_NE(got.find(want), std::string::npos) << "got:  " << got << "\nwant: " << want;
  };
  expect(error("{\"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [}"), "t.gltf:2:13: syntax error");
  expect(error("[1, 2]"), "t.gltf: the JSON text is not an object");
  expect(error("{\"asset\": {\"version\": \"2.0\"}, \"x\": 1e999}"), "t.gltf: JSON: number overflow parsing '1e999'");
  expect(error("{\"asset\": {\"version\": \"1.0\"}}"), "t.gltf: asset.version: '1.0' (strahl reads glTF 2)");
  expect(error("{\"asset\": {\"version\": \"2.0\"}}"), "t.gltf: the scene holds no triangles");
  expect(changed([](Gltf& g) { g.doc["accessors"][0]["count"] = 4; }),
         "t.gltf: accessors[0]: 4 elements of 12 bytes from byte 0 reach past the end of bufferViews[0] (36 bytes)");
  expect(changed([](Gltf& g) { g.doc["bufferViews"][0]["byteLength"] = 1000; }),
         "bufferViews[0]: bytes 0 to 1000 reach past the end of its buffer");
  expect(changed([](Gltf& g) { g.doc["bufferViews"][0]["byteStride"] = 6; }),
         "bufferViews[0].byteStride: must be a multiple of 4 from 4 to 252");
  expect(changed([](Gltf& g) { g.doc["bufferViews"][0]["byteStride"] = 8; }),
         "accessors[0]: its elements (12 bytes) are longer than the byteStride of bufferViews[0] (8)");
  expect(changed([](Gltf& g) { g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9; }),
         "meshes[0].primitives[0].attributes.POSITION: refers to accessors[9], but the file has 4");
  expect(changed([](Gltf& g) { g.doc["accessors"][0]["type"] = "VEC2"; }), "accessors[0].type: must be VEC3 for POSITION");
  expect(changed([](Gltf& g) { g.doc["accessors"][3]["componentType"] = 5126; }),
         "accessors[3].componentType: indices must be unsigned integers");
  expect(changed([](Gltf& g) { g.doc["accessors"][0]["componentType"] = 5124; }),
         "accessors[0].componentType: 5124 is not a glTF component type");
  expect(changed([](Gltf& g) { g.doc["accessors"][0]["normalized"] = true; }),
         "accessors[0].normalized: only 8- and 16-bit integers can be normalized");
  expect(changed([](Gltf& g) { g.doc["accessors"][1]["count"] = 2; }),
         "meshes[0].primitives[0].attributes.NORMAL: holds 2 elements, but POSITION holds 3");
  expect(changed([](Gltf& g) { g.doc["accessors"][3]["count"] = 2; }),
         "meshes[0].primitives[0]: holds 2 corners of triangles, not a multiple of 3");
  expect(changed([](Gltf& g) {
           g.bin[g.bin.size() - 6] = 7;  // (the triangle's first corner, index 0)
         }),
         "meshes[0].primitives[0].indices: element 0 is vertex 7, but POSITION holds 3");
  expect(changed([](Gltf& g) { std::memset(&g.bin[4], 0xff, 4); }), "accessors[0]: element 0 is not finite");
  expect(changed([](Gltf& g) { g.doc["meshes"][0]["primitives"][0]["mode"] = 7; }),
         "meshes[0].primitives[0].mode: 7 is not a glTF primitive mode (0 to 6)");
  expect(changed([](Gltf& g) { g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }),
         "extensionsRequired[0]: the file needs extension 'KHR_draco_mesh_compression', which strahl does not read");
  expect(changed([](Gltf& g) {
           g.doc["nodes"][0]["children"] = {0};
           g.doc["scenes"] = json::array({{{"nodes", {0}}}});
         }),
         "nodes[0]: is reached twice: the nodes of a scene must form trees");
  expect(changed([](Gltf& g) { g.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1}; }),
         "nodes[0].matrix: is not affine (its last row must be 0 0 0 1)");
  expect(changed([](Gltf& g) { g.doc["nodes"][0]["rotation"] = {0, 0, 0, 0}; }),
         "nodes[0].rotation: is not a rotation (a quaternion of length 0)");
  expect(changed([](Gltf& g) { g.doc["nodes"][0]["scale"] = {1, 2}; }), "nodes[0].scale: must be a list of 3 numbers");
  expect(changed([](Gltf& g) { g.doc["nodes"][0]["translation"] = {1e308, 0, 0}, g.doc["nodes"][0]["scale"] = {1e308, 1, 1}; }),
         "meshes[0].primitives[0]: a vertex placed by its node's transform is not finite");
  expect(changed([](Gltf& g) { g.doc["accessors"][0]["count"] = -1; }), "accessors[0].count: must not be negative");
  expect(changed([](Gltf& g) { g.doc["accessors"][0]["count"] = 1.5; }), "accessors[0].count: must be a whole number");
  expect(changed([](Gltf& g) {
           g.doc["accessors"][0].erase("bufferView");
           g.doc["accessors"][0]["count"] = 100000000;
         }),
         "accessors[0]: has no bufferView, and its count 100000000 is larger than the file");
  // A mesh drawn by many nodes counts for each (the limit is checked before anything is allocated).
  Gltf many = triangle();
  for (int k = 0; k < 9; ++k) many.node({{"mesh", 0}});
  EXPECT_EQ(parse(many.text()).faces.size(), 10u);
  expect(error_of([&] { parse_gltf(many.text(), "t.gltf", "/", false, 9); }),
         "t.gltf: the scene holds more than 9 triangles (a mesh counts once for each node that draws it)");
  // The buffer's URI.
  Gltf g = triangle();
  expect(error(g.text("https://example.com/t.bin")), "buffers[0].uri: 'https:' URIs are not read");
  expect(error(g.text("data:application/octet-stream;base64,AAA*")), "buffers[0].uri: character 41 of a data: URI is not base64");
  expect(error(g.text("data:application/octet-stream;base64,AAAA")), "buffers[0]: its byteLength is 102, but its data has 3 bytes");
  expect(error(g.text("t.bin")), "buffers[0].uri: /nonexistent-strahl-test-dir/t.bin: cannot open mesh file");
  // The binary container.
  std::string glb = g.glb();
  expect(error_of([&] { parse_gltf(glb.substr(0, 30), "t.glb", "/"); }),
         "t.glb: binary glTF, byte 8: the header gives a length of");
  std::string v1 = glb;
  v1[4] = 1;
  expect(error_of([&] { parse_gltf(v1, "t.glb", "/"); }), "t.glb: binary glTF, byte 4: version 1 (strahl reads glTF 2)");
  std::string long_chunk = glb;
  long_chunk[12] = '\xff', long_chunk[13] = '\xff';
  expect(error_of([&] { parse_gltf(long_chunk, "t.glb", "/"); }), "t.glb: binary glTF, byte 12: a chunk of");
  std::string bad_json = glb;
  bad_json[20] = '[';
  expect(error_of([&] { parse_gltf(bad_json, "t.glb", "/"); }), "t.glb: JSON chunk, line 1, column ");
}

}  // namespace
}  // namespace strahl
