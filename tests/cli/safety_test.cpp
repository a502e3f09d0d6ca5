// Nothing a user owns is ever lost (issue #24), through the real binary and real folders:
// the output folder rule, checked writes on a full disk (RLIMIT_FSIZE), signals sent to a
// running child, channels by name and raw alpha, option and report errors. None needs root.
// docs/hard-cases.md ("Fault injection") lists what each test shows.
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>

#include "harness/run/out_folder.h"
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "core/image.h"
#include "io/image_io.h"
#include "tests/cli/cli_util.h"
#include "tests/cli/process_util.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;
using clitest::Aalab;
using clitest::Bytes;
using clitest::CmdResult;
using clitest::RunCommand;
using clitest::SpawnAalab;
using clitest::TempDir;

const std::string kSmall = "--scenes circle --methods none,fxaa311-p39 --size 24x16 --ref-spp 4 --repeat 1 --quiet";

/// Every entry under `dir` whose name starts with ".tmp-" or ends in ".partial" (leftovers).
std::vector<std::string> Leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(".tmp-", 0) == 0 || n.find(".partial") != std::string::npos || n.find(".old-") != std::string::npos ||
        n.find(".tmp.") != std::string::npos) {
      found.push_back(e.path().string());
    }
  }
  return found;
}

void ExpectFail(const CmdResult& r, int code, const std::vector<std::string>& parts, const std::string& what) {
  EXPECT_EQ(r.code, code) << what << "\n" << r.output;
  for (const auto& p : parts)
    EXPECT_NE(r.output.find(p), std::string::npos) << what << "\nmissing: " << p << "\n" << r.output;
  EXPECT_EQ(r.output.find("Success"), std::string::npos) << r.output;
}

TEST(Safety, OutputPathsAreNormalisedAndUsersFilesSurvive) {
  const fs::path dir = TempDir("safety-out");
  const std::string res = (dir / "results").string();
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res).code, 0);
  const std::string report = Bytes(dir / "results" / "report.json");
  std::ofstream(dir / "results" / "notes.txt") << "mine";
  // The spellings shell completion and users type: all the same folder, all refused because of
  // the user's file, which survives with the report.
  for (const std::string& out : {res + "/", res + "/.", res + "/images/..", res + "//"}) {
    ExpectFail(Aalab("run " + kSmall + " --out " + out), 1,
               {"cannot be replaced", "'notes.txt', which aalab did not write"}, out);
    EXPECT_EQ(Bytes(dir / "results" / "notes.txt"), "mine") << out;
    EXPECT_EQ(Bytes(dir / "results" / "report.json"), report) << out;
  }
  const CmdResult cwd =
      RunCommand("cd " + res + " && " + std::string(AALAB_BINARY_DIR) + "/aalab run " + kSmall + " --out . 2>&1");
  ExpectFail(cwd, 1, {"notes.txt"}, "--out .");
  EXPECT_TRUE(fs::exists(dir / "results" / "notes.txt"));
  // Without the user's file, an earlier run's folder is replaced through every spelling.
  fs::remove(dir / "results" / "notes.txt");
  for (const std::string& out : {res + "/", res + "/.", res + "/images/.."}) {
    EXPECT_EQ(Aalab("run " + kSmall + " --out " + out).code, 0) << out;
    EXPECT_TRUE(fs::exists(dir / "results" / "report.json")) << out;
  }
  // A new folder given with a slash is kept at the end.
  EXPECT_EQ(Aalab("run " + kSmall + " --out " + (dir / "fresh").string() + "/").code, 0);
  EXPECT_TRUE(fs::exists(dir / "fresh" / "report.json"));
  // Another kind (a sweep folder) is not replaced by a run, nor a folder aalab never wrote.
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "a.txt") << "x";
  ExpectFail(Aalab("run " + kSmall + " --out " + (dir / "mine").string()), 1, {"was not written by aalab"}, "mine");
  std::ofstream(dir / "not-a-folder") << "x";
  ExpectFail(Aalab("run " + kSmall + " --out " + (dir / "not-a-folder").string()), 1, {"is not a folder"}, "file");
  // A DIR.partial aalab did not make is never removed.
  fs::create_directories(dir / "x.partial");
  std::ofstream(dir / "x.partial" / "keep.txt") << "x";
  ExpectFail(Aalab("run " + kSmall + " --out " + (dir / "x").string()), 1, {"was not made by aalab"}, "x.partial");
  EXPECT_TRUE(fs::exists(dir / "x.partial" / "keep.txt"));
  EXPECT_EQ(Leftovers(dir), std::vector<std::string>{(dir / "x.partial").string()});
  fs::remove_all(dir);
}

