#pragma once
// POV-Ray scenes (.pov): the importer reads a subset of POV-Ray 3.7's scene description language
// (docs/pov-import.md lists it) and translates it into strahl's own scene format, which the one
// scene reader (scene_file.h) then reads: every value is checked there, and its errors and
// warnings name the .pov file's line and column. Meshes (`mesh`, `mesh2`) go to the reader as
// mesh data, not as YAML text.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "strahl/scene/mesh_data.h"
#include "strahl/scene/scene.h"

namespace strahl {

struct PovOptions {
  int width = 1280;   // image_width (POV-Ray's +W) and the render's width
  int height = 720;   // image_height (+H)
  std::vector<std::pair<std::string, double>> declares;  // POV-Ray's Declare=NAME=VALUE
  // Bounds on what a file can make the importer do (errors past them): loop iterations
  // (#while and #for together, and macro calls), tokens read (loops and macros read their
  // bodies again) and objects. A caller reading untrusted files in bounded time lowers them (the
  // scene reader takes ~0.1 ms per object).
  long max_loop_iterations = 1'000'000;
  std::size_t max_tokens_read = 50'000'000;
  std::size_t max_objects = 200'000;
};

// The scene in strahl's format: YAML text, where each line came from (the .pov item it
// translates), the meshes it names as "pov-mesh-N", and what the importer left out.
struct PovTranslation {
  std::string yaml;
  std::vector<FileLoc> line_locs;  // [line − 1]: the .pov location of the YAML text's line
  std::vector<MeshData> meshes;
  std::vector<std::string> warnings;
};

// `text` is the scene file `name` (#include finds files beside it). Throws strahl::Error with
// the .pov file's file:line:column for syntax errors and what the importer does not support.
PovTranslation translate_pov(const std::string& text, const std::string& name, const PovOptions& options);

// translate_pov, then the scene reader; its errors and warnings point into the .pov file.
// (load_scene() in scene_file.h reads a .pov file through this.)
Scene parse_pov_scene(const std::string& text, const std::string& name, const PovOptions& options);

}  // namespace strahl
