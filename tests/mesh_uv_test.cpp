// A mesh's own texture coordinates (OBJ `vt`, PLY u/v) under a uv-mapped image
// (shading/image_texture.h, ImageMapping::UV): the loaders read them, compile() keeps them per
// face (through mirroring and motion), the renderer interpolates them at the hit — whole rendered
// images equal the picture where the UVs put it — and every other mapping, and a mesh without
// them, still reads the point.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/image/image_io.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/ply_loader.h"
#include "strahl/scene/scene_writer.h"
#include "test_helpers.h"
#include "test_picture.h"

namespace strahl::mesh_uv_test {
namespace {

constexpr int kW = test::kPictureWidth, kH = test::kPictureHeight;
using test::picture;
using test::picture_pixel;

// The picture's pixel at texture coordinate (u, v) (planar: u across, v up), repeated.
Vec3 picture_at(Real u, Real v) {
  const int x = int(std::floor(u * kW)), row = int(std::floor((1 - v) * kH));
  return picture_pixel(((x % kW) + kW) % kW, ((row % kH) + kH) % kH);
}

// The unit square of the wall z = 0 as two triangles, its texture coordinates turned a quarter:
// the vertex at (x, y) has (u, v) = (y, 1 − x).
MeshData turned_square() {
  MeshData data;
  data.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  data.texcoords = {{0, 1}, {0, 0}, {1, 0}, {1, 1}};
  data.faces.push_back({{0, 1, 2}, {-1, -1, -1}, {0, 1, 2}});
  data.faces.push_back({{0, 2, 3}, {-1, -1, -1}, {0, 2, 3}});
  return data;
}

// A camera of kN × kN pixels on the unit square of the wall z = 0, an image material lit by the
// ambient term alone (its colour is the picture's, exactly).
constexpr int kN = 8;
Material wall_scene(Scene& s, ImageMapping mapping) {
  test::set_camera(s, {0.5, 0.5, 1}, {0.5, 0.5, 0}, {0, 1, 0}, -0.5, 0.5, -0.5, 0.5, 1, kN, kN);
  s.settings.ambient_light = Vec3(1);
  ImageTexture t;
  t.image = picture();
  t.bilinear = false;
  t.mapping = mapping;
  Material m = test::phong(Vec3(0.5), 1, 0, Vec3(0), 1);
  m.texture = s.add_texture(t);
  return m;
}

// The wall point under the centre of camera pixel (x, row).
Real wall_x(int x) { return (x + 0.5) / kN; }
Real wall_y(int row) { return 1 - (row + 0.5) / kN; }

// Every pixel of the compiled scene against expected(x, y) at the wall point under its centre.
template <class Expected>
void expect_wall(const RenderScene& rs, Expected expected, const std::string& what) {
  for (int row = 0; row < kN; ++row)
    for (int x = 0; x < kN; ++x) {
      RayCounters counters;
      const Vec3 c = render_pixel(rs.view(), x, row, 1, counters);
      EXPECT_EQ(c, expected(wall_x(x), wall_y(row))) << what << ": pixel " << x << ", " << row;
    }
}

TEST(MeshUv, InterpolatedWithTheBarycentricWeights) {
  const kernel::VertexTexcoords t{0.25, 0.5, 1, 0, 0, 0.75};
  EXPECT_EQ(kernel::texcoord_at(t, 0, 0), Vec3(0.25, 0.5, 0));
  EXPECT_EQ(kernel::texcoord_at(t, 1, 0), Vec3(1, 0, 0));
  EXPECT_EQ(kernel::texcoord_at(t, 0, 1), Vec3(0, 0.75, 0));
  EXPECT_EQ(kernel::texcoord_at(t, 0.5, 0.25), Vec3(0.25 * 0.25 + 0.5, 0.5 * 0.25 + 0.75 * 0.25, 0));
}

// The turned square shows the picture turned: the point (x, y) reads (u, v) = (y, 1 − x). Under
// planar mapping the same mesh reads the point (its UVs unused), and under uv mapping a mesh
// without UVs reads the point too (as planar).
TEST(MeshUv, RenderedPixelsAreThePictureWhereTheUvsPutIt) {
  for (const AccelKind accel : {AccelKind::Naive, AccelKind::Bvh, AccelKind::KdTree, AccelKind::Octree
#if defined(STRAHL_HAVE_EMBREE)
                                ,
                                AccelKind::Embree
#endif
       }) {
    const std::string name = "accel " + std::to_string(int(accel));
    for (const ImageMapping mapping : {ImageMapping::UV, ImageMapping::Planar}) {
      Scene s;
      s.settings.accel = accel;
      s.add(Mesh(turned_square(), wall_scene(s, mapping), Transform{}));
      if (mapping == ImageMapping::UV)
        expect_wall(compile(s), [](Real x, Real y) { return picture_at(y, 1 - x); }, name + " uv");
      else
        expect_wall(compile(s), [](Real x, Real y) { return picture_at(x, y); }, name + " planar");
    }
    Scene s;
    s.settings.accel = accel;
    MeshData plain = turned_square();
    plain.texcoords.clear();
    for (MeshData::Face& f : plain.faces) f.t = {-1, -1, -1};
    s.add(Mesh(plain, wall_scene(s, ImageMapping::UV), Transform{}));
    expect_wall(compile(s), [](Real x, Real y) { return picture_at(x, y); }, name + " without uvs");
  }
}

// A mirroring transform swaps two corners of each face (to keep it facing out): the texture
// coordinates go with their corners. Mirrored in x and moved back onto the square, the vertex
// now at (x, y) came from (1 − x, y): it reads (u, v) = (y, x).
TEST(MeshUv, TheyStayWithTheirCornersWhenTheMeshIsMirrored) {
  Scene s;
  Transform mirror;
  mirror.scale = {-1, 1, 1};
  mirror.translate = {1, 0, 0};
  s.add(Mesh(turned_square(), wall_scene(s, ImageMapping::UV), mirror));
  expect_wall(compile(s), [](Real x, Real y) { return picture_at(y, x); }, "mirrored");
}

// A mesh moving towards the camera during the shutter: each pixel's sample meets it at its own
// time, at the same (x, y), and reads the same texture coordinate. Keyframes that turn it make it
// an instance of a group holding it: there too.
TEST(MeshUv, MovingMeshesAndInstancesKeepThem) {
  for (const bool turning : {false, true}) {
    Scene s;
    s.camera.shutter_open = 0;
    s.camera.shutter_close = 1;
    Mesh mesh(turned_square(), wall_scene(s, ImageMapping::UV), Transform{});
    if (turning) {
      Transform to;
      to.rotate_degrees = {0, 0, 0.001};  // (turns: an instance; too little to move a pixel's point off its texel)
      mesh.motion = Motion::keyframes(Transform{}, to);
    } else {
      mesh.motion = Motion::linear({0, 0, 0.001});  // (towards the camera: too little to move a point off its texel)
    }
    s.add(std::move(mesh));
    const RenderScene rs = compile(s);
    ASSERT_EQ(turning ? rs.moving_instances.size() : rs.moving_triangles.size(), turning ? 1u : 2u);
    expect_wall(rs, [](Real x, Real y) { return picture_at(y, 1 - x); }, turning ? "turning" : "moving");
  }
}

// In an instanced group: the UVs are the mesh's own, wherever the instance puts it — moved and
// turned half a turn about z, the square's point (x, y) shows what (1 − x, 1 − y) showed.
TEST(MeshUv, InstancesCarryThem) {
  test::TempDir dir;
  write_image(*picture(), dir / "picture.pfm");
  test::write_text(dir / "square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3 4/4\n");
  Scene s = parse_scene(
      "render: {ambient_light: 1}\n"
      "groups:\n  square:\n    - {type: mesh, file: square.obj, material: {ambient: 1, diffuse: 0, specular: 0, "
      "image: {file: picture.pfm, mapping: uv, interpolate: nearest}}}\n"
      "objects:\n  - {type: instance, of: square, rotate: [0, 0, 180], translate: [6, 1, 0]}\n",
      "t.yaml", dir.path());
  test::set_camera(s, {5.5, 0.5, 1}, {5.5, 0.5, 0}, {0, 1, 0}, -0.5, 0.5, -0.5, 0.5, 1, kN, kN);
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.instances.size(), 1u);
  expect_wall(rs, [](Real x, Real y) { return picture_at(1 - y, x); }, "instance");
}

// A uv-mapped image on an object without texture coordinates is read at the point: compile()
// says so, once per such object (in a group too), and not for a mesh that has them.
TEST(MeshUv, AnObjectWithoutThemIsWarnedOf) {
  Scene s;
  const Material m = wall_scene(s, ImageMapping::UV);
  s.add(Mesh(turned_square(), m, Transform{}));
  MeshData plain = turned_square();
  for (MeshData::Face& f : plain.faces) f.t = {-1, -1, -1};
  s.add(Mesh(plain, m, Transform{}));
  s.add(Sphere({0, 0, -5}, 1, m));
  Material planar = m;
  ImageTexture t;
  t.image = picture();
  planar.texture = s.add_texture(t);
  s.add(Sphere({0, 0, -9}, 1, planar));
  const RenderScene rs = compile(s);
  ASSERT_EQ(rs.warnings.size(), 2u);
  EXPECT_NE(rs.warnings[0].find("the mesh has no texture coordinates (OBJ vt, PLY u and v): its uv-mapped image is read "
                                "at the point, as planar"),
            std::string::npos)
      << rs.warnings[0];
  EXPECT_NE(rs.warnings[1].find("only meshes have texture coordinates"), std::string::npos) << rs.warnings[1];
}

// The C++ API's mesh data is checked as the files are: a coordinate that is not finite is an
// error (where it is kept: the material has an image).
TEST(MeshUv, NonFiniteOnesAreRefused) {
  Scene s;
  MeshData data = turned_square();
  data.texcoords[2].v = std::nan("");
  s.add(Mesh(data, wall_scene(s, ImageMapping::UV), Transform{}));
  const std::string message = test::error_of([&] { compile(s); });
  EXPECT_NE(message.find("mesh texture coordinate is not a finite number"), std::string::npos) << message;
}

TEST(MeshUv, ObjReadsVtAndTheCornersThatNameThem) {
  const MeshData m = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
      "vt 0.25 0.5\nvt 0.75\nvt 1 1 0.5\n"
      "f 1/1 2/2 3/3\n"
      "f 1/3/1 3/2/1 4/1/1\n"
      "f 1//1 2//1 4//1\n"
      "f 1/1 2/2 3/3 4/-1\n",  // a quad: split, each triangle keeping its corners' coordinates
      "t.obj");
  ASSERT_EQ(m.texcoords.size(), 3u);
  EXPECT_EQ(m.texcoords[0], (Texcoord{0.25, 0.5}));
  EXPECT_EQ(m.texcoords[1], (Texcoord{0.75, 0}));  // (v left out: 0)
  EXPECT_EQ(m.texcoords[2], (Texcoord{1, 1}));     // (w unused)
  ASSERT_EQ(m.faces.size(), 5u);
  EXPECT_EQ(m.faces[0].t, (std::array<std::int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.faces[1].t, (std::array<std::int32_t, 3>{2, 1, 0}));
  EXPECT_EQ(m.faces[1].n, (std::array<std::int32_t, 3>{0, 0, 0}));
  EXPECT_EQ(m.faces[2].t, (std::array<std::int32_t, 3>{-1, -1, -1}));
  for (std::size_t f = 3; f < 5; ++f)
    for (std::size_t k = 0; k < 3; ++k) {  // each corner's coordinate is its vertex's: vertex i + 1 → vt i + 1 (4 → 3)
      const std::uint32_t v = m.faces[f].v[k];
      EXPECT_EQ(m.faces[f].t[k], std::int32_t(v == 3 ? 2 : v)) << f << ", " << k;
    }
  EXPECT_THROW(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/2\nf 1/1 2/5 3/1\n", "t.obj"), Error);
  EXPECT_THROW(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 nan\nf 1/1 2/1 3/1\n", "t.obj"), Error);
}

TEST(MeshUv, PlyReadsUvByAnyOfItsNames) {
  for (const std::string names : {"u v", "s t", "texture_u texture_v", "texture_s texture_t"}) {
    const std::string u = names.substr(0, names.find(' ')), v = names.substr(names.find(' ') + 1);
    const std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nproperty float " + u + "\nproperty float " + v +
                             "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0 0.25 0.5\n1 0 0 1 0\n0 1 0 0 0.75\n3 0 1 2\n";
    const MeshData m = parse_ply(text, "t.ply");
    ASSERT_EQ(m.texcoords.size(), 3u) << names;
    EXPECT_EQ(m.texcoords[0], (Texcoord{0.25, 0.5})) << names;
    EXPECT_EQ(m.texcoords[2], (Texcoord{0, 0.75})) << names;
    EXPECT_EQ(m.faces.at(0).t, (std::array<std::int32_t, 3>{0, 1, 2})) << names;
  }
  // Binary, with a property between them (the fixed-stride path): the same numbers.
  std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nproperty double s\nproperty uchar alpha\nproperty float t\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&bin](const auto value) { bin.append(reinterpret_cast<const char*>(&value), sizeof value); };
  const float xyz[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const double s[3] = {0.25, 1, 0};
  const float t[3] = {0.5, 0, 0.75};
  for (int i = 0; i < 3; ++i) {
    for (const float c : xyz[i]) put(c);
    put(s[i]);
    put(std::uint8_t(255));
    put(t[i]);
  }
  put(std::uint8_t(3));
  for (const std::int32_t i : {0, 1, 2}) put(i);
  const MeshData m = parse_ply(bin, "t.ply");
  ASSERT_EQ(m.texcoords.size(), 3u);
  EXPECT_EQ(m.texcoords[0], (Texcoord{0.25, 0.5}));
  EXPECT_EQ(m.texcoords[1], (Texcoord{1, 0}));
  EXPECT_EQ(m.faces.at(0).t, (std::array<std::int32_t, 3>{0, 1, 2}));
  // Only one of the pair: none; both names of one coordinate: an error.
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string tail = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_TRUE(parse_ply(head + "property float u\n" + tail + "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", "t.ply").texcoords.empty());
  const std::string twice = test::error_of([&] {
    parse_ply(head + "property float u\nproperty float s\nproperty float v\n" + tail +
                  "0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2\n",
              "t.ply");
  });
  EXPECT_NE(twice.find("properties 'u' and 's' of element 'vertex' both give the texture coordinate u"), std::string::npos)
      << twice;
  const std::string infinite = test::error_of([&] {
    parse_ply(head + "property float u\nproperty float v\n" + tail + "0 0 0 1 1\n1 0 0 1 inf\n0 1 0 1 1\n3 0 1 2\n", "t.ply");
  });
  EXPECT_NE(infinite.find("vertex 1 has a texture coordinate that is not finite"), std::string::npos) << infinite;
}

// The scene writer's OBJ keeps them: written and read back, the same mesh.
TEST(MeshUv, WrittenObjKeepsThem) {
  MeshData data = turned_square();
  data.normals = {{0, 0, 1}};
  data.faces[1].n = {0, 0, 0};
  const MeshData back = parse_obj(mesh_to_obj(data), "back.obj");
  ASSERT_EQ(back.texcoords.size(), data.texcoords.size());
  for (std::size_t i = 0; i < data.texcoords.size(); ++i) EXPECT_EQ(back.texcoords[i], data.texcoords[i]);
  ASSERT_EQ(back.faces.size(), data.faces.size());
  for (std::size_t f = 0; f < data.faces.size(); ++f) {
    EXPECT_EQ(back.faces[f].v, data.faces[f].v);
    EXPECT_EQ(back.faces[f].n, data.faces[f].n);
    EXPECT_EQ(back.faces[f].t, data.faces[f].t);
  }
}

TEST(MeshUv, SceneFilesNameTheMapping) {
  test::TempDir dir;
  write_image(*picture(), dir / "picture.pfm");
  const Scene s = parse_scene(
      "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: {image: {file: picture.pfm, mapping: uv}}}\n",
      "t.yaml", dir.path());
  ASSERT_EQ(s.textures().size(), 1u);
  EXPECT_EQ(s.textures()[0].mapping, ImageMapping::UV);
  const std::string message = test::error_of([&] {
    parse_scene("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, material: {image: {file: picture.pfm, "
                "mapping: uvw}}}\n",
                "t.yaml", dir.path());
  });
  EXPECT_NE(message.find("unknown image mapping 'uvw' (planar, spherical, cylindrical or uv)"), std::string::npos)
      << message;
  for (const ImageMapping m : {ImageMapping::Planar, ImageMapping::Spherical, ImageMapping::Cylindrical, ImageMapping::UV}) {
    ImageMapping back = ImageMapping::Planar;
    ASSERT_TRUE(image_mapping_from(image_mapping_name(m), back));
    EXPECT_EQ(back, m);
  }
}

}  // namespace
}  // namespace strahl::mesh_uv_test
