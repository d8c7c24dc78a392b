// The POV-Ray importer (scene/pov/): the benchmark's POV-Ray scenes read into the same pictures
// as their YAML twins, pixel for pixel; POV-Ray's left-handed camera; its directives and
// expressions; its texture rules; errors and warnings at the .pov file's line and column.

#include <gtest/gtest.h>

#include <algorithm>

#include "strahl/scene/csg.h"
#include "strahl/scene/pov/pov_scene.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::pov_import_test {
namespace {

const fs::path kSource = STRAHL_SOURCE_DIR;

Scene pov_scene(const std::string& text, int width = 48, int height = 36, const std::string& name = "test.pov") {
  PovOptions o;
  o.width = width;
  o.height = height;
  return parse_pov_scene(text, name, o);
}

// (With a right-handed camera: nothing mirrored.)
std::string yaml_of(const std::string& text) {
  return translate_pov("camera { right -x * 4 / 3 }\n" + text, "test.pov", PovOptions{}).yaml;
}

std::string pov_error(const std::string& text, const std::string& name = "test.pov") {
  try {
    (void)compile(pov_scene(text, 48, 36, name));
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::size_t count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t i = haystack.find(needle); i != std::string::npos; i = haystack.find(needle, i + 1)) ++n;
  return n;
}

// The benchmark's POV-Ray scenes (bench/povray-*.sh render them in POV-Ray) and their YAML
// twins, written by hand to match: the same image, every pixel bit for bit.
TEST(PovImport, TheBenchmarkScenesAreTheirYamlTwinsPixelForPixel) {
  struct Case {
    const char* pov;
    const char* yaml;
    double whitted;
  };
  for (const Case& c : {Case{"scenes/lecture.pov", "scenes/lecture.yaml", 0}, Case{"scenes/lecture.pov", "scenes/lecture-whitted.yaml", 1},
                        Case{"bench/shapes.pov", "scenes/shapes-pov.yaml", 0}, Case{"bench/csg.pov", "scenes/csg-pov.yaml", 0},
                        Case{"bench/plate.pov", "scenes/plate-pov.yaml", 0}}) {
    SCOPED_TRACE(c.pov + std::string(" vs ") + c.yaml);
    PovOptions o;
    o.width = 96;
    o.height = 54;
    if (c.whitted != 0) o.declares.emplace_back("WHITTED", c.whitted);
    const Scene from_pov = load_scene(kSource / c.pov, o);
    Scene from_yaml = load_scene(kSource / c.yaml);
    from_yaml.settings.width = 96;
    from_yaml.settings.height = 54;
    EXPECT_TRUE(from_pov.warnings.empty()) << from_pov.warnings.front();
    const Image a = test::render_image(from_pov, 2), b = test::render_image(from_yaml, 2);
    EXPECT_EQ(test::max_abs_diff(a, b), 0.0f);
  }
}

// POV-Ray's default camera is left-handed: +x is to the right looking down +z. The importer
// mirrors the scene (and the camera) in x, so the picture is POV-Ray's: a sphere at +x appears
// on the right; with `right -x` (right-handed) on the left; and the left-handed picture is the
// right-handed one of the scene mirrored by hand, bit for bit.
TEST(PovImport, ALeftHandedCameraSeesPovRaysPicture) {
  auto render = [&](const std::string& right, double x) {
    return test::render_image(pov_scene("camera { location <0, 0, -5> look_at <0, 0, 0> " + right + " }\n"
                                        "light_source { <0, 0, -10> color rgb 1 }\n"
                                        "sphere { <" + std::to_string(x) + ", 0.3, 0>, 0.6 pigment { color rgb 1 } "
                                        "finish { ambient 1 diffuse 0 } }\n",
                                        64, 48));
  };
  // The columns of the sphere's pixels (ambient 1: exactly 1).
  auto lit_columns = [](const Image& im) {
    std::pair<int, int> span{im.width(), -1};
    for (int y = 0; y < im.height(); ++y)
      for (int x = 0; x < im.width(); ++x)
        if (im.at(x, y).r == 1.0f) span = {std::min(span.first, x), std::max(span.second, x)};
    return span;
  };
  EXPECT_GT(lit_columns(render("", 1.5)).first, 32) << "the sphere at +x is in the right half";
  const Image left = render("right x*4/3", 1.5);  // (the default right is <1.33, 0, 0>)
  EXPECT_GT(lit_columns(left).first, 32);
  EXPECT_LT(lit_columns(render("right -x*4/3", 1.5)).second, 32) << "right-handed: in the left half";
  EXPECT_EQ(test::max_abs_diff(left, render("right -x*4/3", -1.5)), 0.0f);
}

TEST(PovImport, DirectivesAndExpressions) {
  const std::string y = yaml_of(
      "#version 3.7;\n"
      "#declare A = 2;\n"
      "#declare V = <1, 2, 3> * A;\n"
      "#if (A > 1) sphere { V, 1 } #else sphere { 0, 9 } #end\n"
      "#if (A < 1) sphere { 0, 7 } #elseif (A = 2) sphere { 0, 0.25 } #else sphere { 0, 8 } #end\n"
      "#ifndef (B) #declare B = 5; #end\n"
      "#ifdef (B) #declare B = B + 1; #end\n"
      "#for (I, 1, 3) sphere { <I, B, 0>, 0.5 } #end\n"
      "#declare J = 0;\n"
      "#while (J < 2) sphere { <0, 0, J>, sqrt(4) } #declare J = J + 1; #end\n"
      "sphere { <V.y, vlength(<3, 4, 0>), pow(2, 3)>, max(1, 0.5) + (A = 2 ? 1 : 0) }\n"
      "sphere { <-image_width / 1280, 2 * (1 + 2), radians(180) / pi>, 1 }\n"
      "/* a /* nested */ comment */ // and a line comment\n");
  EXPECT_EQ(count(y, "type: sphere"), 9u) << y;
  for (const char* s : {"center: [2, 4, 6], radius: 1,", "center: [0, 0, 0], radius: 0.25,", "center: [1, 6, 0], radius: 0.5",
                        "center: [3, 6, 0]", "center: [0, 0, 1], radius: 2", "center: [4, 5, 8], radius: 2",
                        "center: [-1, 6, 1], radius: 1"})
    EXPECT_NE(y.find(s), std::string::npos) << s << " in\n" << y;
  EXPECT_EQ(y.find("radius: 9"), std::string::npos);
  EXPECT_EQ(y.find("radius: 7"), std::string::npos);
}

TEST(PovImport, MacrosAndIncludesInLoops) {
  const std::string y = yaml_of(
      "#macro Ring(N, R)\n"
      "  #local I = 0;\n"
      "  #while (I < N)\n"
      "    sphere { <R * cos(2 * pi * I / N), 0, R * sin(2 * pi * I / N)>, 0.1 }\n"
      "    #local I = I + 1;\n"
      "  #end\n"
      "#end\n"
      "#macro Sq(A) (A * A) #end\n"
      "#macro Ball(C) sphere { C, 0.5 } #end\n"
      "#declare I = 42;\n"
      "Ring(4, 2)\n"
      "sphere { <Sq(3), I, 0>, 1 }\n"  // (I is 42 again after Ring's #local I)
      "#declare S = Sq(Sq(2));\n"
      "sphere { 0, S }\n"
      "union { Ring(2, 1) sphere { <0, 5, 0>, 1 } }\n"
      "#declare B = Ball(<1, 2, 3>);\n"
      "object { B }\n"
      "#ifdef (A) sphere { 0, 99 } #end\n");  // (a parameter is gone after the call)
  EXPECT_EQ(count(y, "type: sphere"), 10u) << y;
  for (const char* s : {"center: [2, 0, 0], radius: 0.1", "center: [9, 42, 0], radius: 1,", "center: [0, 0, 0], radius: 16,",
                        "center: [-1, 0, 1.2246467991473532e-16], radius: 0.1", "center: [1, 2, 3], radius: 0.5"})
    EXPECT_NE(y.find(s), std::string::npos) << s << " in\n" << y;

  // #switch: the first clause that holds, falling through to #break; #break from inside an #if.
  const std::string sw = yaml_of(
      "#macro Pick(V)\n"
      "  #switch (V)\n"
      "    #case (1) sphere { <1, 0, 0>, 1 } #break\n"
      "    #range (2, 3) sphere { <2, 0, 0>, 1 }\n"
      "    #case (4) sphere { <4, 0, 0>, 1 } #if (V = 3) #break #end\n"
      "    #case (5) sphere { <5, 0, 0>, 1 } #break\n"
      "    #else sphere { <9, 0, 0>, 1 }\n"
      "  #end\n"
      "#end\n"
      "Pick(1) Pick(2.5) Pick(3) Pick(7)\n");
  EXPECT_EQ(count(sw, "type: sphere"), 7u) << sw;
  EXPECT_EQ(count(sw, "center: [1, 0, 0]"), 1u) << sw;
  EXPECT_EQ(count(sw, "center: [2, 0, 0]"), 2u) << sw;
  EXPECT_EQ(count(sw, "center: [4, 0, 0]"), 2u) << sw;
  EXPECT_EQ(count(sw, "center: [5, 0, 0]"), 1u) << sw;  // (2.5 falls through to 5; 3 breaks at 4)
  EXPECT_EQ(count(sw, "center: [9, 0, 0]"), 1u) << sw;

  const test::TempDir dir;
  test::write_text(dir / "ball.inc", "sphere { <I, 0, 0>, 1 }\n");
  test::write_text(dir / "row.pov", "camera { right -x * 4 / 3 }\n#for (I, 0, 2)\n  #include \"ball.inc\"\n#end\n"
                                    "#macro Two() #include \"ball.inc\" #include \"ball.inc\" #end\n#declare I = 7;\nTwo()\n");
  const std::string row = translate_pov(test::read_text(dir / "row.pov"), (dir / "row.pov").string(), PovOptions{}).yaml;
  EXPECT_EQ(count(row, "type: sphere"), 5u) << row;
  for (const char* s : {"center: [0, 0, 0]", "center: [1, 0, 0]", "center: [2, 0, 0]", "center: [7, 0, 0]"})
    EXPECT_NE(row.find(s), std::string::npos) << s << " in\n" << row;
}

// Include files such as textures.inc declare much the importer does not read: such a name is
// unusable, not the file, and using it is the error. Strings, and POV-Ray's random streams (the
// numbers POV-Ray 3.7 prints for the same calls).
TEST(PovImport, UnreadableDeclarationsStringsAndRandomNumbers) {
  const Scene s = pov_scene(
      "#version 3.7;\n"
      "#declare Bad = pigment { bozo color_map { [0 rgb 0] [1 rgb 1] } }\n"
      "#declare Layered = texture { pigment { rgb 1 } } texture { pigment { rgb 0 } }\n"
      "#declare F = function { x + y }\n"
      "#declare G = F(1, 2, 3);\n"
      "#declare S = seed(1);\n"
      "#declare R1 = rand(S);\n"
      "#declare R2 = rand(S);\n"
      "#declare T = seed(-7);\n"
      "#warning concat(\"R \", str(R1, 0, 12), \" \", str(R2, 0, 12), \" \", str(rand(T), 0, 12), chr(33))\n"
      "#ifdef (Bad) sphere { 0, 1 texture { Layered } } #end\n");
  ASSERT_EQ(s.objects().size(), 1u);
  std::string all;
  for (const std::string& w : s.warnings) all += w + "\n";
  EXPECT_NE(all.find("test.pov:10:1: #warning: R 0.421992875268 0.487121198207 0.046072868175!\n"), std::string::npos) << all;
  EXPECT_NE(all.find("test.pov:3:20: a layered texture is drawn as its first layer"), std::string::npos) << all;
  EXPECT_NE(pov_error("#declare Bad = pigment { bozo }\nsphere { 0, 1 pigment { Bad } }")
                .find("test.pov:2:25: 'Bad' cannot be used: its declaration holds what strahl's POV-Ray importer does not "
                      "read (test.pov:1:26: 'bozo' in pigment is not supported"),
            std::string::npos)
      << pov_error("#declare Bad = pigment { bozo }\nsphere { 0, 1 pigment { Bad } }");
  EXPECT_NE(pov_error("#declare F = function { x }\n#declare G = F(1);\nsphere { 0, G }").find("test.pov:3:13: 'G' cannot be used"),
            std::string::npos);
  // A value that is not an item in braces is an error where it stands.
  EXPECT_NE(pov_error("#declare X = 1 + Q;").find("test.pov:1:18: unknown name 'Q'"), std::string::npos);
}

// POV-Ray's texture rules: the default texture (black, ambient 0.1, diffuse 0.6, no highlight);
// a union is a group whose parts take its transforms after their own and its texture where they
// have none; rgbf is filtered transparency; roughness is 1/shininess; declared textures.
TEST(PovImport, TexturesAndUnionsFollowPovRaysRules) {
  const std::string y = yaml_of(
      "#declare T = texture { pigment { color rgbf <0.7, 0.7, 1, 0.9> } finish { specular 0.6 roughness 0.01 "
      "reflection { 0.1 } } }\n"
      "sphere { 0, 1 }\n"
      "union {\n"
      "  sphere { <1, 0, 0>, 1 }\n"
      "  sphere { <2, 0, 0>, 1 pigment { color rgb <0, 1, 0> } scale 2 }\n"
      "  translate <0, 1, 0> pigment { color red 1 } }\n"
      "sphere { 0, 1 texture { T } interior { ior 1.5 } }\n"
      "plane { <0, 2, 0>, 1 pigment { checker color rgb 1, color rgb 0.1 scale 0.5 } }\n"
      "quadric { <1, 0, 1>, <0, 0, 0>, <0, 0, 0>, -1 clipped_by { box { <-2, 0, -2>, <2, 1, 2> } } }\n"
      "light_source { <1, 2, 3> color rgb <1, 0.5, 0> }\n"
      "light_source { <0, 10, 0> color rgb 2 parallel point_at <1, 0, 0> }\n"
      "light_source { <0, 5, 0> color rgb 1 spotlight point_at <1, 0, 0> radius 10 falloff 15 tightness 4 }\n"
      "light_source { <0, 5, 0> color rgb 1 spotlight }\n"
      "light_source { <0, 5, 0> color rgb 1 fade_distance 2 fade_power 1.5 }\n");
  EXPECT_NE(y.find("  - {type: point, position: [1, 2, 3], color: [1, 0.5, 0]}\n"
                   "  - {type: directional, direction: [1, -10, 0], color: [2, 2, 2]}\n"
                   "  - {type: spot, position: [0, 5, 0], point_at: [1, 0, 0], angle: 10, falloff: 15, tightness: 4, "
                   "color: [1, 1, 1]}\n"
                   // POV-Ray's defaults: point_at <0, 0, 1>, radius 30, falloff 45, tightness 0
                   "  - {type: spot, position: [0, 5, 0], point_at: [0, 0, 1], angle: 30, falloff: 45, tightness: 0, "
                   "color: [1, 1, 1]}\n"
                   "  - {type: point, position: [0, 5, 0], color: [1, 1, 1], fade_distance: 2, fade_power: 1.5}\n"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("{type: sphere, center: [0, 0, 0], radius: 1, material: {color: [0, 0, 0], ambient: 0.1, diffuse: 0.6, "
                   "specular: 0, shininess: 20}}"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("center: [1, 0, 0], radius: 1, transform: [{translate: [0, 1, 0]}], material: {color: [1, 0, 0]"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("center: [2, 0, 0], radius: 1, transform: [{scale: [2, 2, 2]}, {translate: [0, 1, 0]}], material: "
                   "{color: [0, 1, 0]"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("material: {color: [0.7, 0.7, 1], ambient: 0.1, diffuse: 0.6, specular: 0.6, shininess: 100, "
                   "reflectivity: 0.1, transparency: 0.9, filter: true, ior: 1.5}"),
            std::string::npos)
      << y;
  // POV-Ray's plane {N, d} lies d along the unit normal.
  EXPECT_NE(y.find("{type: plane, normal: [0, 1, 0], distance: 1, material: {color: [1, 1, 1]"), std::string::npos) << y;
  EXPECT_NE(y.find("checker: {size: 0.5, color: [0.1, 0.1, 0.1]}"), std::string::npos) << y;
  EXPECT_NE(y.find("{type: quadric, coefficients: [1, 0, 1, 0, 0, 0, 0, 0, 0, -1], clipped_by: {type: box, corners: "
                   "[[-2, 0, -2], [2, 1, 2]]}, material:"),
            std::string::npos)
      << y;
}

TEST(PovImport, MeshesAndIncludes) {
  const test::TempDir dir;
  test::write_text(dir / "quad.inc",
                   "#declare Q = mesh2 {\n"
                   "  vertex_vectors { 4, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 1, 0> }\n"
                   "  normal_vectors { 4, <0, 0, -1>, <0, 0, -1>, <0, 0.1, -1>, <0, 0, -1> }\n"
                   "  face_indices { 2, <0, 1, 2>, <0, 2, 3> }\n"
                   "}\n");
  test::write_text(dir / "main.pov",
                   "#include \"quad.inc\"\n"
                   "object { Q pigment { color rgb 1 } translate <0, 0, 1> }\n"
                   "object { Q translate <0, 0, 2> }\n"  // (a declared mesh used twice)
                   "mesh { triangle { <0, 0, 0>, <1, 0, 0>, <0, 1, 0> } smooth_triangle { <0, 0, 0>, <0, 0, 1>, "
                   "<1, 0, 0>, <0, 0, 1>, <0, 1, 0>, <0, 0, 1> } }\n");
  const Scene s = load_scene(dir / "main.pov");
  const RenderScene rs = compile(s);
  EXPECT_EQ(rs.triangles.size(), 6u);
  ASSERT_EQ(s.objects().size(), 3u);
  const auto* quad = dynamic_cast<const Mesh*>(s.objects()[0].get());
  ASSERT_NE(quad, nullptr);
  EXPECT_EQ(quad->data.faces.size(), 2u);
  EXPECT_EQ(quad->data.faces[1].n[2], 3);
  EXPECT_EQ(quad->transform.translate, Vec3(0, 0, 1));
  // A mesh's triangle with one normal at its corners is flat in POV-Ray (checked with POV-Ray 3.7):
  // the smooth_triangle above, and a mesh2 face; a smooth_triangle of its own keeps its normals.
  const auto* triangles = dynamic_cast<const Mesh*>(s.objects()[2].get());
  ASSERT_NE(triangles, nullptr);
  EXPECT_EQ(triangles->data.faces[1].n[0], -1);
  const Scene flat = pov_scene("mesh2 { vertex_vectors { 3, 0, x, y } normal_vectors { 3, <0, 0.3, -1>, <0, 0.6, -2>, "
                               "<0, 0.3, -1> } face_indices { 1, <0, 1, 2> } }\n"
                               "smooth_triangle { 0, <0, 0.3, -1>, x, <0, 0.3, -1>, y, <0, 0.3, -1> }");
  EXPECT_EQ(dynamic_cast<const Mesh&>(*flat.objects()[0]).data.faces[0].n[0], -1);
  EXPECT_EQ(dynamic_cast<const Mesh&>(*flat.objects()[1]).data.faces[0].n[0], 0);

  test::write_text(dir / "loop.pov", "#include \"loop.pov\"\n");
  EXPECT_NE(pov_error(test::read_text(dir / "loop.pov"), (dir / "loop.pov").string()).find("more than 256 #include"),
            std::string::npos);
}

TEST(PovImport, ErrorsNameThePovFilesLineAndColumn) {
  struct Case {
    const char* text;
    const char* message;
  };
  for (const Case& c : {
           Case{"sphere { <0, 0, 0> 1 }", "test.pov:1:20: expected ',' after the sphere's centre, found the number 1"},
           Case{"sphere { 0, 1 }\nsky_sphere { }", "test.pov:2:1: 'sky_sphere' is not supported by strahl's POV-Ray importer"},
           Case{"sphere { 0, 1 }\n  sphere { 0, -1 }", "test.pov:2:3: sphere radius must be positive (got -1)"},
           Case{"sphere { 0, 1 bozo }", "test.pov:1:15: 'bozo' in sphere is not supported"},
           Case{"sphere { 0, 1 pigment { bozo } }", "test.pov:1:25: 'bozo' in pigment is not supported"},
           Case{"#if (1)\nsphere { 0, 1 }", "test.pov:1:1: this #if has no #end"},
           Case{"#if (0)\nsphere { 0, 1 }", "test.pov:1:1: this #if has no #end"},
           Case{"#end", "test.pov:1:1: #end without #if, #while, #for, #switch or #macro"},
           Case{"#while (1) #end", "test.pov:1:1: more than 1000000 loop iterations"},
           Case{"sphere { 0, 1", "test.pov:1:1: this sphere is never closed"},
           Case{"camera { location 0", "test.pov:1:20: the file ends inside camera"},
           Case{"#fopen F \"x.txt\" read", "test.pov:1:1: #fopen is not supported"},
           Case{"#break", "test.pov:1:1: #break outside a #switch"},
           Case{"#declare S = sphere { 0, 1 }\nsphere { 0, 1 pigment { S } }", "test.pov:2:25: 'S' is not a pigment, finish"},
           Case{"cylinder { 0, y, 1 open open }", "(no error)"},
           Case{"#switch (1) #case (1) sphere { 0, 1 }", "test.pov:1:1: this #switch has no #end"},
           Case{"sphere { 0, 1 clipped_by { box { -1, 1 } } }", "test.pov:1:15: 'clipped_by' in sphere is not supported"},           Case{"#macro M(A) sphere { 0, A } #end\nM(1, 2)", "test.pov:2:1: the macro M takes 1 arguments, not 2"},
           Case{"#macro M(A) M(A) #end\nM(1)", "test.pov:1:13: macros called more than 200 deep"},
           Case{"#macro M(A) A A #end\nsphere { 0, M(1) }", "test.pov:1:15: the macro M gives more than one value here"},
           Case{"sphere { Q, 1 }", "test.pov:1:10: unknown name 'Q' (not declared)"},
           Case{"#include \"nothere.inc\"", "test.pov:1:10: #include \"nothere.inc\": no such file"},
           Case{"/* open", "test.pov:1:1: this comment is never closed"},
           Case{"sphere { 0, 1 }\n\"", "test.pov:2:1: this string is never closed"},
           Case{"sphere { 0, 1 } $", "test.pov:1:17: unexpected character '$'"},
           Case{"sphere { 0, 1 } \x01", "test.pov:1:17: unexpected byte 1"},
           Case{"sphere { 0, 1e999 }", "test.pov:1:13: number '1e999' is out of range"},
           Case{"camera { location 0 look_at 0 }", "test.pov:1:1: camera position and look_at coincide"},
           Case{"sphere { 0, 1 scale <1, 0, 1> }", "test.pov:1:1: "},
           Case{"#error \"stop here\"", "test.pov:1:1: #error: stop here"},
           // compile()'s own errors, at the item's line and column too.
           Case{"sphere { 0, 1 }\n  difference { sphere { 0, 1 } box { 0, <1, 0, 1> } }", "test.pov:2:3: box is flat"},
           Case{"light_source { <0, 0, 0> color rgb -1 }", "test.pov:1:1: light color must not have negative components"},
           Case{"light_source { 0, 1 spotlight radius 95 }", "test.pov:1:31: spotlight radius must lie in [0, 90] degrees"},
           Case{"light_source { 0, 1 spotlight tightness -1 }", "test.pov:1:31: spotlight tightness must not be negative"},
           Case{"light_source { 0, 1 fade_power -1 }", "test.pov:1:21: fade_power must not be negative"},
           Case{"light_source { <0, 0, 1>, 1 spotlight }", "test.pov:1:1: spotlight direction (point_at − position) must"},
       }) {
    SCOPED_TRACE(c.text);
    EXPECT_NE(pov_error(c.text).find(c.message), std::string::npos) << pov_error(c.text);
  }
  // Nesting is bounded (no stack overflow): parentheses, signs, objects in objects.
  EXPECT_NE(pov_error("sphere { 0, " + std::string(5000, '(') + "1 }").find("nested more than 200 deep"), std::string::npos);
  EXPECT_NE(pov_error("sphere { 0, " + std::string(5000, '-') + "1 }").find("nested more than 200 deep"), std::string::npos);
  std::string unions;
  for (int i = 0; i < 300; ++i) unions += "union { ";
  EXPECT_NE(pov_error(unions).find("nested more than 200 deep"), std::string::npos);
  // A NUL byte: not a text file.
  EXPECT_NE(pov_error(std::string("sphere { 0,\n\0 1 }", 17)).find("test.pov:2: not a text file"), std::string::npos);
  // Loops and macros read their bodies again: besides their turns, the tokens they read are
  // bounded (a turn may read far). Lowered here from the default 50,000,000.
  std::string sum = "1";
  for (int i = 0; i < 40; ++i) sum += " + 1";  // 81 tokens
  const std::string loop = "#declare J = 0;\n#while (J < 1000)\n  #declare X = " + sum + ";\n  #declare J = J + 1;\n#end\n",
                    macro = "#macro M() #declare X = " + sum + "; #end\n#for (I, 1, 1000)\n  M()\n#end\n";
  for (const std::string& text : {loop, macro}) {
    SCOPED_TRACE(text);
    PovOptions o;
    o.max_tokens_read = 10'000;
    try {
      (void)translate_pov(text + "sphere { 0, 1 }", "test.pov", o);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("the scene's loops and macros read more than 10000 tokens"), std::string::npos) << e.what();
    }
    o.max_tokens_read = 100'000'000;  // ~100,000 tokens read: within it
    EXPECT_NO_THROW((void)translate_pov(text + "sphere { 0, 1 }", "test.pov", o));
  }
}

TEST(PovImport, WarningsNameWhatIsLeftOut) {
  const Scene s = pov_scene(
      "global_settings { assumed_gamma 2.2 }\n"
      "sphere { 0, 1 pigment { color rgb 1 } finish { phong 0.5 } normal { bumps 0.4 } no_shadow }\n"
      "difference { sphere { 0, 1 pigment { color rgb 1 } } sphere { <1, 0, 0>, 1 pigment { color rgb 0 } } }\n");
  std::string all;
  for (const std::string& w : s.warnings) all += w + "\n";
  for (const char* w : {"test.pov:1:19: assumed_gamma 2.2 is ignored", "test.pov:2:48: phong is drawn as a Blinn-Phong highlight",
                        "test.pov:2:60: normal (bump maps) is left out", "test.pov:2:81: no_shadow is left out",
                        "test.pov:3:14: CSG operands' own textures are left out"})
    EXPECT_NE(all.find(w), std::string::npos) << w << " in\n" << all;
  // Without #version 3.7 or assumed_gamma, POV-Ray draws with its legacy gamma.
  const std::vector<std::string> legacy = pov_scene("sphere { 0, 1 }").warnings;
  ASSERT_EQ(legacy.size(), 1u);
  EXPECT_EQ(legacy[0].rfind("test.pov: no #version 3.7 and no assumed_gamma", 0), 0u) << legacy[0];
  EXPECT_TRUE(pov_scene("#version 3.7;\nsphere { 0, 1 }").warnings.empty());
}

// global_settings { radiosity { … } } is drawn by path tracing (render.integrator: path), with a
// warning that names what differs; without it the scene is Whitted's.
TEST(PovImport, RadiosityIsDrawnByPathTracing) {
  const std::string body = "sphere { 0, 1 pigment { color rgb 1 } }\nlight_source { <2, 3, -4> color rgb 1 }\n";
  const Scene s = pov_scene("#version 3.7;\nglobal_settings { radiosity { count 100 error_bound 0.5 } max_trace_level 7 }\n" + body);
  EXPECT_EQ(s.settings.integrator, IntegratorKind::Path);
  EXPECT_EQ(s.settings.max_depth, 7);  // (what follows the radiosity block is read)
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].rfind("test.pov:2:19: radiosity is drawn by path tracing (integrator: path)", 0), 0u) << s.warnings[0];
  EXPECT_EQ(pov_scene("#version 3.7;\n" + body).settings.integrator, IntegratorKind::Whitted);
}

// finish { emission e }: the pigment's colour times e, as POV-Ray adds it.
TEST(PovImport, EmissionIsThePigmentsColourTimesIt) {
  const std::string yaml = yaml_of("sphere { 0, 1 pigment { color rgb <1, 0.5, 0.25> } finish { emission 0.5 } }\n"
                                   "sphere { 0, 1 pigment { color rgb 1 } finish { emission rgb <0, 1, 2> } }\n");
  EXPECT_NE(yaml.find("emission: [0.5, 0.25, 0.125]"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("emission: [0, 1, 2]"), std::string::npos) << yaml;
}

// image_map: the picture, its mapping and lookup as the scene file's `image` keys; the pigment's
// transforms and the object's after the pigment (not those before it) place it, as in POV-Ray,
// and the left-handed camera's mirror too. bench/pov/imagemap.pov renders as POV-Ray renders it
// (bench/povray-import.sh).
TEST(PovImport, ImageMapsArePlacedAsPovRayPlacesThem) {
  const std::string y = yaml_of(
      "sphere { 0, 1 translate x pigment { image_map { png \"a b.png\" map_type 1 interpolate 2 } scale 2 rotate y*90 }\n"
      "  rotate z*10 translate y }\n"
      "box { 0, 1 pigment { image_map { \"c.png\" once } } }\n"
      "cylinder { 0, y, 1 pigment { image_map { ppm \"d.ppm\" map_type 2 interpolate 0 } } }");
  EXPECT_NE(y.find("image: {file: \"a b.png\", mapping: spherical, interpolate: bilinear, once: false, transform: "
                   "[{scale: 2}, {rotate: [0, 90, 0]}, {rotate: [0, 0, 10]}, {translate: [0, 1, 0]}]}"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("image: {file: \"c.png\", mapping: planar, interpolate: nearest, once: true}"), std::string::npos) << y;
  EXPECT_NE(y.find("image: {file: \"d.ppm\", mapping: cylindrical, interpolate: nearest, once: false}"), std::string::npos)
      << y;
  // POV-Ray's own left-handed camera: the mirror moves the picture too.
  const std::string mirrored = translate_pov("sphere { 0, 1 pigment { image_map { png \"a.png\" } } }", "test.pov", {}).yaml;
  EXPECT_NE(mirrored.find("once: false, transform: [{scale: [-1, 1, 1]}]}"), std::string::npos) << mirrored;
  for (const auto& [text, message] :
       {std::pair{"sphere { 0, 1 pigment { image_map { gif \"a.gif\" } } }", "test.pov:1:37: strahl reads image_map files"},
        std::pair{"sphere { 0, 1 pigment { image_map { \"a.png\" map_type 5 } } }", "test.pov:1:45: strahl maps images with map_type 0, 1 or 2"},
        std::pair{"sphere { 0, 1 pigment { image_map { \"a.png\" interpolate 3 } } }", "test.pov:1:45: strahl interpolates images"},
        std::pair{"sphere { 0, 1 pigment { image_map { \"missing.png\" } } }", "test.pov:1:1: image: "}})
    EXPECT_EQ(pov_error(text).rfind(message, 0), 0u) << pov_error(text);
}

// uv_mapping reads a mesh's uv_vectors (bench/pov/uvmap.pov renders as POV-Ray draws it): the
// pigment's transforms act on (u, v, 0); neither the object's transforms nor the mirror of
// POV-Ray's left-handed camera move the picture, which lies on the surface.
TEST(PovImport, UvMappedImageMapsLieOnTheMeshesUvs) {
  const std::string quad = "mesh2 { vertex_vectors { 4, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 1, 0> } "
                           "uv_vectors { 4, <0, 0>, <0.5, 0>, <0.5, 0.25>, <0, 0.25> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } ";
  const std::string y = translate_pov(quad + "pigment { uv_mapping image_map { png \"a.png\" interpolate 2 } scale 2 rotate z*10 }\n"
                                             "  rotate y*30 translate x }\n" +
                                          quad + "texture { uv_mapping pigment { image_map { \"b.png\" once } } scale 3 } translate y }",
                                      "test.pov", {})
                            .yaml;
  EXPECT_NE(y.find("image: {file: \"a.png\", mapping: uv, interpolate: bilinear, once: false, transform: "
                   "[{scale: 2}, {rotate: [0, 0, 10]}]}"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("image: {file: \"b.png\", mapping: uv, interpolate: nearest, once: true, transform: [{scale: 3}]}"),
            std::string::npos)
      << y;

  // The UVs: by uv_indices, by face_indices without them, a triangle's uv_vectors (<0, 0> where a
  // triangle of the mesh has none, as in POV-Ray).
  const Scene s = pov_scene(
      "mesh2 { vertex_vectors { 3, <0, 0, 0>, <1, 0, 0>, <0, 1, 0> } uv_vectors { 2, <0.5, 0.25>, 0.75 }\n"
      "  face_indices { 1, <0, 1, 2> } uv_indices { 1, <1, 0, 1> } }\n"
      "mesh2 { vertex_vectors { 3, <0, 0, 0>, <1, 0, 0>, <0, 1, 0> } uv_vectors { 3, <0, 0>, <1, 0>, <0, 1> }\n"
      "  face_indices { 1, <2, 0, 1> } }\n"
      "mesh { triangle { <0, 0, 0>, <1, 0, 0>, <0, 1, 0> uv_vectors <0, 0.5>, <1, 0.5>, <0.25, 1> }\n"
      "  smooth_triangle { <0, 0, 0>, z, <1, 0, 0>, z, <0, 1, 0>, z } }");
  ASSERT_EQ(s.objects().size(), 3u);
  const auto data = [&](std::size_t i) -> const MeshData& { return dynamic_cast<const Mesh&>(*s.objects()[i]).data; };
  ASSERT_EQ(data(0).texcoords.size(), 2u);
  EXPECT_EQ(data(0).texcoords[0], (Texcoord{0.5, 0.25}));
  EXPECT_EQ(data(0).texcoords[1], (Texcoord{0.75, 0.75}));
  EXPECT_EQ(data(0).faces[0].t, (std::array<std::int32_t, 3>{1, 0, 1}));
  EXPECT_EQ(data(1).faces[0].t, (std::array<std::int32_t, 3>{2, 0, 1}));
  ASSERT_EQ(data(2).texcoords.size(), 4u);
  EXPECT_EQ(data(2).texcoords[2], (Texcoord{0.25, 1}));
  EXPECT_EQ(data(2).faces[0].t, (std::array<std::int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(data(2).faces[1].t, (std::array<std::int32_t, 3>{3, 3, 3}));
  EXPECT_EQ(data(2).texcoords[3], (Texcoord{0, 0}));
}

TEST(PovImport, UvMappingErrorsNameWhatIsMissing) {
  const std::string verts = "mesh2 { vertex_vectors { 3, <0, 0, 0>, <1, 0, 0>, <0, 1, 0> } ";
  const std::string image = " pigment { uv_mapping image_map { \"a.png\" } } }";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"sphere { 0, 1" + image, "test.pov:1:1: uv_mapping on a sphere: strahl reads uv-mapped images on meshes"},
           {"disc { 0, y, 1" + image, "test.pov:1:1: uv_mapping on a disc:"},
           {verts + "face_indices { 1, <0, 1, 2> }" + image, "test.pov:1:1: uv_mapping on a mesh without uv_vectors"},
           {verts + "uv_vectors { 2, 0, 1 } face_indices { 1, <0, 1, 2> } }",
                     "test.pov:1:86: face_indices: index 2 is past the uv_vectors (2); without uv_indices"},
           {verts + "uv_vectors { 2, 0, 1 } face_indices { 1, <0, 1, 2> } uv_indices { 1, <0, 1, 2> } }",
                     "test.pov:1:116: uv_indices: index 2 is past the uv_vectors (2)"},
           {verts + "uv_vectors { 2, 0, 1 } face_indices { 1, <0, 1, 2> } uv_indices { 2, <0, 1, 1>, <0, 0, 0> } }",
                     "test.pov:1:116: uv_indices needs one entry per face (2 for 1 faces)"},
           {verts + "face_indices { 1, <0, 1, 2> } uv_indices { 1, <0, 1, 1> } }",
                     "test.pov:1:93: uv_indices without uv_vectors"},
           {"mesh { triangle { 0, x, y uv_vectors 0, 1 } }", "test.pov:1:43: expected ','"},
           {"sphere { 0, 1 pigment { uv_mapping image_map { \"a.png\" map_type 1 } } }",
                     "test.pov:1:36: strahl reads a uv-mapped image_map with map_type 0 only"},
           {"sphere { 0, 1 pigment { uv_mapping checker } }", "test.pov:1:36: strahl reads uv_mapping for an image_map only"}})
    EXPECT_EQ(pov_error(text).rfind(message, 0), 0u) << text << "\n" << pov_error(text);
}

// A fade is the light's own (POV-Ray's formula, tests/spotlight_test.cpp), but a parallel light
// is directional in strahl and does not fade: a warning says so.
TEST(PovImport, AParallelLightsFadeIsLeftOutWithAWarning) {
  const Scene s = pov_scene("#version 3.7;\nsphere { 0, 1 }\n"
                            "light_source { <0, 10, 0> color rgb 1 parallel point_at 0 fade_distance 2 fade_power 2 }");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].rfind("test.pov:3:1: fade_distance and fade_power are left out: a parallel light", 0), 0u)
      << s.warnings[0];
  EXPECT_EQ(s.lights().at(0).fade_power, 0);
  EXPECT_TRUE(pov_scene("#version 3.7;\nsphere { 0, 1 }\nlight_source { <0, 10, 0> color rgb 1 fade_distance 2 fade_power 2 }")
                  .warnings.empty());
  // POV-Ray draws a light with fade_distance 0 as one without a fade (checked with POV-Ray 3.7).
  EXPECT_EQ(pov_scene("sphere { 0, 1 }\nlight_source { <0, 10, 0> color rgb 1 fade_power 2 }").lights().at(0).fade_power, 0);
}

}  // namespace
}  // namespace strahl::pov_import_test
