#pragma once
// Where a glTF 2.0 file's bytes are: the binary container (.glb: a 12-byte header, a JSON chunk
// and an optional BIN chunk) and the URIs of its buffers (base64 `data:` URIs and relative file
// names, percent-encoded). Byte work only; the JSON is read by gltf_loader.cpp.

#include <string>
#include <string_view>

#include "strahl/util/large_array.h"

namespace strahl::gltf {

// The JSON text and the BIN chunk (empty view: none) of a file: a .glb's chunks where the bytes
// start with the magic "glTF", else the whole text. Throws strahl::Error naming `name` and the
// byte offset of a container that is cut short or malformed.
struct Container {
  std::string_view json;
  std::string_view bin;
  bool binary = false;  // the bytes were a .glb
};
Container split_container(std::string_view bytes, const std::string& name);

// A URI's scheme ("data", "http", …) or empty for a relative reference (a file name).
std::string uri_scheme(std::string_view uri);

// The bytes of a `data:` URI whose payload is base64 ("data:<media type>;base64,<payload>").
// Throws strahl::Error (message only; the caller adds where) for another encoding or a character
// outside the base64 alphabet.
LargeArray<char> decode_data_uri(std::string_view uri);

// A relative reference's %XX escapes decoded ("my%20mesh.bin" → "my mesh.bin"). Throws
// strahl::Error for a '%' without two hexadecimal digits or a decoded NUL byte.
std::string decode_percent(std::string_view uri);

}  // namespace strahl::gltf
