#include "strahl/scene/yaml_limits.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <vector>

#include "strahl/util/cancel.h"
#include "strahl/util/error.h"

namespace strahl {

namespace {

class LimitChecker : public YAML::EventHandler {
 public:
  explicit LimitChecker(const std::string& name) : name_(name) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { node(mark, nullptr, anchor); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, nullptr, 1); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string& value) override {
    node(mark, &value, anchor);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value style) override {
    open(mark, false, anchor, style);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value style) override {
    open(mark, true, anchor, style);
  }
  void OnMapEnd() override { close(); }

  YamlOutline outline() const {
    YamlOutline o = outline_;
    o.objects_by_element = objects_ == Objects::after && !anchors_ && !o.elements.empty();
    return o;
  }

 private:
  struct Container {
    bool map;
    bool long_allowed;
    bool csg_objects = false;  // a CSG node's `objects`: up to kMaxCsgList
    std::size_t entries = 0;  // for a map: keys and values
    std::string key;          // the last key of a map (scalars only)
  };

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& message) const {
    throw Error(FileLoc{name_, mark.line + 1, mark.column + 1}, message);
  }

  // A node inside the current container (or the root): counts it and checks its container's size.
  void node(const YAML::Mark& mark, const std::string* scalar, YAML::anchor_t anchor) {
    if (anchor != YAML::NullAnchor) anchors_ = true;
    if (objects_ == Objects::inside && stack_.size() == objects_depth_) outline_.elements.push_back({mark.line, mark.column});
    if (objects_ == Objects::after && stack_.size() == 1 && outline_.objects_end_line < 0)
      outline_.objects_end_line = mark.line;
    if (++nodes_ > kMaxSceneNodes)
      fail(mark, "the scene file holds more than " + std::to_string(kMaxSceneNodes) +
                     " YAML values, lists and maps; put large geometry in a mesh file (OBJ or PLY)");
    if ((nodes_ & 0xfff) == 0) check_cancelled("yaml");
    if (stack_.empty()) return;
    Container& c = stack_.back();
    ++c.entries;
    if (c.map) {
      if (c.entries % 2 == 1) c.key = scalar ? *scalar : std::string();
      if (!c.long_allowed && c.entries > 2 * kMaxShortMap)
        fail(mark, "a map of more than " + std::to_string(kMaxShortMap) +
                       " keys; no map in a scene file holds that many (only the top-level 'materials' and 'groups')");
    } else if (c.csg_objects && c.entries > kMaxCsgList) {
      fail(mark, "a CSG node's objects list of more than " + std::to_string(kMaxCsgList) +
                     " elements (a CSG tree holds at most 256 solids)");
    } else if (!c.long_allowed && !c.csg_objects && c.entries > kMaxShortList) {
      fail(mark, "a list of more than " + std::to_string(kMaxShortList) +
                     " elements; no list in a scene file holds that many (only the top-level 'objects' and "
                     "'lights', a group's objects and a CSG's 'objects'; put large geometry in a mesh file)");
    }
  }

  void open(const YAML::Mark& mark, bool map, YAML::anchor_t anchor, YAML::EmitterStyle::value style) {
    node(mark, nullptr, anchor);
    // The top-level map's 'objects', 'lights' (lists) and 'materials' (a map) may be long.
    bool long_allowed = false;
    if (stack_.size() == 1 && stack_[0].map && stack_[0].entries % 2 == 0) {
      const std::string& key = stack_[0].key;
      long_allowed = map ? (key == "materials" || key == "groups") : (key == "objects" || key == "lights");
      if (!map && key == "objects") {
        // Only one block-style list can be read element by element (a repeated key is an error later).
        objects_ = objects_ == Objects::none && style == YAML::EmitterStyle::Block ? Objects::inside : Objects::unusable;
        objects_depth_ = stack_.size() + 1;
      }
    }
    // So may the lists of objects of the top-level 'groups' (scene/instances.h).
    if (!map && stack_.size() == 2 && stack_[0].map && stack_[0].key == "groups" && stack_[1].map &&
        stack_[1].entries % 2 == 0)
      long_allowed = true;
    // So may a CSG node's 'objects', up to kMaxCsgList (scene/csg.h).
    const bool csg_objects = !map && stack_.size() > 1 && stack_.back().map && stack_.back().entries % 2 == 0 &&
                             stack_.back().key == "objects";
    stack_.push_back({map, long_allowed, csg_objects, 0, {}});
  }

  void close() {
    if (objects_ == Objects::inside && stack_.size() == objects_depth_) objects_ = Objects::after;
    stack_.pop_back();
  }

  const std::string& name_;
  std::size_t nodes_ = 0;
  std::vector<Container> stack_;
  enum class Objects { none, inside, after, unusable } objects_ = Objects::none;
  std::size_t objects_depth_ = 0;
  bool anchors_ = false;
  YamlOutline outline_;
};

}  // namespace

YamlOutline check_yaml_limits(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  LimitChecker checker(name);
  try {
    YAML::Parser parser(in);
    parser.HandleNextDocument(checker);
  } catch (const YAML::Exception& e) {
    throw Error(FileLoc{name, e.mark.line + 1, e.mark.column + 1}, "syntax error: " + e.msg);
  }
  return checker.outline();
}

}  // namespace strahl
