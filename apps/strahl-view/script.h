#pragma once
// --script FILE: a session of timed input events, played into the window as if a person made
// them (the tests' way to drive the viewer; docs/viewer.md, "Scripts"). One event per line:
//
//   <delay> <event> [arguments]      delay: seconds after the previous line's event
//
//   mouse down|up left|middle|right X Y   a button pressed or released at window pixel (X, Y)
//   mouse move X Y                        the pointer moves to (X, Y) (dragging with the buttons held)
//   wheel N                               N wheel steps (positive: away from the user, closer)
//   key [ctrl+][shift+]NAME               a key pressed and released (SDL key names: a, r, f1, escape, [, =)
//   keydown NAME / keyup NAME             a key held / let go (flying)
//   wait spp N                            until the still image has N samples per pixel (or is complete)
//   wait still                            until the still image is complete
//   wait reload N                         until the scene file has been reloaded N times (or failed to)
//   quit                                  closes the window
//
// `#` starts a comment. Errors name the file, line and column.

#include <filesystem>
#include <string>
#include <vector>

namespace strahl::view {

struct ScriptEvent {
  enum class Kind { MouseDown, MouseUp, MouseMove, Wheel, Key, KeyDown, KeyUp, WaitSpp, WaitStill, WaitReload, Quit };
  double delay = 0;
  Kind kind = Kind::Quit;
  int button = 1;  // 1 left, 2 middle, 3 right (SDL's numbers)
  int x = 0, y = 0;
  int amount = 0;  // wheel steps, spp, reloads
  std::string key;
  bool ctrl = false, shift = false;
  int line = 0;
};

// Throws strahl::Error (file:line:column) for a file it cannot read or a line it does not understand.
std::vector<ScriptEvent> load_script(const std::filesystem::path& path);
std::vector<ScriptEvent> parse_script(const std::string& text, const std::string& name);

}  // namespace strahl::view