// A run folder from an aalab build before the list of written files (no .aalab-output) is
// replaced when it holds only report.json, index.html and the images report.json names, so
// `make run` after an update reuses out/; one more file anywhere in it and it is refused.
TEST(Safety, AnOlderBuildsRunFolderIsReplacedOnlyWhenItHoldsNothingElse) {
  const fs::path dir = TempDir("safety-legacy");
  const fs::path res = dir / "old";
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res.string()).code, 0);
  fs::remove(res / kOutputMarker);  // as an older build left it
  std::ofstream(res / "images" / "circle" / "mine.png") << "x";
  ExpectFail(Aalab("run " + kSmall + " --out " + res.string()), 1, {"was not written by aalab"}, "legacy+user file");
  EXPECT_EQ(Bytes(res / "images" / "circle" / "mine.png"), "x");
  fs::remove(res / "images" / "circle" / "mine.png");
  // A report.json that is not an aalab report does not make a folder aalab's.
  const std::string report = Bytes(res / "report.json");
  std::ofstream(res / "report.json") << "{\"rows\": []}";
  ExpectFail(Aalab("run " + kSmall + " --out " + res.string()), 1, {"was not written by aalab"}, "legacy+foreign json");
  std::ofstream(res / "report.json") << report;
  EXPECT_EQ(Aalab("run " + kSmall + " --out " + res.string()).code, 0);
  EXPECT_TRUE(fs::exists(res / kOutputMarker));
  fs::remove_all(dir);
}

TEST(Safety, AnOutputFolderMayNotHoldTheInputs) {
  const fs::path dir = TempDir("safety-inputs");
  const std::string res = (dir / "res").string();
  // The reference cache inside (or equal to) the output folder: refused before any work.
  ExpectFail(Aalab("run " + kSmall + " --out " + res + " --ref-cache " + res + "/cache"), 1,
             {"contains the input", "cache"}, "cache inside");
  ExpectFail(Aalab("run " + kSmall + " --out " + res + " --ref-cache " + res), 1, {"is the input"}, "cache equal");
  EXPECT_FALSE(fs::exists(res));
  // A scene file inside the output folder.
  fs::create_directories(dir / "scenes");
  fs::copy_file(fs::path(AALAB_SOURCE_DIR) / "scenes" / "library" / "circle.json", dir / "scenes" / "s.json");
  ExpectFail(Aalab("run --scenes " + (dir / "scenes" / "s.json").string() + " --out " + (dir / "scenes").string()), 1,
             {"contains the input"}, "scene file");
  // merge into one of its own shard folders.
  const std::string s0 = (dir / "s0").string(), s1 = (dir / "s1").string();
  ASSERT_EQ(Aalab("run " + kSmall + " --shard 0/2 --out " + s0).code, 0);
  ASSERT_EQ(Aalab("run " + kSmall + " --shard 1/2 --out " + s1).code, 0);
  const std::string shard0 = Bytes(dir / "s0" / "report.json");
  ExpectFail(Aalab("merge " + s0 + " " + s1 + " --out " + s0 + "/"), 1, {"is the input"}, "merge into a shard");
  EXPECT_EQ(Bytes(dir / "s0" / "report.json"), shard0);
  EXPECT_EQ(Aalab("merge " + s0 + " " + s1 + " --out " + (dir / "merged").string() + "/").code, 0);
  EXPECT_TRUE(fs::exists(dir / "merged" / "report.json"));
  EXPECT_TRUE(Leftovers(dir).empty());
  fs::remove_all(dir);
}

