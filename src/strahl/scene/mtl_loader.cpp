#include "strahl/scene/mtl_loader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "strahl/scene/mesh_file.h"
#include "strahl/util/error.h"

namespace strahl {

namespace {

struct Token {
  std::string_view text;
  int column;  // 1-based
};

class MtlReader {
 public:
  MtlReader(const std::string& name, const std::filesystem::path& dir) : name_(name), dir_(dir) {}

  std::vector<MtlMaterial> read(std::string_view text) {
    int line = 0;
    for (std::size_t pos = 0; pos < text.size();) {
      ++line;
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      statement(text.substr(pos, end - pos), line);
      pos = end + 1;
    }
    return std::move(materials_);
  }

 private:
  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw Error(FileLoc{name_, line, column}, message);
  }

  void split(std::string_view s, int line) {
    tokens_.clear();
    for (std::size_t i = 0; i < s.size();) {
      const unsigned char c = static_cast<unsigned char>(s[i]);
      if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++i;
        continue;
      }
      if (c == '#') break;
      const std::size_t start = i;
      for (; i < s.size(); ++i) {
        const unsigned char d = static_cast<unsigned char>(s[i]);
        if (d == ' ' || d == '\t' || d == '\r' || d == '\f' || d == '\v') break;
        if (d < 0x20 || d == 0x7f) {
          char hex[8];
          std::snprintf(hex, sizeof hex, "0x%02x", d);
          fail(line, int(i) + 1, std::string("not a text file (byte ") + hex + ")");
        }
      }
      tokens_.push_back({s.substr(start, i - start), int(start) + 1});
    }
  }

  MtlMaterial& current(const Token& key, int line) {
    if (materials_.empty()) fail(line, key.column, std::string(key.text) + " before the first newmtl");
    return materials_.back();
  }

  void statement(std::string_view s, int line) {
    split(s, line);
    if (tokens_.empty()) return;
    const Token& key = tokens_[0];
    const auto end_column = [&] { return tokens_.back().column + int(tokens_.back().text.size()); };
    if (key.text == "newmtl") {
      if (tokens_.size() != 2) fail(line, tokens_.size() < 2 ? end_column() : tokens_[2].column, "newmtl needs one name");
      const std::string n(tokens_[1].text);
      for (const MtlMaterial& m : materials_)
        if (m.name == n) fail(line, tokens_[1].column, "material '" + n + "' is defined twice (first on line " + std::to_string(m.line) + ")");
      materials_.push_back({n, Vec3(1, 1, 1), {}, name_, line, 0});
    } else if (key.text == "Kd") {
      MtlMaterial& m = current(key, line);
      if (tokens_.size() >= 2 && (tokens_[1].text == "spectral" || tokens_[1].text == "xyz"))
        fail(line, tokens_[1].column, "Kd " + std::string(tokens_[1].text) + " is not read (only Kd r g b)");
      if (tokens_.size() != 4 && tokens_.size() != 2)
        fail(line, tokens_.size() < 4 ? end_column() : tokens_[4].column, "Kd needs r g b (or one number for all three)");
      double c[3];
      for (std::size_t k = 1; k < tokens_.size(); ++k) c[k - 1] = number(tokens_[k], line);
      m.kd = tokens_.size() == 2 ? Vec3(c[0]) : Vec3(c[0], c[1], c[2]);
    } else if (key.text == "map_Kd") {
      MtlMaterial& m = current(key, line);
      if (tokens_.size() < 2) fail(line, end_column(), "map_Kd needs a file name");
      if (tokens_[1].text[0] == '-')
        fail(line, tokens_[1].column, "map_Kd options ('" + std::string(tokens_[1].text) + "', …) are not read");
      // The rest of the line is the name (it may hold spaces); Windows' backslashes as '/'.
      std::string file(s.substr(std::size_t(tokens_[1].column - 1),
                                std::size_t(end_column() - tokens_[1].column)));
      for (char& ch : file)
        if (ch == '\\') ch = '/';
      m.map_kd = dir_ / file;
      m.map_kd_line = line;
    }
    // Everything else (Ka, Ks, Ke, Ns, Ni, d, Tr, Tf, illum, map_Ka, map_Ks, bump, …) is skipped.
  }

  double number(const Token& t, int line) const {
    std::string_view v = t.text;
    if (v.size() > 1 && v[0] == '+') v.remove_prefix(1);
    double x = 0;
    const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    if (ec != std::errc() || p != v.data() + v.size() || !std::isfinite(x))
      fail(line, t.column, "Kd: '" + std::string(t.text) + "' is not a finite number");
    if (x < 0) fail(line, t.column, "Kd: '" + std::string(t.text) + "' is negative");
    return x;
  }

  const std::string& name_;
  const std::filesystem::path& dir_;
  std::vector<Token> tokens_;
  std::vector<MtlMaterial> materials_;
};

}  // namespace

std::vector<MtlMaterial> parse_mtl(std::string_view text, const std::string& name, const std::filesystem::path& dir) {
  return MtlReader(name, dir).read(text);
}

std::vector<MtlMaterial> load_mtl(const std::filesystem::path& path) {
  const LargeArray<char> text = read_mesh_file(path);
  return parse_mtl(std::string_view(text.data(), text.size()), path.string(), path.parent_path());
}

}  // namespace strahl
