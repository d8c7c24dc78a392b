#include "strahl/scene/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "strahl/scene/gltf_loader.h"
#include "strahl/scene/obj_loader.h"
#include "strahl/scene/ply_loader.h"
#include "strahl/util/error.h"
#include "strahl/util/system_error.h"

namespace strahl {

LargeArray<char> read_mesh_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(FileLoc{file}, "cannot open mesh file: " + (ec ? ec.message() : std::string("not a regular file")));
  const std::uintmax_t expected = std::filesystem::file_size(path, ec);
  if (ec) throw Error(FileLoc{file}, "cannot open mesh file: " + ec.message());
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) throw Error(FileLoc{file}, "cannot open mesh file: " + system_reason(errno));
  LargeArray<char> bytes;
  try {
    bytes.resize(static_cast<std::size_t>(expected) + 1);
  } catch (const std::exception&) {  // bad_alloc, length_error
    throw Error(FileLoc{file}, "the file is too large to read into memory (" + std::to_string(expected) + " bytes)");
  }
  bytes.resize(std::fread(bytes.data(), 1, static_cast<std::size_t>(expected), f.get()));
  if (std::ferror(f.get())) throw Error(FileLoc{file}, "cannot read mesh file: " + system_reason(errno));
  return bytes;
}

namespace {
std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}
}  // namespace

bool is_gltf_file(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".gltf" || ext == ".glb";
}

bool gives_materials(const std::filesystem::path& path) { return is_gltf_file(path) || lower_extension(path) == ".obj"; }

MeshData load_mesh(const std::filesystem::path& path, bool materials) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return load_obj(path, materials);
  if (ext == ".ply") return load_ply(path);
  if (is_gltf_file(path)) return load_gltf(path, materials);
  throw Error(FileLoc{path.string()}, "unknown mesh format '" + path.extension().string() + "' (use .obj, .ply, .gltf or .glb)");
}

}  // namespace strahl
