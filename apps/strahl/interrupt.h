#pragma once
// SIGINT (Ctrl-C), SIGTERM and SIGHUP: the first one sets a flag that the loaders poll
// (util/cancel.h) and the renderer checks before every camera sample (RenderOptions::cancel), so
// loading ends with nothing written and a render writes the image so far; the CLI exits with 130
// (docs/cli.md, "Interrupting a run"). A second signal ends the process at once, leaving no
// temporary file behind. SIGPIPE is ignored (console.h), SIGXFSZ too (a failed write reports EFBIG).

#include <atomic>

namespace strahl::cli {

// Installs the handlers and makes the flag the loaders' cancel flag; returns it. Call once, early.
const std::atomic<bool>* install_interrupt_handlers();

// The signal that set the flag (SIGINT, SIGTERM or SIGHUP), 0 if none, and its name.
int interrupt_signal();
const char* interrupt_signal_name();

// A test hook: with STRAHL_TEST_HOLD=STAGE[:SECONDS] in the environment, the run stops at the first
// poll of that stage (yaml, obj, ply, build, render or write), prints "strahl: holding at STAGE"
// to stderr
// and waits until a signal sets the flag or SECONDS (default 10) pass, then goes on. The signal
// tests use it to deliver a signal inside a stage, deterministically.
void hold_for_test(const char* stage);

}  // namespace strahl::cli
