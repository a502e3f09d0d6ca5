// Sharded runs and sweeps (harness/run/shard.h, merge.h, reference_cache.h): the split worked
// out by hand, the reference cache bit for bit, and sharded-then-merged runs against single
// runs on the user's path (the default method list, a scene without edges, an odd frame
// size, a motion run with a method with memory, a sweep): the merged report.json and
// index.html equal the single run's byte for byte once the single run's timings and context
// are copied in, and every image is byte-identical.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "harness/run/merge.h"
#include "harness/run/pipeline.h"
#include "harness/run/reference_cache.h"
#include "harness/run/runner.h"
#include "harness/run/same_results.h"
#include "harness/run/shard.h"
#include "methods/registry.h"
#include "metrics/metric.h"
#include "harness/run/sweep.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "scenes/library.h"
#include "scenes/scene_hash.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) { return testenv::ScratchDir("shard-" + name); }

std::string ReadBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}

// ---- the split -------------------------------------------------------------------------

TEST(Shard, ParsesKOverNAndRefusesEverythingElse) {
  const ShardSpec s = ParseShard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  EXPECT_TRUE(s.Active());
  EXPECT_EQ(ParseShard("0/1").count, 1);
  EXPECT_FALSE(ShardSpec{}.Active());
  for (const char* bad :
       {"", "3", "/3", "3/", "1/0", "5/5", "6/5", "-1/5", "1/-5", "a/b", "1/2/3", "1 /2", "0/100001"}) {
    const std::string m = MessageOf([&] { ParseShard(bad); });
    EXPECT_NE(m.find("--shard '" + std::string(bad) + "'"), std::string::npos) << m;
    EXPECT_NE(m.find("0 <= K < N"), std::string::npos) << m;
  }
  EXPECT_NE(MessageOf([] { ParseShard("4/4"); }).find("K must be below N"), std::string::npos);
}

TEST(Shard, RoundRobinSharesWorkedOutByHand) {
  // 5 units over 3 shards: 0 3 | 1 4 | 2.
  EXPECT_EQ(ShardShare(5, {0, 3}), (std::vector<size_t>{0, 3}));
  EXPECT_EQ(ShardShare(5, {1, 3}), (std::vector<size_t>{1, 4}));
  EXPECT_EQ(ShardShare(5, {2, 3}), (std::vector<size_t>{2}));
  // More shards than units: the last ones get nothing.
  EXPECT_EQ(ShardShare(2, {3, 4}), (std::vector<size_t>{}));
  // Not sharded: everything.
  EXPECT_EQ(ShardShare(3, ShardSpec{}), (std::vector<size_t>{0, 1, 2}));
  // Every unit exactly once, for many N.
  for (int n = 1; n <= 13; ++n) {
    std::vector<int> seen(11, 0);
    for (int k = 0; k < n; ++k) {
      for (size_t u : ShardShare(11, {k, n})) ++seen[u];
    }
    for (int c : seen) EXPECT_EQ(c, 1) << "N=" << n;
  }
}

// ---- the scene fingerprint -------------------------------------------------------------

TEST(SceneHash, SameContentSameHashAndEveryKindOfEditChangesIt) {
  const Scene a = LoadScene("circle"), b = LoadScene("circle");
  EXPECT_EQ(SceneContentHash(a), SceneContentHash(b));
  Scene moved = a;
  moved.path = "/somewhere/else.json";
  moved.description = "another description";
  EXPECT_EQ(SceneContentHash(moved), SceneContentHash(a)) << "path and description are not content";
  std::vector<Scene> edits(7, a);
  edits[0].camera.position.x = std::nextafter(a.camera.position.x, 1e9f);  // one ulp
  edits[1].materials.at(0).color.y += 0.5f;
  edits[2].shapes.at(0).radius += 0.25f;
  edits[3].background.z += 0.125f;
  edits[4].name = "circle2";
  edits[5].animation.frames = 2;
  edits[6].display.exposure = 2.0f;
  std::set<uint64_t> hashes = {SceneContentHash(a)};
  for (const Scene& e : edits) hashes.insert(SceneContentHash(e));
  EXPECT_EQ(hashes.size(), edits.size() + 1);
  // A mesh vertex of a triangle scene.
  const Scene m = LoadScene("mesh");
  Scene m2 = m;
  for (auto& sh : m2.shapes) {
    if (!sh.positions.empty()) {
      sh.positions[7].y += 1e-3f;
      break;
    }
  }
  EXPECT_NE(SceneContentHash(m), SceneContentHash(m2));
}

