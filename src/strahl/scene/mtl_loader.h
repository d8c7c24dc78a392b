#pragma once
// Wavefront MTL material libraries (an OBJ file's `mtllib`), read by hand for what a mesh's
// `file_materials` uses: each material's diffuse colour (Kd) and picture (map_Kd). Other
// statements (Ka, Ks, Ns, d, illum, bump and other maps, …) are skipped; docs/scene-format.md
// (`mesh`) lists what is read and refused.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/math/vec3.h"

namespace strahl {

struct MtlMaterial {
  std::string name;
  Vec3 kd{1, 1, 1};              // the diffuse colour (linear RGB; 1 where the file gives none)
  std::filesystem::path map_kd;  // the picture's file (empty: none), relative names resolved
  std::string file;              // where it was defined, for messages
  int line = 0, map_kd_line = 0;
};

// Throws strahl::Error naming file:line:column for the first problem: a Kd without three finite,
// non-negative numbers (or in another form, spectral or xyz), map_Kd without a file name or with
// options (-s, -o, …), a statement before the first newmtl that needs a material, a material
// defined twice. Picture names are resolved relative to `dir` (backslashes read as '/').
std::vector<MtlMaterial> parse_mtl(std::string_view text, const std::string& name, const std::filesystem::path& dir);
std::vector<MtlMaterial> load_mtl(const std::filesystem::path& path);

}  // namespace strahl
