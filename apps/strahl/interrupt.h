#pragma once
// SIGINT (Ctrl-C) and SIGTERM during a render: the first one sets a flag that the renderer polls
// between tiles (RenderOptions::cancel), so the image rendered so far is still written and the
// CLI exits with 130. The handlers reset themselves: a second signal ends the process at once.

#include <atomic>

namespace strahl::cli {

// Installs the handlers; returns the flag they set. Call once, early in main().
const std::atomic<bool>* install_interrupt_handlers();

// The signal that set the flag (SIGINT or SIGTERM), 0 if none.
int interrupt_signal();

}  // namespace strahl::cli
