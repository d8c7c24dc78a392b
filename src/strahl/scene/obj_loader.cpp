#include "strahl/scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <system_error>

#include "strahl/util/error.h"

namespace strahl {

MeshData load_obj(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(FileLoc{path.string()}, "cannot open mesh file");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = path.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config)) {
    std::string message = reader.Error();
    while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
    throw Error(FileLoc{path.string()}, "cannot read OBJ: " + (message.empty() ? "parse error" : message));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  MeshData mesh;
  mesh.positions.reserve(attrib.vertices.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    mesh.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
  mesh.normals.reserve(attrib.normals.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.normals.size(); i += 3)
    mesh.normals.emplace_back(attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]);

  const auto vertex_count = static_cast<long>(mesh.positions.size());
  const auto normal_count = static_cast<long>(mesh.normals.size());
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    std::size_t offset = 0;
    for (const unsigned char fv : shape.mesh.num_face_vertices) {
      if (fv == 3) {
        MeshData::Face face;
        for (int k = 0; k < 3; ++k) {
          const tinyobj::index_t& idx = indices[offset + std::size_t(k)];
          if (idx.vertex_index < 0 || idx.vertex_index >= vertex_count)
            throw Error(FileLoc{path.string()}, "face in shape '" + shape.name + "' refers to vertex " +
                                                    std::to_string(idx.vertex_index + 1) + " of " +
                                                    std::to_string(vertex_count));
          face.v[std::size_t(k)] = static_cast<std::uint32_t>(idx.vertex_index);
          face.n[std::size_t(k)] = (idx.normal_index >= 0 && idx.normal_index < normal_count) ? idx.normal_index : -1;
        }
        mesh.faces.push_back(face);
      }
      offset += fv;
    }
  }
  if (mesh.faces.empty()) throw Error(FileLoc{path.string()}, "OBJ file contains no faces");
  return mesh;
}

}  // namespace strahl
