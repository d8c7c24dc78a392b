#pragma once
// Limits a scene file's YAML must keep, checked by a streaming pass over the text before
// yaml-cpp builds its tree (several hundred bytes per node), so an over-large input is refused
// before the memory is spent (docs/scene-format.md, "Size limits"):
//   * at most kMaxSceneNodes nodes (values, lists and maps) in all;
//   * only the top-level `objects` and `lights` lists may hold more than kMaxShortList elements
//     (a CSG node's `objects` up to kMaxCsgList), and only the top-level `materials` map more than kMaxShortMap keys: every other
//     list or map of the format is a vector, a colour, a transform or one object's keys.
// The pass also polls the cancel flag (util/cancel.h), so a signal ends it, and finds where the
// elements of the top-level `objects` list start, so that the loader can read them one at a time
// instead of holding the whole file's tree.

#include <cstddef>
#include <string>
#include <vector>

namespace strahl {

inline constexpr std::size_t kMaxSceneNodes = std::size_t(1) << 22;  // 4,194,304: some 350,000 spheres
inline constexpr std::size_t kMaxShortList = 16;
inline constexpr std::size_t kMaxShortMap = 64;
inline constexpr std::size_t kMaxCsgList = 256;  // kernel::kMaxCsgLeaves

struct YamlOutline {
  // The top-level `objects` list is in block style (one `- ` per element) and the document has
  // no anchors or aliases, so its elements can be read one at a time.
  bool objects_by_element = false;
  struct Element {
    int line, column;  // where the element starts (0-based, as yaml-cpp counts)
  };
  std::vector<Element> elements;
  int objects_end_line = -1;  // the line of the first node after the list, −1: the text ends first
};

// Throws strahl::Error naming file:line:column of the node that passes a limit, or of a syntax
// error. Reads the first document only, as the loader does.
YamlOutline check_yaml_limits(const std::string& text, const std::string& name);

}  // namespace strahl
