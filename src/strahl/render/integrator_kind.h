#pragma once
// Which integrator computes a camera sample's radiance (the scene's render.integrator,
// docs/scene-format.md "Path tracing"): Whitted's recursive ray tracing with the lecture's ambient
// term (render/whitted.h), or path tracing (render/path_tracer.h), which computes the
// interreflected light the ambient term stands in for.

#include <cstdint>
#include <optional>
#include <string_view>

namespace strahl {

enum class IntegratorKind : std::uint8_t { Whitted, Path };

inline std::optional<IntegratorKind> integrator_from_name(std::string_view name) {
  if (name == "whitted") return IntegratorKind::Whitted;
  if (name == "path") return IntegratorKind::Path;
  return std::nullopt;
}
inline const char* integrator_name(IntegratorKind kind) { return kind == IntegratorKind::Path ? "path" : "whitted"; }
inline constexpr const char* kIntegratorNames = "whitted, path";

}  // namespace strahl
