// Reads YAML/JSON scene files into a Scene (scene_file.h): the entry of the YAML reader
// (yaml_reader.h). Limits are checked before any tree is built; then the scene's sections are read
// and the top-level objects, each parsed from its own text (a batch at a time on all cores).

#include <yaml-cpp/yaml.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <exception>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "strahl/scene/scene_file.h"
#include "strahl/scene/yaml_limits.h"
#include "strahl/scene/yaml_merge.h"
#include "strahl/scene/yaml_reader.h"
#include "strahl/util/cancel.h"
#include "strahl/util/large_pages.h"
#include "strahl/util/system_error.h"

namespace strahl {
namespace fs = std::filesystem;

// `objects`: when not empty, the text of each element of the top-level objects list, read one
// at a time (the list itself was blanked out of `root`'s text, line numbers kept).
Scene YamlReader::read(const YAML::Node& root, const std::vector<ObjectText>& objects) {
  Scene scene;
  if (root.IsNull()) fail(root, "the scene file is empty");
  map(root, "scene");
  keys(root, {"camera", "render", "materials", "groups", "lights", "objects"}, "scene");
  if (const YAML::Node n = root["render"]) render(n, scene.settings);
  if (const YAML::Node n = root["camera"]) camera(n, scene.camera);
  if (const YAML::Node n = root["materials"]) {
    map(n, "materials");
    for (const auto& kv : n) {
      const std::string name = scalar(kv.first, "material name");
      if (materials_.count(name)) fail(kv.first, "material '" + name + "' is defined twice");
      materials_[name] = material(kv.second);
    }
  }
  if (const YAML::Node n = root["groups"]) groups(n, scene);
  if (const YAML::Node n = root["lights"]) {
    sequence(n, "lights");
    for (const YAML::Node& l : n) light(l, scene);
  }
  if (!objects.empty()) {
    // The elements' texts are parsed a batch at a time on all cores, then read in the file's
    // order, so that errors come as a reading from the top meets them; memory holds one batch.
    constexpr std::size_t kBatch = 512;
    std::vector<std::optional<YAML::Node>> elements;
    std::vector<std::exception_ptr> failures;
    for (std::size_t first = 0; first < objects.size(); first += kBatch) {
      check_cancelled("yaml");
      const std::size_t count = std::min(kBatch, objects.size() - first);
      elements.assign(count, std::nullopt);
      failures.assign(count, nullptr);
      tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
        const ObjectText& o = objects[first + k];
        try {
          YAML::Node element = YAML::Load(o.text);
          if (may_hold_merge_keys(o.text)) expand_merge_keys(element, name_, o.line);
          elements[k].emplace(element);
        } catch (const YAML::Exception& e) {
          failures[k] = std::make_exception_ptr(
              Error(FileLoc{name_, o.line + e.mark.line + 1, e.mark.column + 1}, "syntax error: " + e.msg));
        } catch (...) {
          failures[k] = std::current_exception();
        }
      });
      for (std::size_t k = 0; k < count; ++k) {
        if (failures[k]) std::rethrow_exception(failures[k]);
        line_offset_ = objects[first + k].line;
        object(*elements[k], scene);
        line_offset_ = 0;
      }
    }
  } else if (const YAML::Node n = root["objects"]) {
    sequence(n, "objects");
    for (const YAML::Node& o : n) {
      check_cancelled("yaml");
      object(o, scene);
    }
  }
  if (scene.objects().empty()) fail(root, "the scene has no objects");
  for (ImageTexture& t : textures_) scene.add_texture(std::move(t));  // (in order: materials hold their indices)
  textures_.clear();
  return scene;
}