// ---- the reference cache ---------------------------------------------------------------

bool SameImage(const ImageF& a, const ImageF& b) {
  return a.Width() == b.Width() && a.Height() == b.Height() && a.Channels() == b.Channels() && a.Data() == b.Data();
}

TEST(ReferenceCache, StoresAndReadsBackBitForBitAndChecksWhatItReads) {
  const fs::path dir = TempDir("cache");
  const ReferenceCache cache((dir / "c").string());
  const Scene scene = LoadScene("wedges");
  const Tracer tracer(scene);
  bool hit = true;
  const CachedReference first = ObtainReference(scene, tracer, 37, 23, 4, 7, false, &cache, &hit);
  EXPECT_FALSE(hit);
  const CachedReference direct = ObtainReference(scene, tracer, 37, 23, 4, 7, false, nullptr, &hit);
  EXPECT_FALSE(hit);
  const CachedReference again = ObtainReference(scene, tracer, 37, 23, 4, 7, false, &cache, &hit);
  EXPECT_TRUE(hit);
  for (const CachedReference* r : {&first, &again}) {
    EXPECT_TRUE(SameImage(r->ref.image, direct.ref.image));
    EXPECT_EQ(r->halves_mse, MeanSquaredError(direct.ref.half_a, direct.ref.half_b).mse);
    EXPECT_TRUE(SameImage(r->ref.edge_mask, direct.ref.edge_mask));
    EXPECT_TRUE(SameImage(r->ref.edge_mask_raw, direct.ref.edge_mask_raw));
    EXPECT_EQ(r->ref.grid, 4);
    EXPECT_EQ(r->primary_rays, direct.primary_rays);
    EXPECT_EQ(r->primary_rays, 37u * 23u * 16u) << "16 camera rays per pixel (no alpha cut-outs in wedges)";
  }
  EXPECT_EQ(again.render_ms, first.render_ms) << "a hit reports the time the render took when it was made";
  EXPECT_GT(direct.halves_mse, 0.0) << "4x4 samples on edges: the halves differ";
  EXPECT_TRUE(again.ref.half_a.Data().empty()) << "the halves are not stored";
  // The entry: 3 float images (RGB, two masks) = 20 bytes a pixel, plus a header under 1 KB.
  const auto size = fs::file_size(cache.PathOf(ReferenceCache::Key(scene, 37, 23, 4, 7, false)));
  EXPECT_GE(size, 37u * 23u * 20u);
  EXPECT_LT(size, 37u * 23u * 20u + 1024u);
  // Every input of the key changes it.
  const std::string key = ReferenceCache::Key(scene, 37, 23, 4, 7, false);
  std::set<std::string> keys = {key,
                                ReferenceCache::Key(scene, 38, 23, 4, 7, false),
                                ReferenceCache::Key(scene, 37, 24, 4, 7, false),
                                ReferenceCache::Key(scene, 37, 23, 2, 7, false),
                                ReferenceCache::Key(scene, 37, 23, 4, 8, false),
                                ReferenceCache::Key(scene, 37, 23, 4, 7, true),
                                ReferenceCache::Key(LoadScene("circle"), 37, 23, 4, 7, false)};
  EXPECT_EQ(keys.size(), 7u);
  // A damaged entry is refused with its file named, not read.
  const std::string path = cache.PathOf(key);
  std::string bytes = ReadBytes(path);
  bytes[bytes.size() / 2] ^= 0x01;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  std::string m = MessageOf([&] { cache.Load(key); });
  EXPECT_NE(m.find(path), std::string::npos) << m;
  EXPECT_NE(m.find("checksum"), std::string::npos) << m;
  // An entry holding another key (a file copied by hand, or a name collision) is refused too.
  const std::string other = ReferenceCache::Key(scene, 37, 23, 4, 8, false);
  ObtainReference(scene, tracer, 37, 23, 4, 8, false, &cache, &hit);
  fs::copy_file(cache.PathOf(other), path, fs::copy_options::overwrite_existing);
  m = MessageOf([&] { cache.Load(key); });
  EXPECT_NE(m.find("holds another reference"), std::string::npos) << m;
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(dir / "c")) EXPECT_EQ(e.path().extension(), ".ref") << e.path();
  // A file where the folder should be.
  std::ofstream(dir / "file") << "x";
  EXPECT_NE(MessageOf([&] { ReferenceCache c((dir / "file").string()); }).find("is not a folder"), std::string::npos);
  fs::remove_all(dir);
}

