#pragma once
// The resume journal: every completed tile of a render appended to a file beside the output as
// it is delivered, so that after a crash or a kill of the whole run, `--resume` renders only the
// missing tiles and writes the same bytes as an uninterrupted run (RenderJob replays the journal's
// tiles pass by pass: JobOptions::on_tile / replay).
//
// File: a header (magic, the render's key: scene hash, version and every setting that decides
// what a tile holds) and records, each [magic, length, FNV-1a checksum, tile result
// (render/tile_codec.h)], appended with one write(2) each. A record cut short by a crash fails
// its checksum and it and everything after it are dropped when the journal is opened again.
// Tiles stopped early (cancel, time limit) are not recorded: a resumed run renders them whole.

#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <sys/types.h>
#include <utility>

#include "strahl/render/tile.h"

namespace strahl {

class TileJournal {
 public:
  // A new, empty journal at `path` (an existing one is replaced).
  static TileJournal create(const std::filesystem::path& path, std::uint64_t key);
  // The journal at `path` with the tiles it holds, to resume; throws strahl::Error when there is
  // none, or when it belongs to another scene or other settings (a different key).
  static TileJournal resume(const std::filesystem::path& path, std::uint64_t key);

  TileJournal(TileJournal&& other) noexcept;
  TileJournal& operator=(TileJournal&&) = delete;
  ~TileJournal();

  // Records a delivered tile if it is complete and not recorded yet. Thread-safe. Throws
  // strahl::Error (with errno's reason) when the file cannot be written.
  void record(const TileWork& tile);
  // The recorded tile of (pass, index), if any.
  std::optional<TileWork> find(int pass, int index) const;
  std::size_t size() const;             // tiles recorded, in this run or before
  std::size_t replayable() const { return replayable_; }  // tiles an earlier run recorded
  // The render finished and its image is written: the journal is no longer needed.
  void remove();
  const std::filesystem::path& path() const { return path_; }

 private:
  TileJournal(std::filesystem::path path, int fd) : path_(std::move(path)), fd_(fd) {}

  std::filesystem::path path_;
  int fd_ = -1;
  struct Record {
    off_t offset = -1;  // of the tile's bytes in the file; −1: recorded by this run
    std::uint32_t length = 0;
  };
  mutable std::mutex mutex_;
  std::map<std::pair<int, int>, Record> records_;  // (pass, index) → where its result is
  std::size_t replayable_ = 0;
};

// The journal's key: the scene's hash and what decides a tile's contents besides the scene.
std::uint64_t journal_key(std::uint64_t scene_hash, int tile_size, bool progressive, std::uint32_t max_pass_samples);

}  // namespace strahl