/// `aalab ARGS` with a file size limit of `bytes` (SIGXFSZ ignored, so writes fail with EFBIG
/// as on a full disk).
CmdResult AalabWithFileLimit(const std::string& args, long bytes) {
  // dash's ulimit -f counts 512-byte blocks.
  return RunCommand("sh -c 'trap \"\" XFSZ; ulimit -f " + std::to_string(bytes / 512) + "; exec " +
                    std::string(AALAB_BINARY_DIR) + "/aalab " + args + "' 2>&1");
}

TEST(Safety, AFullDiskFailsNamingTheFileAndLeavesNothing) {
  const fs::path dir = TempDir("safety-full");
  const std::string in = (dir / "in.png").string();
  ASSERT_EQ(Aalab("render --scene checker-plane --size 200x150 --out " + in).code, 0);
  ASSERT_GT(fs::file_size(in), 1024u);
  for (const std::string out : {"o.png", "o.jpg", "o.tif"}) {
    const CmdResult r = AalabWithFileLimit("apply --method fxaa311-p39 " + in + " " + (dir / out).string(), 512);
    ExpectFail(r, 1, {"cannot write '" + (dir / out).string() + "': File too large"}, out);
    EXPECT_EQ(r.output.find("wrote"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / out)) << out;
  }
  const CmdResult render =
      AalabWithFileLimit("render --scene checker-plane --size 200x150 --out " + (dir / "r.exr").string(), 512);
  ExpectFail(render, 1, {"r.exr': File too large"}, "render");
  EXPECT_FALSE(fs::exists(dir / "r.exr"));
  // A run: nothing of it stays (no DIR, no DIR.partial), and an earlier result is kept.
  const std::string res = (dir / "res").string();
  ExpectFail(AalabWithFileLimit("run " + kSmall + " --out " + res, 512), 1, {"File too large"}, "run");
  EXPECT_FALSE(fs::exists(res));
  EXPECT_EQ(Leftovers(dir), std::vector<std::string>{});
  fs::remove_all(dir);
}

TEST(Safety, SignalsStopPromptlyAndLeaveWhatWasThere) {
  const fs::path dir = TempDir("safety-signal");
  const std::string res = (dir / "res").string(), cache = (dir / "cache").string();
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res).code, 0);
  const std::string report = Bytes(dir / "res" / "report.json");
  for (const auto& [sig, code, word] : std::vector<std::tuple<int, int, std::string>>{
           {SIGINT, 130, "interrupted (SIGINT)"}, {SIGTERM, 143, "terminated (SIGTERM)"}}) {
    // A run long enough to be caught: several scenes at 320x240 with 256 samples per pixel.
    const pid_t pid =
        SpawnAalab("run --suite quick --size 320x240 --ref-spp 256 --quiet --ref-cache " + cache + " --out " + res,
                   dir / "log.txt");
    // Wait until it has started writing (DIR.partial exists), then signal it.
    for (int i = 0; i < 600 && !fs::exists(res + ".partial"); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(fs::exists(res + ".partial"));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const auto t0 = std::chrono::steady_clock::now();
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(WIFEXITED(status)) << word;
    EXPECT_EQ(WEXITSTATUS(status), code) << word;
    EXPECT_LT(seconds, 5.0) << word;
    const std::string log = Bytes(dir / "log.txt");
    EXPECT_NE(log.find("aalab: " + word + ": stopped"), std::string::npos) << log;
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
    // What the run had started is gone; what was there before is as it was.
    EXPECT_FALSE(fs::exists(res + ".partial")) << word;
    EXPECT_EQ(Bytes(dir / "res" / "report.json"), report) << word;
    EXPECT_EQ(Leftovers(dir), std::vector<std::string>{}) << word;
  }
  fs::remove_all(dir);
}

