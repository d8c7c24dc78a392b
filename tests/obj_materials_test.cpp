// OBJ materials (scene/mtl_loader.h, obj_loader.h with materials): mtllib files' Kd and map_Kd,
// each face's usemtl through the polygon splitter, and `file_materials: true` drawing them as the
// same meshes given those materials in the scene file would be drawn.

#include <gtest/gtest.h>

#include "strahl/scene/mesh_file.h"
#include "strahl/scene/mtl_loader.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"
#include "test_picture.h"

namespace strahl {
namespace {

using test::error_of;
using test::kPpm;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(ObjMaterials, MtlReadsKdAndMapKd) {
  const std::vector<MtlMaterial> m = parse_mtl(
      "# a library\nnewmtl red\nKa 0.1 0.1 0.1\nKd 0.8 0.1 0.05\nillum 2\n\n"
      "newmtl pictured\n  Kd 0.5\nmap_Kd  textures\\my picture.png  \nmap_Bump -bm 2 bump.png\n",
      "lib.mtl", "/models");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].name, "red");
  EXPECT_EQ(m[0].kd, Vec3(0.8, 0.1, 0.05));
  EXPECT_TRUE(m[0].map_kd.empty());
  EXPECT_EQ(m[1].kd, Vec3(0.5));
  EXPECT_EQ(m[1].map_kd, std::filesystem::path("/models/textures/my picture.png"));
  EXPECT_EQ(m[1].map_kd_line, 9);
  const auto error = [](const std::string& text) { return error_of([&] { parse_mtl(text, "lib.mtl", "/"); }); };
  EXPECT_EQ(error("Kd 1 1 1\n"), "lib.mtl:1:1: Kd before the first newmtl");
  EXPECT_EQ(error("newmtl a\nKd 1 2\n"), "lib.mtl:2:7: Kd needs r g b (or one number for all three)");
  EXPECT_EQ(error("newmtl a\nKd spectral x.rfl\n"), "lib.mtl:2:4: Kd spectral is not read (only Kd r g b)");
  EXPECT_EQ(error("newmtl a\nKd 1 -1 0\n"), "lib.mtl:2:6: Kd: '-1' is negative");
  EXPECT_EQ(error("newmtl a\nKd 1 nan 0\n"), "lib.mtl:2:6: Kd: 'nan' is not a finite number");
  EXPECT_EQ(error("newmtl a\nmap_Kd -s 2 2 1 x.png\n"), "lib.mtl:2:8: map_Kd options ('-s', …) are not read");
  EXPECT_EQ(error("newmtl a\nmap_Kd\n"), "lib.mtl:2:7: map_Kd needs a file name");
  EXPECT_EQ(error("newmtl a\nnewmtl a\n"), "lib.mtl:2:8: material 'a' is defined twice (first on line 1)");
  EXPECT_EQ(error("newmtl\n"), "lib.mtl:1:7: newmtl needs one name");
}

class ObjMaterialsFiles : public ::testing::Test {
 protected:
  void write(const std::string& name, const std::string& text) { test::write_text(dir_ / name, text); }
  MeshData load(const std::string& name, bool materials = true) { return load_obj(dir_ / name, materials); }
  test::TempDir dir_;
};

