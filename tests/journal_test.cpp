// Resuming renders: the tile encoding round-trips every field and refuses malformed bytes; a
// render stopped part-way and resumed from its journal ends with the same film sums as one that
// ran through (a journal cut off mid-record included); a journal of another scene or other
// settings is refused; the scene hash tells compiled scenes apart.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <random>

#include "strahl/render/cpu_backend.h"
#include "strahl/render/journal.h"
#include "strahl/render/render_job.h"
#include "strahl/render/scene_hash.h"
#include "strahl/render/tile_codec.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"

namespace strahl::journal_test {
namespace {

TileWork random_tile(std::mt19937& rng, bool wide) {
  TileWork t;
  t.pass = 3;
  t.index = 17;
  t.rect = {8, 16, 13, 19};
  const std::size_t n = t.rect.pixels();
  std::uniform_int_distribution<std::uint32_t> u(0, 1000);
  std::uniform_real_distribution<double> d(-5, 5);
  for (std::size_t i = 0; i < n; ++i) {
    t.first.push_back(u(rng));
    t.count.push_back(u(rng));
    t.taken.push_back(u(rng));
    t.stats.push_back({d(rng), d(rng), u(rng)});
  }
  if (wide) {
    t.bx0 = 6;
    t.brow0 = 14;
    t.bw = 9;
    t.bh = 7;
    for (int i = 0; i < t.bw * t.bh * 4; ++i) t.fixed.push_back(std::int64_t(u(rng)) << 30);
  } else {
    for (std::size_t i = 0; i < n * 4; ++i) t.local.push_back(d(rng));
  }
  t.counters = {1, 2, 3, 4, 5};
  return t;
}

TEST(TileCodec, RequestsAndResultsRoundTrip) {
  std::mt19937 rng(3);
  for (bool wide : {false, true}) {
    const TileWork t = random_tile(rng, wide);
    TileWork req;
    decode_tile(encode_tile(t, TilePart::Request), TilePart::Request, req);
    EXPECT_EQ(req.pass, 3);
    EXPECT_EQ(req.index, 17);
    EXPECT_EQ(req.rect.x1, 13);
    EXPECT_EQ(req.first, t.first);
    EXPECT_EQ(req.count, t.count);
    EXPECT_EQ(req.local, t.local);
    ASSERT_EQ(req.stats.size(), t.stats.size());
    EXPECT_EQ(req.stats.back().sum_sq, t.stats.back().sum_sq);
    TileWork res;
    decode_tile(encode_tile(t, TilePart::Result), TilePart::Result, res);
    EXPECT_EQ(res.taken, t.taken);
    EXPECT_EQ(res.local, t.local);
    EXPECT_EQ(res.fixed, t.fixed);
    EXPECT_EQ(res.bw, wide ? 9 : 0);
    EXPECT_EQ(res.counters.refraction, 4u);
    EXPECT_EQ(res.stats.front().n, t.stats.front().n);
  }
  // A uniform pass sends one range, a first pass no sums: a request of a 32×32 tile is small.
  TileWork uniform;
  uniform.rect = {0, 0, 32, 32};
  uniform.first.assign(1024, 4);
  uniform.count.assign(1024, 4);
  uniform.local.assign(4096, 0.0);
  EXPECT_LT(encode_tile(uniform, TilePart::Request).size(), 64u);
  TileWork back;
  decode_tile(encode_tile(uniform, TilePart::Request), TilePart::Request, back);
  EXPECT_EQ(back.count, uniform.count);
  EXPECT_TRUE(back.local.empty()) << "zero sums are not sent; the worker's layout makes them";
}

TEST(TileCodec, MalformedBytesAreRefused) {
  std::mt19937 rng(4);
  const std::vector<std::uint8_t> good = encode_tile(random_tile(rng, true), TilePart::Result);
  TileWork t;
  for (std::size_t cut : {std::size_t(0), std::size_t(3), good.size() / 2, good.size() - 1})
    EXPECT_THROW(decode_tile({good.data(), cut}, TilePart::Result, t), Error) << cut;
  std::vector<std::uint8_t> longer = good;
  longer.push_back(0);
  EXPECT_THROW(decode_tile(longer, TilePart::Result, t), Error);
  EXPECT_THROW(decode_tile(good, TilePart::Request, t), Error) << "a result is not a request";
  std::vector<std::uint8_t> bad_rect = good;
  bad_rect[4 + 4 + 4 + 8] = 0xff;  // x1 → negative
  bad_rect[4 + 4 + 4 + 11] = 0xff;
  EXPECT_THROW(decode_tile(bad_rect, TilePart::Result, t), Error);
}

RenderScene scene(SamplerKind kind, int spp, FilterKind filter = FilterKind::Box, Real radius = 0.5) {
  Scene s = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  s.settings.width = 33;
  s.settings.height = 20;
  s.settings.sampling.sampler = kind;
  s.settings.sampling.spp = spp;
  s.settings.sampling.filter = {filter, radius};
  s.settings.sampling.adaptive_min = 2;
  return compile(s);
}

std::vector<std::array<double, 4>> sums(const RenderJob& job, const RenderScene& rs) {
  std::vector<std::array<double, 4>> out;
  for (int row = 0; row < rs.camera.ny; ++row)
    for (int x = 0; x < rs.camera.nx; ++x) out.push_back(job.film().sums(x, row));
  return out;
}

JobOptions progressive_tiles() {
  JobOptions o;
  o.tile_size = 8;
  o.progressive = true;
  return o;
}

TEST(Journal, AStoppedRenderResumesToTheSameFilm) {
  const test::TempDir dir;
  for (const RenderScene& rs : {scene(SamplerKind::Adaptive, 16), scene(SamplerKind::Sobol, 8, FilterKind::Gaussian, 1.5)}) {
    const std::uint64_t key = journal_key(scene_hash(rs), 8, true, 0);
    RenderJob reference(rs.view(), rs.sampling, progressive_tiles());
    CpuBackend cpu(2);
    reference.run(cpu);

    for (bool cut_last_record : {false, true}) {
      const fs::path path = dir / "out.journal";
      {
        TileJournal journal = TileJournal::create(path, key);
        JobOptions o = progressive_tiles();
        RenderJob* self = nullptr;
        std::atomic<int> delivered{0};
        o.on_tile = [&](const TileWork& t) {
          journal.record(t);
          if (++delivered == 20) self->cancel();  // somewhere in the second or third pass
        };
        RenderJob first(rs.view(), rs.sampling, o);
        self = &first;
        first.run(cpu);
        ASSERT_TRUE(first.stats().cancelled);
      }
      if (cut_last_record) fs::resize_file(path, fs::file_size(path) - 5);
      TileJournal journal = TileJournal::resume(path, key);
      EXPECT_GT(journal.replayable(), 5u);
      JobOptions o = progressive_tiles();
      o.on_tile = [&](const TileWork& t) { journal.record(t); };
      o.replay = [&](int pass, int index) { return journal.find(pass, index); };
      RenderJob resumed(rs.view(), rs.sampling, o);
      resumed.run(cpu);
      EXPECT_FALSE(resumed.stats().cancelled);
      EXPECT_GT(resumed.stats().replayed_tiles, 5u);
      EXPECT_EQ(resumed.stats().samples, reference.stats().samples);
      EXPECT_TRUE(std::ranges::equal(resumed.pixel_samples(), reference.pixel_samples()));
      EXPECT_TRUE(sums(resumed, rs) == sums(reference, rs)) << sampler_name(rs.sampling.sampler);
      journal.remove();
      EXPECT_FALSE(fs::exists(path));
    }
  }
}

TEST(Journal, AJournalOfAnotherSceneOrOtherSettingsIsRefused) {
  const test::TempDir dir;
  const fs::path path = dir / "out.journal";
  const RenderScene a = scene(SamplerKind::Sobol, 8);
  const std::uint64_t key = journal_key(scene_hash(a), 8, true, 0);
  { TileJournal::create(path, key); }
  EXPECT_NO_THROW(TileJournal::resume(path, key));
  EXPECT_THROW(TileJournal::resume(path, journal_key(scene_hash(scene(SamplerKind::Sobol, 16)), 8, true, 0)), Error);
  EXPECT_THROW(TileJournal::resume(path, journal_key(scene_hash(a), 16, true, 0)), Error);
  EXPECT_THROW(TileJournal::resume(path, journal_key(scene_hash(a), 8, false, 0)), Error);
  test::write_text(path, "not a journal");
  EXPECT_THROW(TileJournal::resume(path, key), Error);
  EXPECT_THROW(TileJournal::resume(path.parent_path() / "missing.journal", key), Error);
}

TEST(SceneHash, SameSceneSameHashAnyChangeAnother) {
  const std::uint64_t h = scene_hash(scene(SamplerKind::Sobol, 8));
  EXPECT_EQ(scene_hash(scene(SamplerKind::Sobol, 8)), h);
  EXPECT_NE(scene_hash(scene(SamplerKind::Sobol, 16)), h);
  EXPECT_NE(scene_hash(scene(SamplerKind::Random, 8)), h);
  Scene s = load_scene(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "lecture-whitted.yaml");
  s.settings.width = 33;
  s.settings.height = 20;
  s.settings.sampling.sampler = SamplerKind::Sobol;
  s.settings.sampling.spp = 8;
  s.settings.sampling.adaptive_min = 2;
  EXPECT_EQ(scene_hash(compile(s)), h);
  RenderScene moved = compile(s);
  moved.spheres.at(0).radius *= 1.0000001;
  EXPECT_NE(scene_hash(moved), h);
  RenderScene recoloured = compile(s);
  recoloured.materials.back().color.y += 1e-9;
  EXPECT_NE(scene_hash(recoloured), h);
  RenderScene lit = compile(s);
  lit.lights.at(0).position.x += 1e-9;
  EXPECT_NE(scene_hash(lit), h);
  RenderScene deeper = compile(s);
  deeper.settings.max_depth += 1;
  EXPECT_NE(scene_hash(deeper), h);
}

}  // namespace
}  // namespace strahl::journal_test