TEST(Safety, ASecondRunIntoTheSameFolderIsRefusedAtStart) {
  const fs::path dir = TempDir("safety-lock");
  const std::string res = (dir / "res").string();
  const pid_t pid = SpawnAalab("run --suite quick --size 320x240 --ref-spp 256 --quiet --out " + res, dir / "log.txt");
  for (int i = 0; i < 600 && !fs::exists(res + ".partial"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(fs::exists(res + ".partial"));
  // The second run asks for work that would take minutes (1280x720 at 1024 spp: ~940 M reference
  // samples), so a refusal within 20 s, however loaded the machine, proves it came before any
  // rendering; a bar on a tiny run's wall time proved less and failed under load (5.2 s).
  const auto t0 = std::chrono::steady_clock::now();
  ExpectFail(
      Aalab("run --scenes circle --methods none --size 1280x720 --ref-spp 1024 --repeat 1 --quiet --out " + res + "/"),
      1, {"is being written by another aalab command right now (process " + std::to_string(pid)}, "second run");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 20.0);
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_FALSE(fs::exists(res + ".partial"));
  // A DIR.partial left by a killed command (SIGKILL: no clean-up) is taken over.
  const pid_t killed =
      SpawnAalab("run --suite quick --size 320x240 --ref-spp 256 --quiet --out " + res, dir / "log.txt");
  for (int i = 0; i < 600 && !fs::exists(res + ".partial"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ::kill(killed, SIGKILL);
  ::waitpid(killed, &status, 0);
  ASSERT_TRUE(fs::exists(res + ".partial"));
  EXPECT_EQ(Aalab("run " + kSmall + " --out " + res).code, 0);
  EXPECT_TRUE(fs::exists(dir / "res" / "report.json"));
  EXPECT_FALSE(fs::exists(res + ".partial"));
  fs::remove_all(dir);
}

void WriteNamed(const fs::path& p, int w, int h, const std::vector<std::string>& names, OIIO::TypeDesc type,
                const std::vector<float>& data) {
  OIIO::ImageSpec spec(w, h, static_cast<int>(names.size()), type);
  spec.channelnames = names;
  spec.alpha_channel = -1;
  for (size_t c = 0; c < names.size(); ++c)
    spec.alpha_channel = names[c] == "A" ? static_cast<int>(c) : spec.alpha_channel;
  spec.attribute("oiio:UnassociatedAlpha", 1);
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out && out->open(p.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, data.data()) &&
              out->close());
}

TEST(Safety, ApplyReadsColourByNameAndNeverPremultiplies) {
  const fs::path dir = TempDir("safety-alpha");
  // A frame with an edge, stored with alpha 255, 254 and 0: apply must give the same output
  // for all three (premultiplied, alpha 0 is a black frame and alpha 254 moves values).
  const int w = 16, h = 12;
  std::vector<float> rgb;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float v = x + y > 12 ? 220.0f / 255 : 30.0f / 255;
      rgb.insert(rgb.end(), {v, v * 0.5f, 1.0f - v});
    }
  }
  for (int a : {255, 254, 0}) {
    std::vector<float> rgba;
    for (size_t i = 0; i < rgb.size(); i += 3) rgba.insert(rgba.end(), {rgb[i], rgb[i + 1], rgb[i + 2], a / 255.0f});
    WriteNamed(dir / ("a" + std::to_string(a) + ".png"), w, h, {"R", "G", "B", "A"}, OIIO::TypeDesc::UINT8, rgba);
    ASSERT_EQ(Aalab("apply --method fxaa311-p39 " + (dir / ("a" + std::to_string(a) + ".png")).string() + " " +
                    (dir / ("o" + std::to_string(a) + ".png")).string())
                  .code,
              0);
  }
  EXPECT_EQ(ReadImage8((dir / "o254.png").string()), ReadImage8((dir / "o255.png").string()));
  EXPECT_EQ(ReadImage8((dir / "o0.png").string()), ReadImage8((dir / "o255.png").string()));
  // EXR channels by name: B, G, R order and a renderer's R, G, B, A, Z give the RGB result.
  std::vector<float> bgr, rgbaz;
  for (size_t i = 0; i < rgb.size(); i += 3) {
    bgr.insert(bgr.end(), {rgb[i + 2], rgb[i + 1], rgb[i]});
    rgbaz.insert(rgbaz.end(), {rgb[i], rgb[i + 1], rgb[i + 2], 1.0f, 1e30f});
  }
  WriteNamed(dir / "rgb.exr", w, h, {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, rgb);
  WriteNamed(dir / "bgr.exr", w, h, {"B", "G", "R"}, OIIO::TypeDesc::FLOAT, bgr);
  WriteNamed(dir / "rgbaz.exr", w, h, {"R", "G", "B", "A", "Z"}, OIIO::TypeDesc::FLOAT, rgbaz);
  for (const std::string n : {"rgb", "bgr", "rgbaz"}) {
    ASSERT_EQ(
        Aalab("apply --method fxaa311-p39 " + (dir / (n + ".exr")).string() + " " + (dir / (n + ".png")).string()).code,
        0)
        << n;
  }
  EXPECT_EQ(ReadImage8((dir / "bgr.png").string()), ReadImage8((dir / "rgb.png").string()));
  EXPECT_EQ(ReadImage8((dir / "rgbaz.png").string()), ReadImage8((dir / "rgb.png").string()));
  WriteNamed(dir / "xyz.exr", w, h, {"U", "V", "W"}, OIIO::TypeDesc::FLOAT, rgb);
  ExpectFail(Aalab("apply --method fxaa311-p39 " + (dir / "xyz.exr").string() + " " + (dir / "x.png").string()), 1,
             {"has no channels named R, G and B (its channels: U, V, W)"}, "U, V, W");
  // apply onto its own input: refused, the input kept.
  const std::string before = Bytes(dir / "a255.png");
  ExpectFail(Aalab("apply --method fxaa311-p39 " + (dir / "a255.png").string() + " " + (dir / "a255.png").string()), 1,
             {"is the input"}, "onto its input");
  EXPECT_EQ(Bytes(dir / "a255.png"), before);
  // A FIFO as input: refused at once, not read (a read would block for ever).
  ASSERT_EQ(::mkfifo((dir / "pipe.png").c_str(), 0600), 0);
  ExpectFail(RunCommand("timeout 20 " + std::string(AALAB_BINARY_DIR) + "/aalab apply --method fxaa311-p39 " +
                        (dir / "pipe.png").string() + " " + (dir / "p.png").string() + " 2>&1"),
             1, {"is not a regular file"}, "FIFO");
  fs::remove_all(dir);
}

TEST(Safety, OptionAndReportErrorsSayWhatIsAllowed) {
  const fs::path dir = TempDir("safety-args");
  ExpectFail(Aalab("run --frames abc"), 1, {"--frames", "abc", "a whole number"}, "--frames abc");
  ExpectFail(Aalab("run --threads 1.5"), 1, {"--threads", "1.5", "a whole number"}, "--threads 1.5");
  ExpectFail(Aalab("run --bogus"), 1, {"--bogus", "aalab run --help"}, "--bogus");
  ExpectFail(Aalab("sweep --repeat x"), 1, {"--repeat", "x", "a whole number"}, "--repeat x");
  ExpectFail(Aalab(""), 1, {"subcommand is required", "commands: list"}, "no command");
  EXPECT_EQ(Aalab("--help").code, 0);
  // same-results on folders whose report.json is not an aalab report: could not compare (2),
  // naming the file; an unsupported schema version likewise.
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  std::ofstream(dir / "a" / "report.json") << "[1, 2]";
  std::ofstream(dir / "b" / "report.json") << R"({"schema_version": 99})";
  const std::string a = (dir / "a").string(), b = (dir / "b").string();
  ExpectFail(Aalab("same-results " + a + " " + b), 2, {(dir / "a" / "report.json").string(), "not an aalab report"},
             "not a report");
  EXPECT_EQ(Aalab("same-results " + a + " " + b).output.find("[json.exception"), std::string::npos);
  std::ofstream(dir / "a" / "report.json") << R"({"schema_version": 99})";
  ExpectFail(Aalab("same-results " + a + " " + b), 2, {"schema_version 99 is not supported"}, "schema 99");
  // compare and merge-gpu name a folder given as a report as a folder, not as bad JSON.
  ExpectFail(Aalab("compare " + a + " " + (dir / "b" / "report.json").string()), 2, {"is a folder"}, "compare folder");
  ExpectFail(Aalab("merge-gpu " + a + " " + (dir / "b" / "report.json").string()), 1,
             {(dir / "a" / "report.json").string(), "schema_version 99"}, "merge-gpu");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