TEST_F(ObjMaterialsFiles, EachFaceTakesItsUsemtlThroughThePolygonSplitter) {
  write("lib.mtl", "newmtl violet\nKd 0.5 0.25 1\nnewmtl picture\nKd 1 0.5 1\nmap_Kd t.ppm\nnewmtl unused\n");
  write("t.ppm", kPpm);
  // A triangle before any usemtl, a quad (split in two) in violet, a triangle in picture, a
  // pentagon (three) in violet again.
  write("m.obj",
        "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
        "f 1 2 3\nusemtl violet\nf 1 2 3 4\nusemtl picture\nf 1 3 4\nusemtl violet\nf 1 2 3 5 4\n");
  const MeshData m = load("m.obj");
  ASSERT_EQ(m.faces.size(), 7u);
  ASSERT_EQ(m.face_materials.size(), 7u);
  const std::int32_t want[7] = {-1, 0, 0, 1, 0, 0, 0};
  for (std::size_t f = 0; f < 7; ++f) EXPECT_EQ(m.face_materials[f], want[f]) << f;
  ASSERT_EQ(m.materials.size(), 2u);  // (those used, in order of first use)
  EXPECT_EQ(m.materials[0].name, "violet");
  EXPECT_EQ(m.materials[0].color, Vec3(0.5, 0.25, 1));
  ASSERT_NE(m.materials[1].image, nullptr);  // the picture times Kd
  EXPECT_FLOAT_EQ(m.materials[1].image->at(0, 0).g, float(float(test::srgb_code(128)) * 0.5));
  // Without materials asked for, usemtl and mtllib are not read (a missing library is no error).
  const MeshData plain = load("m.obj", false);
  EXPECT_TRUE(plain.materials.empty() && plain.face_materials.empty());
  write("missing.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n");
  EXPECT_EQ(load("missing.obj", false).faces.size(), 1u);
  // With them: the errors name the line and column.
  const std::string path = (dir_ / "missing.obj").string();
  EXPECT_TRUE(contains(error_of([&] { load("missing.obj"); }), path + ":1:8: mtllib: ")) << error_of([&] { load("missing.obj"); });
  write("unknown.obj", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gold\nf 1 2 3\n");
  EXPECT_EQ(error_of([&] { load("unknown.obj"); }),
            (dir_ / "unknown.obj").string() + ":5:8: usemtl 'gold': no such material in the mtllib files");
  write("nolib.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gold\nf 1 2 3\n");
  EXPECT_TRUE(contains(error_of([&] { load("nolib.obj"); }), ":4:8: usemtl 'gold': no such material in the file (it names no mtllib)"));
  write("badpic.mtl", "newmtl p\nmap_Kd none.png\n");
  write("badpic.obj", "mtllib badpic.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl p\nf 1 2 3\n");
  EXPECT_TRUE(contains(error_of([&] { load("badpic.obj"); }), (dir_ / "badpic.mtl").string() + ":2: map_Kd: "));
}

// `file_materials: true` on an OBJ draws each face as the same faces drawn as separate meshes
// with those materials would be drawn (Kd as color, map_Kd as a uv-mapped image).
TEST_F(ObjMaterialsFiles, FileMaterialsRenderAsSeparateMeshes) {
  write("lib.mtl", "newmtl violet\nKd 0.5 0.25 1\nnewmtl picture\nmap_Kd t.ppm\n");
  write("t.ppm", kPpm);
  write("all.obj",
        "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 3 0 0\nv 2 1 0\nv 4 0 0\nv 5 0 0\nv 4 1 0\n"
        "vt 0.25 0.5\nvt 0.75 0.5\nvt 0.25 1\n"
        "usemtl violet\nf 1 2 3\nusemtl picture\nf 4/1 5/2 6/3\nusemtl violet\nf 7 8 9\n");
  write("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 4 0 0\nv 5 0 0\nv 4 1 0\nf 1 2 3\nf 4 5 6\n");
  write("b.obj", "v 2 0 0\nv 3 0 0\nv 2 1 0\nvt 0.25 0.5\nvt 0.75 0.5\nvt 0.25 1\nf 1/1 2/2 3/3\n");
  const std::string head =
      "camera: {position: [2.5, 0.5, 4], look_at: [2.5, 0.5, 0], fov: 70}\nrender: {width: 48, height: 16}\n"
      "lights: [{type: point, position: [2, 3, 4]}]\nobjects:\n";
  const std::string look = "specular: 0.3, shininess: 20";
  const auto image_of = [&](const std::string& objects) {
    return test::render_image(parse_scene(head + objects, "s.yaml", dir_.path()));
  };
  const Image by_file = image_of("  - {type: mesh, file: all.obj, file_materials: true, material: {" + look + "}}\n");
  const Image separate = image_of("  - {type: mesh, file: a.obj, material: {" + look + ", color: [0.5, 0.25, 1]}}\n"
                                  "  - {type: mesh, file: b.obj, material: {" + look + ", image: {file: t.ppm, mapping: uv}}}\n");
  EXPECT_EQ(test::max_abs_diff(by_file, separate), 0.0f);
  const Image plain = image_of("  - {type: mesh, file: all.obj, material: {" + look + "}}\n");
  EXPECT_GT(test::max_abs_diff(plain, by_file), 0.1f);
  // PLY files give no materials.
  EXPECT_TRUE(contains(test::compile_error("objects: [{type: mesh, file: x.ply, file_materials: true}]\n"),
                       "bad.yaml:1:53: file_materials: only glTF (.gltf, .glb) and OBJ files give materials"));
}

}  // namespace
}  // namespace strahl
