#include "strahl/scene/gltf_data.h"

#include <cstdint>

#include "strahl/util/error.h"

namespace strahl::gltf {

namespace {

constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

std::uint32_t le32(std::string_view b, std::size_t at) {
  const auto byte = [&](std::size_t k) { return std::uint32_t(static_cast<unsigned char>(b[at + k])); };
  return byte(0) | byte(1) << 8 | byte(2) << 16 | byte(3) << 24;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

int base64_digit(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;  // (also the URL-safe alphabet's)
  if (c == '/' || c == '_') return 63;
  return -1;
}

}  // namespace

Container split_container(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 4 || le32(bytes, 0) != kMagic) return {bytes, {}, false};
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw Error(FileLoc{name}, "binary glTF, byte " + std::to_string(at) + ": " + what);
  };
  if (bytes.size() < 12) fail(bytes.size(), "the 12-byte header is cut short");
  if (const std::uint32_t version = le32(bytes, 4); version != 2)
    fail(4, "version " + std::to_string(version) + " (strahl reads glTF 2)");
  const std::uint32_t length = le32(bytes, 8);
  if (length > bytes.size())
    fail(8, "the header gives a length of " + std::to_string(length) + " bytes, but the file has " +
                std::to_string(bytes.size()));
  bytes = bytes.substr(0, length);
  Container c{{}, {}, true};
  std::size_t at = 12;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8) fail(at, "a chunk header is cut short");
    const std::uint32_t size = le32(bytes, at), type = le32(bytes, at + 4);
    if (size > bytes.size() - at - 8)
      fail(at, "a chunk of " + std::to_string(size) + " bytes reaches past the end of the file");
    const std::string_view data = bytes.substr(at + 8, size);
    if (chunk == 0 && type != kChunkJson) fail(at + 4, "the first chunk is not JSON");
    if (chunk == 0) c.json = data;
    if (chunk == 1 && type == kChunkBin) c.bin = data;
    at += 8 + std::size_t(size);  // (chunks of other types are skipped, as the format asks)
  }
  if (c.json.data() == nullptr) fail(12, "the file has no JSON chunk");
  return c;
}

std::string uri_scheme(std::string_view uri) {
  // RFC 3986: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":". One letter before ':' is taken as a
  // Windows drive ("C:/…"), not a scheme.
  const std::size_t colon = uri.find(':');
  if (colon == std::string_view::npos || colon < 2) return {};
  for (std::size_t i = 0; i < colon; ++i) {
    const char c = uri[i];
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    if (!alpha && (i == 0 || !((c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.'))) return {};
  }
  return std::string(uri.substr(0, colon));
}

LargeArray<char> decode_data_uri(std::string_view uri) {
  const std::size_t comma = uri.find(',');
  const std::string_view head = uri.substr(0, comma);
  if (comma == std::string_view::npos || head.size() < 7 || head.substr(head.size() - 7) != ";base64")
    throw Error("a data: URI must hold base64 (data:<media type>;base64,…)");
  std::string_view text = uri.substr(comma + 1);
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  if (text.size() % 4 == 1) throw Error("the base64 data of a data: URI is cut short");
  LargeArray<char> out;
  out.resize(text.size() / 4 * 3 + (text.size() % 4 == 0 ? 0 : text.size() % 4 - 1));
  std::uint32_t bits = 0;
  int held = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int d = base64_digit(text[i]);
    if (d < 0)
      throw Error("character " + std::to_string(i + comma + 2) + " of a data: URI is not base64");
    bits = bits << 6 | std::uint32_t(d);
    held += 6;
    if (held >= 8) {
      held -= 8;
      out[n++] = static_cast<char>((bits >> held) & 0xff);
    }
  }
  return out;
}

std::string decode_percent(std::string_view uri) {
  std::string out;
  out.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '\0') throw Error("a URI must not hold a NUL character");
    if (uri[i] != '%') {
      out += uri[i];
      continue;
    }
    const int hi = i + 2 < uri.size() ? hex_digit(uri[i + 1]) : -1, lo = hi >= 0 ? hex_digit(uri[i + 2]) : -1;
    if (lo < 0) throw Error("'%' in a URI must be followed by two hexadecimal digits");
    if (hi == 0 && lo == 0) throw Error("a URI must not hold %00");
    out += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return out;
}

}  // namespace strahl::gltf
