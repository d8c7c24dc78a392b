#pragma once
// The loaders' fuzz entries, shared by the libFuzzer targets (tests/fuzz/fuzz_*.cpp) and the
// normal test suite (tests/fuzz_regression_test.cpp replays saved inputs through them).
// Each takes arbitrary bytes, loads them and compiles the result into a RenderScene. A
// strahl::Error is the expected answer to bad input; anything else (a crash, a sanitizer report,
// another exception escaping, a huge allocation) is a bug.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "strahl/render/render_scene.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/ply_loader.h"
#include "strahl/scene/scene_file.h"
#include "strahl/util/error.h"

namespace strahl::fuzz {

// Whether the input was accepted (compiled) or refused with a strahl::Error.
enum class Outcome { Accepted, Refused };

inline Outcome compile_scene(const Scene& scene) {
  // Resolutions up to 2^28 pixels are legal, but compile() only records them: nothing renders here.
  try {
    (void)compile(scene);
  } catch (const Error&) {
    return Outcome::Refused;
  }
  return Outcome::Accepted;
}

// A scene file's text; mesh paths resolve in a directory that does not exist.
inline Outcome scene_input(const std::uint8_t* data, std::size_t size) {
  Scene scene;
  try {
    scene = parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml",
                        "/nonexistent-strahl-fuzz-dir");
  } catch (const Error&) {
    return Outcome::Refused;
  }
  return compile_scene(scene);
}

inline Outcome mesh_outcome(MeshData (*parse)(std::string_view, const std::string&), const char* name,
                            const std::uint8_t* data, std::size_t size) {
  Scene scene;
  try {
    MeshData mesh = parse(std::string_view(reinterpret_cast<const char*>(data), size), name);
    scene.add(Mesh(std::move(mesh), Material{}, Transform{}));
  } catch (const Error&) {
    return Outcome::Refused;
  }
  scene.settings.width = 4;
  scene.settings.height = 4;
  return compile_scene(scene);
}

inline Outcome obj_input(const std::uint8_t* data, std::size_t size) {
  return mesh_outcome(&parse_obj, "fuzz.obj", data, size);
}
inline Outcome ply_input(const std::uint8_t* data, std::size_t size) {
  return mesh_outcome(&parse_ply, "fuzz.ply", data, size);
}

}  // namespace strahl::fuzz
