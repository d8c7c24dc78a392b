#include "strahl/render/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "strahl/render/tile_codec.h"
#include "strahl/util/error.h"
#include "strahl/version.h"

namespace strahl {

namespace {

constexpr char kFileMagic[8] = {'S', 'T', 'R', 'A', 'H', 'L', 'J', '1'};
constexpr std::uint32_t kRecordMagic = 0x43455254u;  // TREC
constexpr std::size_t kHeader = sizeof kFileMagic + sizeof(std::uint64_t);
constexpr std::size_t kRecordHeader = 4 + 4 + 8;
constexpr std::uint32_t kMaxRecord = 1u << 30;

std::uint64_t fnv1a(const std::uint8_t* p, std::size_t n, std::uint64_t h = 0xcbf29ce484222325ull) {
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

[[noreturn]] void fail(const std::filesystem::path& path, const char* what) {
  throw Error("resume journal " + path.string() + ": cannot " + what + ": " + std::strerror(errno));
}

void write_all(int fd, const std::filesystem::path& path, const std::uint8_t* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      fail(path, "write");
    }
    p += w;
    n -= std::size_t(w);
  }
}

}  // namespace

std::uint64_t journal_key(std::uint64_t scene_hash, int tile_size, bool progressive, std::uint32_t max_pass_samples) {
  std::uint64_t h = fnv1a(reinterpret_cast<const std::uint8_t*>(&scene_hash), sizeof scene_hash);
  const std::string v = version();
  h = fnv1a(reinterpret_cast<const std::uint8_t*>(v.data()), v.size(), h);
  const std::int64_t settings[3] = {tile_size, progressive ? 1 : 0, std::int64_t(max_pass_samples)};
  return fnv1a(reinterpret_cast<const std::uint8_t*>(settings), sizeof settings, h);
}

TileJournal TileJournal::create(const std::filesystem::path& path, std::uint64_t key) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, "create");
  TileJournal j(path, fd);
  std::uint8_t header[kHeader];
  std::memcpy(header, kFileMagic, sizeof kFileMagic);
  std::memcpy(header + sizeof kFileMagic, &key, sizeof key);
  write_all(fd, path, header, sizeof header);
  return j;
}

namespace {

// Reads exactly n bytes at `offset`; false at the end of the file.
bool read_at(int fd, const std::filesystem::path& path, std::uint8_t* p, std::size_t n, off_t offset) {
  while (n > 0) {
    const ssize_t r = ::pread(fd, p, n, offset);
    if (r < 0) {
      if (errno == EINTR) continue;
      fail(path, "read");
    }
    if (r == 0) return false;
    p += r;
    n -= std::size_t(r);
    offset += r;
  }
  return true;
}

}  // namespace

TileJournal TileJournal::resume(const std::filesystem::path& path, std::uint64_t key) {
  const int fd = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
  if (fd < 0) fail(path, "open");
  TileJournal j(path, fd);
  std::uint8_t header[kHeader];
  if (!read_at(fd, path, header, kHeader, 0) || std::memcmp(header, kFileMagic, sizeof kFileMagic) != 0)
    throw Error("resume journal " + path.string() + " is not a strahl journal");
  std::uint64_t stored = 0;
  std::memcpy(&stored, header + sizeof kFileMagic, sizeof stored);
  if (stored != key)
    throw Error("resume journal " + path.string() +
                " belongs to a different scene or different settings (scene, tile size, sampling, progressive "
                "options or strahl version differ); remove it or render without --resume");
  // Each whole record is checked and indexed; its tile is read again when it is replayed.
  off_t at = off_t(kHeader);
  std::vector<std::uint8_t> payload;
  for (;;) {
    std::uint8_t rh[kRecordHeader];
    if (!read_at(fd, path, rh, kRecordHeader, at)) break;
    std::uint32_t magic, length;
    std::uint64_t checksum;
    std::memcpy(&magic, rh, 4);
    std::memcpy(&length, rh + 4, 4);
    std::memcpy(&checksum, rh + 8, 8);
    if (magic != kRecordMagic || length > kMaxRecord) break;
    payload.resize(length);
    if (!read_at(fd, path, payload.data(), length, at + off_t(kRecordHeader))) break;
    if (fnv1a(payload.data(), length) != checksum) break;
    TileWork t;
    try {
      decode_tile(payload, TilePart::Result, t);
    } catch (const Error&) {
      break;
    }
    j.records_.insert_or_assign({t.pass, t.index}, Record{at + off_t(kRecordHeader), length});
    at += off_t(kRecordHeader + length);
  }
  // Whatever follows the last whole record (a write cut short) goes, so new records follow it.
  if (::ftruncate(fd, at) != 0) fail(path, "truncate");
  j.replayable_ = j.records_.size();
  return j;
}

TileJournal::TileJournal(TileJournal&& other) noexcept
    : path_(std::move(other.path_)),
      fd_(std::exchange(other.fd_, -1)),
      records_(std::move(other.records_)),
      replayable_(other.replayable_) {}

TileJournal::~TileJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void TileJournal::record(const TileWork& tile) {
  if (tile.taken != tile.count && !tile.count.empty()) return;  // stopped early: render it again
  std::lock_guard lock(mutex_);
  if (fd_ < 0 || records_.count({tile.pass, tile.index})) return;
  const std::vector<std::uint8_t> payload = encode_tile(tile, TilePart::Result);
  std::vector<std::uint8_t> rec(kRecordHeader + payload.size());
  const std::uint32_t length = std::uint32_t(payload.size());
  const std::uint64_t checksum = fnv1a(payload.data(), payload.size());
  std::memcpy(rec.data(), &kRecordMagic, 4);
  std::memcpy(rec.data() + 4, &length, 4);
  std::memcpy(rec.data() + 8, &checksum, 8);
  std::memcpy(rec.data() + kRecordHeader, payload.data(), payload.size());
  write_all(fd_, path_, rec.data(), rec.size());
  records_.emplace(std::pair{tile.pass, tile.index}, Record{-1, length});  // recorded; never replayed in this run
}

std::optional<TileWork> TileJournal::find(int pass, int index) const {
  Record r;
  {
    std::lock_guard lock(mutex_);
    const auto it = records_.find({pass, index});
    if (it == records_.end() || it->second.offset < 0 || fd_ < 0) return std::nullopt;
    r = it->second;
  }
  std::vector<std::uint8_t> payload(r.length);
  if (!read_at(fd_, path_, payload.data(), r.length, r.offset)) return std::nullopt;
  TileWork t;
  decode_tile(payload, TilePart::Result, t);
  return t;
}

std::size_t TileJournal::size() const {
  std::lock_guard lock(mutex_);
  return records_.size();
}

void TileJournal::remove() {
  std::lock_guard lock(mutex_);
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

}  // namespace strahl