namespace {

// The scene's text with the top-level objects list cut out (its lines left empty, so line numbers
// stay), and the text of each of its elements: the lines from its start to the next one's, with
// the `- ` in front of it blanked (columns stay). Empty when the outline does not allow it.
struct SplitText {
  std::string rest;
  std::vector<ObjectText> objects;
};
SplitText split_objects(const std::string& text, const YamlOutline& outline) {
  SplitText out;
  if (!outline.objects_by_element) return out;
  std::vector<std::size_t> starts{0};  // of each line
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  const auto line_start = [&](int line) { return line < int(starts.size()) ? starts[std::size_t(line)] : text.size(); };
  const int first = outline.elements.front().line;
  const int end = outline.objects_end_line >= 0 ? outline.objects_end_line : int(starts.size());
  std::vector<ObjectText> objects;
  objects.reserve(outline.elements.size());
  for (std::size_t k = 0; k < outline.elements.size(); ++k) {
    const YamlOutline::Element& e = outline.elements[k];
    const int next = k + 1 < outline.elements.size() ? outline.elements[k + 1].line : end;
    if (next <= e.line) return out;  // two elements on one line: read the whole tree
    const std::size_t from = line_start(e.line), to = line_start(next);
    std::string element = text.substr(from, to - from);
    // Only blanks and the element's dash may stand before it on its first line.
    const std::size_t prefix = std::size_t(e.column);
    if (prefix > element.size() || element.substr(0, prefix).find('-') == std::string::npos) return out;
    for (std::size_t i = 0; i < prefix; ++i) {
      if (element[i] != ' ' && element[i] != '\t' && element[i] != '-') return out;
      element[i] = ' ';
    }
    objects.push_back({e.line, std::move(element)});
  }
  out.rest.reserve(text.size() - (line_start(end) - line_start(first)) + std::size_t(end - first));
  out.rest.append(text, 0, line_start(first));
  out.rest.append(std::size_t(std::max(0, std::min(end, int(starts.size())) - first)), '\n');
  out.rest.append(text, line_start(end), std::string::npos);
  out.objects = std::move(objects);
  return out;
}


// Where a second YAML document begins: a `---` line (or a `...` end marker followed by more)
// after the first document's content; line 0 when there is none. Comments and blank lines are
// no content, and a `---` before any content only opens the first document.
FileLoc second_document(const std::string& text, const std::string& name) {
  bool content = false, ended = false;
  int line = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view l(text.data() + start, end - start);
    ++line;
    start = end + 1;
    const auto marker = [&](std::string_view m) {
      return l.substr(0, 3) == m && (l.size() == 3 || l[3] == ' ' || l[3] == '\t' || l[3] == '\r');
    };
    if (marker("---")) {
      if (content || ended) return FileLoc{name, line, 1};
      continue;
    }
    if (marker("...")) {
      ended = content;
      continue;
    }
    const std::size_t first = l.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || l[first] == '#') continue;
    if (ended) return FileLoc{name, line, 1};
    if (l[0] != '%') content = true;  // (a %YAML directive precedes a document's ---)
  }
  return FileLoc{name, 0, 0};
}
}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const fs::path& base_dir, const MeshSource& meshes) {
  // yaml-cpp reads a NUL byte as the end of the text: a binary or UTF-16 file would be half read.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const std::size_t line_start = text.rfind('\n', nul);
    const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'));
    const int column = int(nul - (line_start == std::string::npos ? 0 : line_start + 1)) + 1;
    throw Error(FileLoc{name, line, column}, "not a text file (a NUL byte; scene files are UTF-8 text)");
  }
  // Before the tree is built: an input too large for the format is refused at constant memory.
  // Then the objects are read each from its own text where the text allows it, so that memory
  // holds a batch's trees, not the whole file's (docs/scene-format.md, "Size limits").
  SplitText split = split_objects(text, check_yaml_limits(text, name));
  YAML::Node root;
  try {
    root = YAML::Load(split.objects.empty() ? text : split.rest);
  } catch (const YAML::Exception& e) {
    throw Error(FileLoc{name, e.mark.line + 1, e.mark.column + 1}, "syntax error: " + e.msg);
  }
  if (may_hold_merge_keys(split.objects.empty() ? text : split.rest)) expand_merge_keys(root, name);
  split.rest = std::string();
  Scene scene = YamlReader(name, base_dir, meshes).read(root, split.objects);
  // A scene is one document; what follows a second `---` would be silently dropped.
  if (const FileLoc second = second_document(text, name); second.line > 0)
    scene.warnings.push_back(second.str() +
                             ": a second YAML document starts here (after ---); only the first is read, the rest is ignored");
  return scene;
}

Scene load_scene(const fs::path& path, const PovOptions& pov) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".yaml" && ext != ".yml" && ext != ".json" && ext != ".pov")
    throw Error(FileLoc{path.string()}, "unknown scene format '" + ext + "' (use .yaml, .yml, .json or .pov)");
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(FileLoc{path.string()}, "cannot open scene file (no such file)");
  if (fs::is_directory(path, ec)) throw Error(FileLoc{path.string()}, "is a directory, not a scene file");
  // A FIFO would block and /dev/zero would never end.
  if (!fs::is_regular_file(path, ec))
    throw Error(FileLoc{path.string()}, "is not a regular file (a FIFO, device or socket), not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(FileLoc{path.string()}, "cannot open scene file: " + system_reason(errno));
  Scene scene = [&] {
    std::ostringstream text;
    text << in.rdbuf();
    return ext == ".pov" ? parse_pov_scene(text.str(), path.string(), pov) : parse_scene(text.str(), path.string(), path.parent_path());
  }();
  give_back_free_heap();  // the text's and the parser's memory (util/large_pages.h)
  return scene;
}

}  // namespace strahl
