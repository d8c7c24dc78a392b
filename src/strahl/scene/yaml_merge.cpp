#include "strahl/scene/yaml_merge.h"

#include <set>
#include <utility>
#include <vector>

#include "strahl/scene/yaml_limits.h"
#include "strahl/util/error.h"

namespace strahl {
namespace {

constexpr int kMaxMergeDepth = 64;  // a map merging a map merging a map …

struct Expander {
  const std::string& name;
  int first_line;
  // Nodes by (position in the text, type): a node that aliases reach many times is one node.
  std::set<std::pair<std::size_t, int>> expanded, traversed;
  std::size_t added = 0;

  static std::pair<std::size_t, int> id(const YAML::Node& n) { return {n.Mark().pos, int(n.Type())}; }

  [[noreturn]] void fail(const YAML::Node& n, const std::string& message) const {
    throw Error(FileLoc{name, first_line + n.Mark().line + 1, n.Mark().column + 1}, message);
  }

  static bool has(const YAML::Node& m, const std::string& key) {
    const YAML::Node& map = m;
    return map[key].IsDefined();
  }

  // The merges of map m, after those of the maps it merges.
  void expand(YAML::Node m, int depth) {
    if (!expanded.insert(id(m)).second) return;
    int merge_keys = 0;
    for (const auto& kv : m) merge_keys += kv.first.IsScalar() && kv.first.Scalar() == "<<";
    if (merge_keys == 0) return;
    if (merge_keys > 1) fail(m, "repeated merge key '<<' (merge several maps with a list: <<: [*a, *b])");
    if (depth >= kMaxMergeDepth) fail(m, "merge keys nested more than 64 deep");
    const YAML::Node& map = m;
    const YAML::Node value = map["<<"];
    std::vector<YAML::Node> sources;
    if (value.IsMap()) {
      sources.push_back(value);
    } else if (value.IsSequence()) {
      for (const YAML::Node& s : value) {
        if (!s.IsMap()) fail(s, "a merge key's list must hold maps only (<<: [*a, *b])");
        sources.push_back(s);
      }
    } else {
      fail(value, "a merge key '<<' must name a map (<<: *name) or a list of maps (<<: [*a, *b])");
    }
    for (const YAML::Node& s : sources) expand(s, depth + 1);
    m.remove("<<");
    for (const YAML::Node& s : sources)
      for (const auto& kv : s) {
        if (!kv.first.IsScalar()) continue;
        const std::string& key = kv.first.Scalar();
        if (has(m, key)) continue;  // set by the map itself, or by an earlier map of the list
        m[kv.first] = kv.second;  // the key node itself: errors about the key name its place
        if (++added > kMaxSceneNodes) fail(m, "merge keys add more than 4194304 keys in all");
      }
    if (m.size() > kMaxShortMap) fail(m, "a map with a merge key may hold at most 64 keys once merged");
  }
};

}  // namespace

void expand_merge_keys(YAML::Node root, const std::string& name, int first_line) {
  Expander e{name, first_line, {}, {}};
  std::vector<YAML::Node> stack{root};
  while (!stack.empty()) {
    YAML::Node n = stack.back();
    stack.pop_back();
    if (!(n.IsMap() || n.IsSequence()) || !e.traversed.insert(Expander::id(n)).second) continue;
    if (n.IsMap()) {
      e.expand(n, 0);
      for (const auto& kv : n) stack.push_back(kv.second);
    } else {
      for (const YAML::Node& child : n) stack.push_back(child);
    }
  }
}

bool may_hold_merge_keys(const std::string& text) { return text.find("<<") != std::string::npos; }

}  // namespace strahl