// ---- sharded runs against single runs --------------------------------------------------

/// The single report with the merged report's timings and context: what must match byte for
/// byte (the merged report with the single run's timings and context copied in).
Report WithTimingsOf(Report merged, const Report& single) {
  merged.context = single.context;
  merged.time_breakdown = single.time_breakdown;
  merged.settings = single.settings;  // threads only: the rest is compared below
  EXPECT_EQ(merged.scenes.size(), single.scenes.size());
  EXPECT_EQ(merged.rows.size(), single.rows.size());
  for (size_t i = 0; i < std::min(merged.scenes.size(), single.scenes.size()); ++i) {
    SceneResult& m = merged.scenes[i];
    const SceneResult& s = single.scenes[i];
    m.reference_ms = s.reference_ms;
    m.bvh_build_ms = s.bvh_build_ms;
    m.sequence_scene_ms = s.sequence_scene_ms;
    m.sequence_reference_ms = s.sequence_reference_ms;
  }
  for (size_t i = 0; i < std::min(merged.rows.size(), single.rows.size()); ++i) {
    ResultRow& m = merged.rows[i];
    const ResultRow& s = single.rows[i];
    m.render = s.render;
    m.post = s.post;
    m.resample = s.resample;
    m.total = s.total;
  }
  return merged;
}

void ExpectSameAsSingle(const fs::path& single, const fs::path& merged) {
  const SameResults same = CompareResultFolders(single.string(), merged.string());
  EXPECT_TRUE(same.same);
  for (const auto& d : same.differences) ADD_FAILURE() << d;
  const Report s = ReadReportFile((single / "report.json").string());
  const Report m = ReadReportFile((merged / "report.json").string());
  std::vector<std::pair<std::string, std::string>> ms = m.settings, ss = s.settings;
  std::erase_if(ms, [](const auto& kv) { return kv.first == "threads"; });
  std::erase_if(ss, [](const auto& kv) { return kv.first == "threads"; });
  EXPECT_EQ(ms, ss);
  EXPECT_FALSE(m.shard.has_value());
  const Report aligned = WithTimingsOf(m, s);
  EXPECT_TRUE(ReportToJson(aligned).dump(2) + "\n" == ReadBytes(single / "report.json")) << "report.json differs";
  // Each page is the page of its report, time breakdown included.
  EXPECT_TRUE(RenderHtmlReport(aligned) == ReadBytes(single / "index.html")) << "index.html differs";
  EXPECT_TRUE(RenderHtmlReport(m) == ReadBytes(merged / "index.html"));
}

RunSettings Small(const std::vector<std::string>& scenes, const fs::path& out) {
  RunSettings s;
  s.scenes = scenes;
  s.width = 61;  // odd on both axes
  s.height = 37;
  s.ref_spp = 16;
  s.repeat = 1;
  s.quiet = true;
  s.out_dir = out.string();
  return s;
}

