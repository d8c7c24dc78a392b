#pragma once
// YAML merge keys (docs/scene-format.md, "General rules"), which yaml-cpp reads as an ordinary key
// `<<`: in a map, `<<: *base` or `<<: [*first, *second]` adds every key of the named maps that
// the map does not set itself (of a list, the earlier map's value wins), and `<<` goes. The
// merged values are the anchored nodes themselves, so an error in one names the place where it
// is written. Done on the parsed tree before the loader reads it.

#include <yaml-cpp/yaml.h>

#include <string>

namespace strahl {

// Expands every merge key under `root`, each map once however many aliases reach it. Throws
// strahl::Error (at `name`:line:column, lines counted from `first_line` + 1) where `<<` names
// something other than a map or a list of maps, where a merged map would hold more than
// kMaxShortMap keys, or where the merges of one tree would add more than kMaxSceneNodes keys
// (yaml_limits.h: such a tree is as large as the largest scene file).
void expand_merge_keys(YAML::Node root, const std::string& name, int first_line = 0);

// Whether `text` may hold a merge key (a cheap test: "<<" anywhere), so that the pass over the
// tree is skipped for the files without one.
bool may_hold_merge_keys(const std::string& text);

}  // namespace strahl
