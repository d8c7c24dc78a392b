#pragma once
// Where the viewer's scene comes from: the command line's scene (cli::configured_scene, so every
// `strahl` flag applies), loaded and compiled on a thread of its own so the window stays
// responsive, and the files it is made of, watched for changes (live reload).

#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "options.h"
#include "strahl/render/render_scene.h"
#include "strahl/scene/scene.h"

namespace strahl::view {

struct LoadedScene {
  std::shared_ptr<const RenderScene> render;
  CameraDescription camera;  // as the file (and command line) give it
  AccelKind accel = AccelKind::Bvh;
  std::vector<std::filesystem::path> files;  // the scene file and the mesh files it names
  double seconds = 0;                        // loading and compiling
};

// The scene file and every mesh file it names (relative to the scene's folder), as far as the
// file can be read now; empty for the built-in scene. Never throws.
std::vector<std::filesystem::path> scene_files(const std::filesystem::path& scene);

// Loads and compiles now (throws strahl::Error); `accel` overrides the scene's and -- accel.
LoadedScene load_scene_now(const cli::Options& options, std::optional<AccelKind> accel = std::nullopt);

// Loads and compiles on its own thread, one load at a time; a request made meanwhile is done next.
class SceneLoader {
 public:
  struct Result {
    std::optional<LoadedScene> scene;  // or:
    std::string error;                 // the message (file:line:column: …)
  };

  explicit SceneLoader(cli::Options options);
  ~SceneLoader();
  SceneLoader(const SceneLoader&) = delete;
  SceneLoader& operator=(const SceneLoader&) = delete;

  void request(std::optional<AccelKind> accel);
  std::optional<Result> take();  // a finished load, once
  bool busy() const;

 private:
  void loop();

  cli::Options options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool requested_ = false, loading_ = false, quit_ = false;
  std::optional<AccelKind> accel_;
  std::optional<Result> result_;
  std::thread thread_;  // last
};

// Changes to a set of files: modification time, size, inode, and whether they exist.
class FileWatch {
 public:
  void watch(const std::vector<std::filesystem::path>& files);  // takes their state now
  bool changed();  // true once for every change since watch() or the last true
  const std::vector<std::filesystem::path>& files() const { return files_; }

 private:
  struct State {
    bool exists = false;
    std::int64_t mtime_ns = 0;
    std::uint64_t size = 0, inode = 0;
    bool operator==(const State&) const = default;
  };
  static State state_of(const std::filesystem::path& p);
  std::vector<std::filesystem::path> files_;
  std::vector<State> states_;
};

}  // namespace strahl::view