TEST(ShardedRun, MergedEqualsSingleWithDefaultMethodsAnEdgelessSceneAndAnEmptyShard) {
  const fs::path dir = TempDir("run");
  // detail-texture has no edge pixels (edge metrics null with a reason).
  const std::vector<std::string> scenes = {"circle", "detail-texture", "wedges", "thin-wires"};
  RunSuite(Small(scenes, dir / "single"));
  for (int n : {3, 5}) {  // 5 > 4 scenes: shard 4 holds nothing
    std::vector<std::string> shard_dirs;
    for (int k = n - 1; k >= 0; --k) {                                       // any order
      const std::string name = std::to_string(n) + "-" + std::to_string(k);  // ("n" + ... trips GCC 12's -Wrestrict)
      RunSettings s = Small(scenes, dir / name);
      s.shard = {k, n};
      s.ref_cache = (dir / "cache").string();
      s.threads = 1 + k % 2;  // thread counts may differ between shards
      const Report r = RunSuite(s);
      ASSERT_TRUE(r.shard.has_value());
      EXPECT_EQ(r.shard->units.size(), ShardShare(scenes.size(), {k, n}).size());
      shard_dirs.push_back(s.out_dir);
    }
    const fs::path merged = dir / ("merged" + std::to_string(n));
    const MergeResult mr = MergeShards(shard_dirs, merged.string());
    EXPECT_EQ(mr.kind, "run");
    EXPECT_EQ(mr.scenes, scenes.size());
    size_t still_methods = 0;  // a still run's default list leaves methods with memory out
    for (const auto& m : DefaultMethods()) still_methods += MakeMethod(m).NeedsHistory() ? 0 : 1;
    EXPECT_EQ(mr.rows, scenes.size() * still_methods);
    ExpectSameAsSingle(dir / "single", merged);
  }
  EXPECT_FALSE(fs::exists(dir / "5-4" / "index.html")) << "an empty shard has no page";
  // The second split read every reference from the cache the first one wrote: 4 entries.
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir / "cache")) entries += e.path().extension() == ".ref" ? 1 : 0;
  EXPECT_EQ(entries, scenes.size());
  fs::remove_all(dir);
}

TEST(ShardedRun, MotionRunWithReferencesPrefilledByFrame) {
  const fs::path dir = TempDir("motion");
  // A moving scene (one reference per frame) and a still one; taa carries memory over frames.
  const std::vector<std::string> scenes = {"motion-pan", "circle"};
  auto settings = [&](const fs::path& out) {
    RunSettings s = Small(scenes, out);
    s.frames = 3;
    s.methods = {"none", "fxaa-high", "taa"};
    return s;
  };
  RunSuite(settings(dir / "single"));
  // References first, split by frame: 3 frames of motion-pan + circle = 4 units over 3 shards.
  int rendered = 0, cached = 0;
  for (int k = 0; k < 3; ++k) {
    RunSettings s = settings(dir / "unused");
    s.shard = {k, 3};
    s.ref_cache = (dir / "cache").string();
    int c = 0;
    rendered += RenderReferencesOnly(s, &c);
    cached += c;
  }
  EXPECT_EQ(rendered, 4);
  EXPECT_EQ(cached, 0);
  // The shards then find every reference cached: the cache does not grow.
  std::vector<std::string> shard_dirs;
  for (int k = 0; k < 2; ++k) {
    RunSettings s = settings(dir / ("s" + std::to_string(k)));
    s.shard = {k, 2};
    s.ref_cache = (dir / "cache").string();
    RunSuite(s);
    shard_dirs.push_back(s.out_dir);
  }
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir / "cache")) entries += e.path().extension() == ".ref" ? 1 : 0;
  EXPECT_EQ(entries, 4u);
  MergeShards(shard_dirs, (dir / "merged").string());
  ExpectSameAsSingle(dir / "single", dir / "merged");
  // --references-only without a cache folder is refused.
  EXPECT_NE(MessageOf([&] { RenderReferencesOnly(settings(dir / "x")); }).find("--ref-cache"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ShardedSweep, MergedSweepEqualsSingleSweep) {
  const fs::path dir = TempDir("sweep");
  auto settings = [&](const fs::path& out) {
    SweepSettings s;
    s.scenes = {"circle", "wedges"};
    s.method = "fxaa311-p39";
    s.grid = {"subpix=0,0.5,1", "edge_threshold=0.125,0.25"};
    s.width = 45;
    s.height = 33;
    s.ref_spp = 16;
    s.repeat = 1;
    s.quiet = true;
    s.out_dir = out.string();
    return s;
  };
  const SweepResult single = RunSweep(settings(dir / "single"));
  // The references first (one per scene, over 2 shards), then the points: the cache holds 2.
  for (int k = 0; k < 2; ++k) {
    SweepSettings s = settings(dir / "unused");
    s.shard = {k, 2};
    s.ref_cache = (dir / "cache").string();
    int cached = -1;
    EXPECT_EQ(RenderSweepReferences(s, &cached), 1);
    EXPECT_EQ(cached, 0);
  }
  std::vector<std::string> shard_dirs;
  for (int k = 0; k < 7; ++k) {  // 7 shards for 6 points: shard 6 has none
    SweepSettings s = settings(dir / ("s" + std::to_string(k)));
    s.shard = {k, 7};
    s.ref_cache = (dir / "cache").string();
    const SweepResult r = RunSweep(s);
    EXPECT_EQ(r.report.rows.size(), 2 * ShardShare(6, {k, 7}).size());
    EXPECT_EQ(r.report.scenes.size(), k < 6 ? 2u : 0u) << "a shard without points renders nothing";
    EXPECT_FALSE(fs::exists(dir / ("s" + std::to_string(k)) / "index.html")) << "a shard writes no summary page";
    shard_dirs.push_back(s.out_dir);
  }
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir / "cache")) entries += e.path().extension() == ".ref" ? 1 : 0;
  EXPECT_EQ(entries, 2u) << "the sweep shards found both references cached";
  const MergeResult mr = MergeShards(shard_dirs, (dir / "merged").string());
  EXPECT_EQ(mr.kind, "sweep");
  EXPECT_EQ(mr.rows, 12u);
  const SameResults same = CompareResultFolders((dir / "single").string(), (dir / "merged").string());
  EXPECT_TRUE(same.same);
  for (const auto& d : same.differences) ADD_FAILURE() << d;
  std::ifstream f(dir / "merged" / "sweep.json");
  const auto j = nlohmann::ordered_json::parse(f);
  EXPECT_EQ(j.at("suggested_preset").get<std::string>(), single.suggested_preset);
  EXPECT_EQ(j.at("points").size(), 6u);
  fs::remove_all(dir);
}

