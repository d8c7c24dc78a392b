#pragma once
// Scene files: YAML (.yaml, .yml) and JSON (.json, read by the same YAML reader).
// Every key is documented in docs/scene-format.md.

#include <filesystem>
#include <string>

#include "strahl/scene/scene.h"

namespace strahl {

// Throws strahl::Error with file:line:column for syntax errors, unknown keys, wrong types,
// missing fields and impossible values.
Scene load_scene(const std::filesystem::path& path);

// The same from text; `name` is used in error messages, `base_dir` resolves mesh paths.
Scene parse_scene(const std::string& text, const std::string& name, const std::filesystem::path& base_dir);

// Named indices of refraction (vacuum, air, water, ice, acrylic, glass, diamond); false if unknown.
bool named_ior(const std::string& name, Real& ior);

}  // namespace strahl
