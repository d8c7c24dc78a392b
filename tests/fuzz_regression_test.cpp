// Replays the fuzz targets' seed corpora (tests/fuzz/corpus/) and every saved input that once
// crashed a loader (tests/fuzz/regressions/) through the same entry functions the libFuzzer
// targets call: each must be accepted or refused with a strahl::Error, nothing else.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fuzz/fuzz_entries.h"
#include "test_helpers.h"

namespace strahl::fuzz_regression_test {
namespace {

using Entry = fuzz::Outcome (*)(const std::uint8_t*, std::size_t);

int replay(const std::string& kind, Entry entry) {
  int count = 0;
  for (const char* set : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(STRAHL_SOURCE_DIR) / "tests" / "fuzz" / set / kind;
    for (const auto& e : fs::directory_iterator(dir)) {
      if (!e.is_regular_file() || e.path().filename() == "README") continue;
      const std::string bytes = test::read_text(e.path());
      SCOPED_TRACE(e.path().string());
      EXPECT_NO_THROW(entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
      ++count;
    }
  }
  return count;
}

TEST(FuzzRegression, SceneInputs) { EXPECT_GT(replay("scene", &fuzz::scene_input), 5); }
TEST(FuzzRegression, PovInputs) { EXPECT_GT(replay("pov", &fuzz::pov_input), 4); }
TEST(FuzzRegression, ObjInputs) { EXPECT_GT(replay("obj", &fuzz::obj_input), 5); }
TEST(FuzzRegression, PlyInputs) { EXPECT_GT(replay("ply", &fuzz::ply_input), 5); }
TEST(FuzzRegression, GltfInputs) { EXPECT_GT(replay("gltf", &fuzz::gltf_input), 5); }
TEST(FuzzRegression, ExpressionInputs) { EXPECT_GT(replay("expression", &fuzz::expression_input), 5); }

// The seeds that are valid meshes and scenes are accepted (so the targets reach compile()).
TEST(FuzzRegression, ValidSeedsAreAccepted) {
  const auto accepted = [](Entry entry, const fs::path& file) {
    const std::string bytes = test::read_text(file);
    return entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()) == fuzz::Outcome::Accepted;
  };
  const fs::path corpus = fs::path(STRAHL_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
  EXPECT_TRUE(accepted(&fuzz::scene_input, corpus / "scene" / "lecture-whitted.yaml"));
  for (const char* pov : {"lecture.pov", "shapes.pov", "csg.pov", "directives.pov", "meshes.pov", "macros.pov"})
    EXPECT_TRUE(accepted(&fuzz::pov_input, corpus / "pov" / pov)) << pov;
  EXPECT_TRUE(accepted(&fuzz::obj_input, corpus / "obj" / "quad-normals-uv.obj"));
  EXPECT_TRUE(accepted(&fuzz::obj_input, corpus / "obj" / "icosahedron.obj"));
  EXPECT_TRUE(accepted(&fuzz::ply_input, corpus / "ply" / "binary_big_endian-quad.ply"));
  EXPECT_TRUE(accepted(&fuzz::ply_input, corpus / "ply" / "ascii-normals.ply"));
  for (const char* gltf : {"carousel.glb", "fan-data-uri.gltf", "sparse-quantized.gltf", "material-image.gltf"})
    EXPECT_TRUE(accepted(&fuzz::gltf_input, corpus / "gltf" / gltf)) << gltf;
  EXPECT_TRUE(accepted(&fuzz::expression_input, corpus / "expression" / "torus"));
}

}  // namespace
}  // namespace strahl::fuzz_regression_test
