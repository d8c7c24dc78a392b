#pragma once
// Every key and mouse control of the window, in one table: the help overlay (H) lists it, and
// docs/viewer.md describes the same.

#include <string_view>

namespace strahl::view {

struct KeyHelp {
  std::string_view keys, action;
};

inline constexpr KeyHelp kKeyHelp[] = {
    {"left drag", "orbit about look_at"},
    {"right / middle drag", "pan (eye and look_at together)"},
    {"wheel", "dolly towards / away from look_at"},
    {"W A S D", "fly forward, left, back, right"},
    {"Q E", "fly down, up (Shift: 5x faster)"},
    {"R", "reset the camera to the scene's"},
    {"+ -", "field of view narrower / wider"},
    {"F", "look at (and focus on) the point under the cursor"},
    {"[ ]", "max depth - / +"},
    {"G", "integrator: Whitted / path tracing"},
    {"M", "next pixel sampler"},
    {", .", "spp target halve / double"},
    {"U", "spp target: as set / unlimited"},
    {"B", "next acceleration structure (rebuilds)"},
    {"V", "display: image, depth, normal, albedo, id"},
    {"9 0", "exposure -/+ half a stop (display only)"},
    {"P", "print the camera as YAML on stdout"},
    {"X", "explain the pixel under the cursor on stdout"},
    {"Ctrl+S", "save the image (numbered, never overwrites)"},
    {"L", "reload the scene now"},
    {"Tab", "HUD on / off"},
    {"H F1", "this help"},
    {"Esc", "quit"},
};

}  // namespace strahl::view
