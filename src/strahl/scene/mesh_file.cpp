#include "strahl/scene/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "strahl/scene/obj_loader.h"
#include "strahl/scene/ply_loader.h"
#include "strahl/util/error.h"

namespace strahl {

MeshData load_mesh(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".obj") return load_obj(path);
  if (ext == ".ply") return load_ply(path);
  throw Error(FileLoc{path.string()}, "unknown mesh format '" + path.extension().string() + "' (use .obj or .ply)");
}

}  // namespace strahl
