#pragma once
// Cancelling the work before rendering (reading a scene or mesh file, compiling, building the
// acceleration structure): one process-wide flag, set by whoever owns the process (the CLI's
// signal handler), that the loaders and compile() poll every few thousand lines or elements.
// The render itself stops through its own StopToken (render/stop_token.h).

#include <atomic>
#include <exception>

namespace strahl {

// Thrown by check_cancelled() once the flag is set. Not a strahl::Error: an interrupted load is
// not a bad scene (the CLI exits with 130, not 2).
class Cancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "cancelled"; }
};

// The flag the loaders poll; nullptr (the default) for none. It must outlive the loading.
void set_cancel_flag(const std::atomic<bool>* flag);

// A function called at every poll with the stage ("yaml", "obj", "ply", "gltf": reading those files;
// "build": compile() and the acceleration structure), before the flag is tested:
// tests use it to hold a stage open until a signal arrives. nullptr (the default) for none.
using CancelHook = void (*)(const char* stage);
void set_cancel_hook(CancelHook hook);

// Throws Cancelled when the flag is set.
void check_cancelled(const char* stage);

}  // namespace strahl
