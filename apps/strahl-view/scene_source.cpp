#include "scene_source.h"

#include <sys/stat.h>
#include <yaml-cpp/yaml.h>

#include <chrono>

#include "setup.h"
#include "strahl/util/error.h"

namespace strahl::view {

namespace fs = std::filesystem;

std::vector<fs::path> scene_files(const fs::path& scene) {
  std::vector<fs::path> files;
  if (scene.empty()) return files;
  files.push_back(scene);
  try {
    const YAML::Node root = YAML::LoadFile(scene.string());
    const YAML::Node objects = root["objects"];
    if (!objects || !objects.IsSequence()) return files;
    for (const YAML::Node& o : objects) {
      if (!o.IsMap() || !o["file"] || !o["file"].IsScalar()) continue;
      files.push_back(scene.parent_path() / o["file"].as<std::string>());
    }
  } catch (const std::exception&) {
    // A file that does not parse now: the scene file alone is watched until it does.
  }
  return files;
}

LoadedScene load_scene_now(const cli::Options& options, std::optional<AccelKind> accel) {
  const auto start = std::chrono::steady_clock::now();
  cli::Options o = options;
  if (accel) o.accel = std::string(accel_name(*accel));
  const Scene scene = cli::configured_scene(o);
  LoadedScene out;
  out.render = std::make_shared<const RenderScene>(compile(scene));
  out.camera = scene.camera;
  out.accel = scene.settings.accel;
  out.files = scene_files(o.scene);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

SceneLoader::SceneLoader(cli::Options options) : options_(std::move(options)), thread_([this] { loop(); }) {}

SceneLoader::~SceneLoader() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void SceneLoader::request(std::optional<AccelKind> accel) {
  {
    std::lock_guard lock(mutex_);
    requested_ = true;
    accel_ = accel;
  }
  wake_.notify_all();
}

std::optional<SceneLoader::Result> SceneLoader::take() {
  std::lock_guard lock(mutex_);
  std::optional<Result> r = std::move(result_);
  result_.reset();
  return r;
}

bool SceneLoader::busy() const {
  std::lock_guard lock(mutex_);
  return requested_ || loading_;
}

void SceneLoader::loop() {
  for (;;) {
    std::optional<AccelKind> accel;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return quit_ || requested_; });
      if (quit_) return;
      requested_ = false;
      loading_ = true;
      accel = accel_;
    }
    Result r;
    try {
      r.scene = load_scene_now(options_, accel);
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    std::lock_guard lock(mutex_);
    loading_ = false;
    if (!requested_) result_ = std::move(r);  // a newer request supersedes this result
  }
}

FileWatch::State FileWatch::state_of(const fs::path& p) {
  struct stat st {};
  State s;
  if (::stat(p.c_str(), &st) != 0) return s;
  s.exists = true;
  s.mtime_ns = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  s.size = std::uint64_t(st.st_size);
  s.inode = std::uint64_t(st.st_ino);
  return s;
}

void FileWatch::watch(const std::vector<fs::path>& files) {
  files_ = files;
  states_.clear();
  for (const fs::path& f : files_) states_.push_back(state_of(f));
}

bool FileWatch::changed() {
  bool any = false;
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const State now = state_of(files_[i]);
    if (!(now == states_[i])) {
      states_[i] = now;
      any = true;
    }
  }
  return any;
}

}  // namespace strahl::view