// ---- what merge refuses ----------------------------------------------------------------

TEST(Merge, RefusesShardsThatDoNotFitAndWritesNothing) {
  const fs::path dir = TempDir("refuse");
  const std::vector<std::string> scenes = {"circle", "wedges", "thin-wires"};
  auto shard = [&](int k, int n, const std::string& name, int ref_spp = 16) {
    RunSettings s = Small(scenes, dir / name);
    s.methods = {"none", "fxaa311-p12"};
    s.ref_spp = ref_spp;
    s.shard = {k, n};
    RunSuite(s);
    return s.out_dir;
  };
  const std::string a = shard(0, 3, "a"), b = shard(1, 3, "b"), c = shard(2, 3, "c");
  const std::string b64 = shard(1, 3, "b64", 64), two = shard(0, 2, "two");
  RunSettings whole = Small(scenes, dir / "whole");
  whole.methods = {"none"};
  RunSuite(whole);
  const std::string out = (dir / "out").string();
  auto refusal = [&](const std::vector<std::string>& dirs) { return MessageOf([&] { MergeShards(dirs, out); }); };
  EXPECT_NE(refusal({a, b}).find("shard(s) 2 of 3 missing"), std::string::npos);
  EXPECT_NE(refusal({a, b, b, c}).find("shard 1/3 is given twice"), std::string::npos);
  EXPECT_NE(refusal({a, b64, c}).find("ref_spp is '16' in '" + a + "' and '64' in '" + b64 + "'"), std::string::npos);
  EXPECT_NE(refusal({a, b, c, two}).find("not one split"), std::string::npos);
  EXPECT_NE(refusal({a, b, whole.out_dir}).find("holds a whole report"), std::string::npos);
  EXPECT_NE(refusal({a, b, (dir / "nowhere").string()}).find("is not a folder"), std::string::npos);
  // A shard folder that lost an image, and one whose report claims another share.
  const fs::path lost = fs::path(c) / "images" / "thin-wires" / "none.png";
  fs::rename(lost, dir / "kept.png");
  EXPECT_NE(refusal({a, b, c}).find("lacks images/thin-wires/none.png"), std::string::npos);
  fs::rename(dir / "kept.png", lost);
  Report rb = ReadReportFile(b + "/report.json");
  rb.shard->units.push_back("circle");
  std::ofstream(b + "/report.json", std::ios::trunc) << ReportToJson(rb).dump(2);
  EXPECT_NE(refusal({a, b, c}).find("holds 2 scene(s) where the split of 3 gives it 1"), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
