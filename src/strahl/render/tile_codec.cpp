#include "strahl/render/tile_codec.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <type_traits>

#include "strahl/util/error.h"

namespace strahl {

namespace {

static_assert(std::endian::native == std::endian::little, "the tile encoding is little-endian");

constexpr std::uint32_t kMagic[2] = {0x51544c54u /* TLTQ */, 0x52544c54u /* TLTR */};
constexpr std::int32_t kMaxSide = 1 << 16;

enum Flags : std::uint8_t { kUniformRanges = 1, kLocal = 2, kStats = 4, kFixed = 8 };

class Writer {
 public:
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void put(const T& v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
  }
  template <class T>
  void put_all(const std::vector<T>& v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(v.data());
    out.insert(out.end(), p, p + v.size() * sizeof(T));
  }
  std::vector<std::uint8_t> out;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : bytes(b) {}
  template <class T>
  T get() {
    T v;
    need(sizeof(T));
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  template <class T>
  void get_all(std::vector<T>& v, std::size_t n) {
    need(n * sizeof(T));
    v.resize(n);
    std::memcpy(v.data(), bytes.data() + at, n * sizeof(T));
    at += n * sizeof(T);
  }
  void need(std::size_t n) const {
    if (bytes.size() - at < n) throw Error("tile data ends early (" + std::to_string(bytes.size()) + " bytes)");
  }
  bool done() const { return at == bytes.size(); }

 private:
  std::span<const std::uint8_t> bytes;
  std::size_t at = 0;
};

template <class T>
bool all_zero(const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(v.data());
  return std::all_of(p, p + v.size() * sizeof(T), [](std::uint8_t b) { return b == 0; });
}

void put_stats(Writer& w, const std::vector<PixelStats>& stats) {
  for (const PixelStats& s : stats) {
    w.put(s.sum);
    w.put(s.sum_sq);
    w.put(s.n);
  }
}

void get_stats(Reader& r, std::vector<PixelStats>& stats, std::size_t n) {
  r.need(n * 20);
  stats.resize(n);
  for (PixelStats& s : stats) {
    s.sum = r.get<double>();
    s.sum_sq = r.get<double>();
    s.n = r.get<std::uint32_t>();
  }
}

}  // namespace

std::vector<std::uint8_t> encode_tile(const TileWork& t, TilePart part) {
  const std::size_t n = t.rect.pixels();
  Writer w;
  w.put(kMagic[int(part)]);
  w.put(std::int32_t(t.pass));
  w.put(std::int32_t(t.index));
  for (int v : {t.rect.x0, t.rect.row0, t.rect.x1, t.rect.row1}) w.put(std::int32_t(v));
  std::uint8_t flags = 0;
  const bool request = part == TilePart::Request;
  const bool uniform = request && n > 0 && std::all_of(t.first.begin(), t.first.end(), [&](auto v) { return v == t.first[0]; }) &&
                       std::all_of(t.count.begin(), t.count.end(), [&](auto v) { return v == t.count[0]; });
  if (uniform) flags |= kUniformRanges;
  if (t.local.size() == n * 4 && n > 0 && !(request && all_zero(t.local))) flags |= kLocal;
  if (t.stats.size() == n && n > 0 && !(request && all_zero(t.stats))) flags |= kStats;
  if (!request && !t.fixed.empty()) flags |= kFixed;
  w.put(flags);
  if (request) {
    if (uniform) {
      w.put(t.first[0]);
      w.put(t.count[0]);
    } else {
      w.put_all(t.first);
      w.put_all(t.count);
    }
  } else {
    w.put_all(t.taken);
  }
  if (flags & kLocal) w.put_all(t.local);
  if (flags & kStats) put_stats(w, t.stats);
  if (flags & kFixed) {
    for (int v : {t.bx0, t.brow0, t.bw, t.bh}) w.put(std::int32_t(v));
    w.put_all(t.fixed);
  }
  if (!request) {
    const RayCounters& c = t.counters;
    for (std::uint64_t v : {c.camera, c.shadow, c.reflection, c.refraction, c.invalid_samples, c.cut}) w.put(v);
  }
  return std::move(w.out);
}

void decode_tile(std::span<const std::uint8_t> bytes, TilePart part, TileWork& t) {
  Reader r(bytes);
  if (r.get<std::uint32_t>() != kMagic[int(part)]) throw Error("not a tile " + std::string(part == TilePart::Request ? "request" : "result"));
  t.pass = r.get<std::int32_t>();
  t.index = r.get<std::int32_t>();
  TileRect rect;
  rect.x0 = r.get<std::int32_t>();
  rect.row0 = r.get<std::int32_t>();
  rect.x1 = r.get<std::int32_t>();
  rect.row1 = r.get<std::int32_t>();
  if (rect.x0 < 0 || rect.row0 < 0 || rect.x1 <= rect.x0 || rect.row1 <= rect.row0 || rect.x1 > kMaxSide ||
      rect.row1 > kMaxSide || t.pass < 0 || t.index < 0)
    throw Error("tile data holds an impossible tile");
  t.rect = rect;
  const std::size_t n = rect.pixels();
  const auto flags = r.get<std::uint8_t>();
  const bool request = part == TilePart::Request;
  if (request) {
    if (flags & kUniformRanges) {
      const auto first = r.get<std::uint32_t>(), count = r.get<std::uint32_t>();
      t.first.assign(n, first);
      t.count.assign(n, count);
    } else {
      r.get_all(t.first, n);
      r.get_all(t.count, n);
    }
  } else {
    r.get_all(t.taken, n);
  }
  if (flags & kLocal) {
    r.get_all(t.local, n * 4);
  } else {
    t.local.clear();
  }
  if (flags & kStats) {
    get_stats(r, t.stats, n);
  } else {
    t.stats.clear();
  }
  if (flags & kFixed) {
    t.bx0 = r.get<std::int32_t>();
    t.brow0 = r.get<std::int32_t>();
    t.bw = r.get<std::int32_t>();
    t.bh = r.get<std::int32_t>();
    if (t.bx0 < 0 || t.brow0 < 0 || t.bw <= 0 || t.bh <= 0 || t.bx0 > rect.x0 || t.brow0 > rect.row0 ||
        t.bx0 + t.bw < rect.x1 || t.brow0 + t.bh < rect.row1 || t.bw > kMaxSide || t.bh > kMaxSide)
      throw Error("tile data holds an impossible filter margin");
    r.get_all(t.fixed, std::size_t(t.bw) * std::size_t(t.bh) * 4);
  } else if (!request) {
    t.fixed.clear();
  }
  if (!request) {
    RayCounters& c = t.counters;
    for (std::uint64_t* v : {&c.camera, &c.shadow, &c.reflection, &c.refraction, &c.invalid_samples, &c.cut})
      *v = r.get<std::uint64_t>();
  }
  if (!r.done()) throw Error("tile data has trailing bytes");
}

}  // namespace strahl
