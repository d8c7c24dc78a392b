#pragma once
// How many reflected and refracted rays one camera sample may spawn (TraceSettings::ray_budget,
// the scene's render.ray_budget; docs/scene-format.md, "Recursion").

#include <cstdint>

namespace strahl {

inline constexpr std::uint32_t kDefaultRayBudget = 4096;  // a full binary ray tree 12 deep has 4094
inline constexpr std::uint32_t kMaxRayBudget = 65536;    // keeps one sample, and so a cancel, short

}  // namespace strahl
