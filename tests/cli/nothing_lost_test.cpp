// Nothing lost, everywhere (issue #39), through the real binary and real folders: paths taken
// from reports and manifests stay inside their folders, names that build output paths stay
// inside --out, every input counts, the output folder's promises (a file added during a run,
// a folder of another kind, a user's .aalab-lock, a mount point), SIGHUP and a closed stdout,
// the sampler as a condition, option exit codes. docs/hard-cases.md lists what each shows.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include <nlohmann/json.hpp>

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
using clitest::WaitForPath;
using clitest::WriteText;

const std::string kSmall = "--scenes circle --methods none,fxaa311-p39 --size 24x16 --ref-spp 4 --repeat 1 --quiet";

nlohmann::json ReadJson(const fs::path& p) { return nlohmann::json::parse(Bytes(p)); }
void WriteJson(const fs::path& p, const nlohmann::json& j) { WriteText(p, j.dump(2)); }

void ExpectFail(const CmdResult& r, int code, const std::vector<std::string>& parts, const std::string& what) {
  EXPECT_EQ(r.code, code) << what << "\n" << r.output;
  for (const auto& p : parts)
    EXPECT_NE(r.output.find(p), std::string::npos) << what << "\nmissing: " << p << "\n" << r.output;
}

/// Every file under `dir` (relative), for "nothing else was written" checks.
std::vector<std::string> FilesUnder(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_directory()) out.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// ---- Paths taken from a report ------------------------------------------------------------

TEST(NothingLost, MergeRefusesImagePathsThatLeaveTheShardOrOut) {
  const fs::path dir = TempDir("nl-merge");
  ASSERT_EQ(Aalab("run " + kSmall + " --shard 0/1 --out " + (dir / "s0").string()).code, 0);
  WriteText(dir / "victim.png", "the user's file");
  const nlohmann::json good = ReadJson(dir / "s0" / "report.json");
  for (const std::string& evil :
       {std::string("../victim.png"), (dir / "victim.png").string(), std::string("images/../../victim.png")}) {
    nlohmann::json j = good;
    j["rows"][0]["images"]["output"] = evil;
    WriteJson(dir / "s0" / "report.json", j);
    const auto before = FilesUnder(dir);
    ExpectFail(Aalab("merge " + (dir / "s0").string() + " --out " + (dir / "out").string()), 1,
               {"image path in report", evil, "stay inside"}, "merge " + evil);
    EXPECT_EQ(Bytes(dir / "victim.png"), "the user's file") << evil;
    EXPECT_FALSE(fs::exists(dir / "out")) << evil;
    EXPECT_EQ(FilesUnder(dir), before) << evil;
  }
  // A scene name that would make a folder outside --out.
  nlohmann::json j = good;
  j["scenes"][0]["name"] = "../x";
  j["shard"]["units"][0] = "../x";
  for (auto& row : j["rows"]) row["scene"] = "../x";
  WriteJson(dir / "s0" / "report.json", j);
  ExpectFail(Aalab("merge " + (dir / "s0").string() + " --out " + (dir / "out").string()), 1,
             {"scene name in report", "'../x'", "plain file names"}, "merge scene ../x");
  fs::remove_all(dir);
}

TEST(NothingLost, ExportSequencesRefusesNamesAndPathsThatLeave) {
  const fs::path dir = TempDir("nl-seq");
  ASSERT_EQ(Aalab("run --scenes motion-pan --methods none --frames 2 --size 24x16 --ref-spp 4 --repeat 1 --quiet "
                  "--out " +
                  (dir / "run").string())
                .code,
            0);
  const nlohmann::json good = ReadJson(dir / "run" / "report.json");
  WriteText(dir / "secret.png", "not an image of the run");
  auto replace_scene = [&](const std::string& name) {
    nlohmann::json j = good;
    j["scenes"][0]["name"] = name;
    for (auto& row : j["rows"]) row["scene"] = name;
    return j;
  };
  for (const std::string& evil : {std::string("../../escaped"), (dir / "abs").string()}) {
    WriteJson(dir / "run" / "report.json", replace_scene(evil));
    ExpectFail(Aalab("export-sequences " + (dir / "run").string() + " --out " + (dir / "seq").string()), 1,
               {"scene name in report", evil}, "scene " + evil);
    EXPECT_FALSE(fs::exists(dir / "seq"));
    EXPECT_FALSE(fs::exists(dir / "abs"));
    EXPECT_FALSE(fs::exists(dir.parent_path().parent_path() / "escaped"));
  }
  {  // a method spec that leaves its scene's folder, and one named like the reference folder
    for (const std::string& spec : {std::string("../../m"), std::string("reference")}) {
      nlohmann::json j = good;
      for (auto& row : j["rows"]) row["spec"] = spec;
      WriteJson(dir / "run" / "report.json", j);
      ExpectFail(Aalab("export-sequences " + (dir / "run").string() + " --out " + (dir / "seq").string()), 1,
                 {"method spec '" + spec + "'"}, "spec " + spec);
      EXPECT_FALSE(fs::exists(dir / "seq"));
    }
  }
  {  // a frame path that reads outside the run folder
    nlohmann::json j = good;
    j["rows"][0]["sequence"]["frames"][0] = "../secret.png";
    j["scenes"][0]["sequence"]["reference_frames"][0] = "../secret.png";
    WriteJson(dir / "run" / "report.json", j);
    ExpectFail(Aalab("export-sequences " + (dir / "run").string() + " --out " + (dir / "seq").string()), 1,
               {"frame path in report", "'../secret.png' leaves the folder"}, "frame ../secret.png");
    EXPECT_FALSE(fs::exists(dir / "seq"));
  }
  fs::remove_all(dir);
}

TEST(NothingLost, ExportNeverReadsImagesOutsideTheReportFolder) {
  const fs::path dir = TempDir("nl-export");
  fs::create_directories(dir / "a" / "b");
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + (dir / "a" / "b" / "run").string()).code, 0);
  // A real image outside the report folder: the old export published it in the figure.
  fs::copy_file(dir / "a" / "b" / "run" / "images" / "circle" / "reference.png", dir / "a" / "secret.png");
  nlohmann::json j = ReadJson(dir / "a" / "b" / "run" / "report.json");
  j["scenes"][0]["images"]["reference_png"] = "../../secret.png";
  WriteJson(dir / "a" / "b" / "run" / "report.json", j);
  ExpectFail(Aalab("export " + (dir / "a" / "b" / "run").string() + " --out " + (dir / "pub").string()), 1,
             {"image path in report", "'../../secret.png' leaves the folder"}, "export ../../secret.png");
  EXPECT_FALSE(fs::exists(dir / "pub"));
  fs::remove_all(dir);
}

// ---- Names that collide, inputs inside the output ------------------------------------------

/// A one-view image scene beside `dir`'s images: frame and reference are run outputs.
void WriteManifest(const fs::path& manifest, const std::string& frame, const std::string& reference,
                   const std::string& output_name = "") {
  nlohmann::json view = {{"name", "v"}, {"frame", frame}, {"reference", reference}};
  if (!output_name.empty()) view["outputs"] = {{{"name", output_name}, {"frame", frame}}};
  WriteJson(manifest, {{"aalab_image_scene", 1}, {"views", {view}}});
}

TEST(NothingLost, ImageScenesKeepTheirInputsAndReservedNames) {
  const fs::path dir = TempDir("nl-image");
  const fs::path res = dir / "res";
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res.string()).code, 0);
  const std::string report = Bytes(res / "report.json");
  // The frames live inside an earlier run folder, and --out is that folder: refused before
  // any work (the old rule checked the manifest only, and the run deleted its own inputs).
  WriteManifest(dir / "m.json", "res/images/circle/none.png", "res/images/circle/reference.png");
  ExpectFail(Aalab("run --scenes " + (dir / "m.json").string() + " --methods none --quiet --out " + res.string()), 1,
             {"contains the input", "none.png"}, "frames inside --out");
  EXPECT_EQ(Bytes(res / "report.json"), report);
  EXPECT_TRUE(fs::exists(res / "images" / "circle" / "none.png"));
  // A supplied output called `reference` would overwrite the reference's images.
  WriteManifest(dir / "m.json", "res/images/circle/none.png", "res/images/circle/reference.png", "reference");
  ExpectFail(
      Aalab("run --scenes " + (dir / "m.json").string() + " --methods none --quiet --out " + (dir / "out").string()), 1,
      {"'reference' is reserved"}, "output named reference");
  // Manifest paths stay inside the manifest's folder.
  WriteText(dir / "sub" / "x.txt", "");
  WriteManifest(dir / "sub" / "m.json", "../res/images/circle/none.png", "../res/images/circle/reference.png");
  ExpectFail(Aalab("run --scenes " + (dir / "sub" / "m.json").string() + " --methods none --quiet --out " +
                   (dir / "out").string()),
             1, {"/views/0/frame", "leaves the folder"}, "manifest ../");
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

// ---- history report, compare --html: the same file rule ------------------------------------

TEST(NothingLost, HistoryReportAndCompareHtmlNeverOverwriteAUsersFile) {
  const fs::path dir = TempDir("nl-history");
  const fs::path res = dir / "res";
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res.string()).code, 0);
  const std::string db = (dir / "db.jsonl").string();
  ASSERT_EQ(Aalab("history add " + (res / "report.json").string() + " --db " + db + " --date 2026-01-01").code, 0);
  // A user's page, and a run folder's own page: refused, untouched.
  WriteText(dir / "site" / "index.html", "<p>my page</p>");
  ExpectFail(Aalab("history report --db " + db + " --out " + (dir / "site").string()), 1,
             {"cannot be replaced", "not written by aalab"}, "history onto a user's page");
  EXPECT_EQ(Bytes(dir / "site" / "index.html"), "<p>my page</p>");
  const std::string run_page = Bytes(res / "index.html");
  ExpectFail(Aalab("history report --db " + db + " --out " + res.string()), 1, {"another kind"},
             "history onto a run folder");
  EXPECT_EQ(Bytes(res / "index.html"), run_page);
  // Its own earlier output is replaced.
  ASSERT_EQ(Aalab("history report --db " + db + " --out " + (dir / "hist").string()).code, 0);
  ASSERT_EQ(Aalab("history report --db " + db + " --out " + (dir / "hist").string()).code, 0);
  EXPECT_NE(Bytes(dir / "hist" / "index.html").find("<h1>aalab history</h1>"), std::string::npos);
  // compare --html onto a file aalab did not write: could not compare (2), file untouched.
  WriteText(dir / "notes.html", "<p>my notes</p>");
  ExpectFail(Aalab("compare " + (res / "report.json").string() + " " + (res / "report.json").string() + " --html " +
                   (dir / "notes.html").string()),
             2, {"not written by aalab compare"}, "compare --html onto a user's file");
  EXPECT_EQ(Bytes(dir / "notes.html"), "<p>my notes</p>");
  ASSERT_EQ(Aalab("compare " + (res / "report.json").string() + " " + (res / "report.json").string() + " --html " +
                  (dir / "cmp.html").string())
                .code,
            0);
  EXPECT_EQ(Aalab("compare " + (res / "report.json").string() + " " + (res / "report.json").string() + " --html " +
                  (dir / "cmp.html").string())
                .code,
            0);  // its own page is replaced
  fs::remove_all(dir);
}

// ---- The output folder's promises -----------------------------------------------------------

TEST(NothingLost, AUsersLockFileIsNeverDeletedSilently) {
  const fs::path dir = TempDir("nl-lock");
  const fs::path res = dir / "res";
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res.string()).code, 0);
  WriteText(res / ".aalab-lock", "my notes, named oddly");
  ExpectFail(Aalab("run " + kSmall + " --out " + res.string()), 1, {"'.aalab-lock', which aalab did not write"},
             "user's .aalab-lock");
  EXPECT_EQ(Bytes(res / ".aalab-lock"), "my notes, named oddly");
  fs::remove_all(dir);
}

TEST(NothingLost, AFileAddedDuringARunIsNeverDeletedAndTheWorkIsKept) {
  // The commit step checks DIR again just before replacing it: a file the user put into the
  // earlier output while the run worked is never deleted. (Planted bug: the re-check looking
  // at DIR.partial instead of DIR deletes the file; this test fails then.)
  const fs::path dir = TempDir("nl-added");
  const fs::path res = dir / "res";
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + res.string()).code, 0);
  const pid_t pid = SpawnAalab(
      "run --scenes circle,wedges --methods none,fxaa311-p39,smaa-high --size 160x90 --ref-spp 64 "
      "--repeat 1 --quiet --out " +
          res.string(),
      dir / "log.txt");
  ASSERT_TRUE(WaitForPath(res.string() + ".partial"));
  WriteText(res / "added-during-run.txt", "written while aalab worked");
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string log = Bytes(dir / "log.txt");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 1) << log;
  EXPECT_NE(log.find("'added-during-run.txt', which aalab did not write"), std::string::npos) << log;
  EXPECT_EQ(Bytes(res / "added-during-run.txt"), "written while aalab worked");
  // The finished work is kept in DIR.partial, and the message says so.
  EXPECT_NE(log.find("The finished output is kept in '" + res.string() + ".partial'"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(res.string() + ".partial/report.json")) << log;
  // A later run does not delete it either (it is no longer aalab's lock-holding leftover).
  fs::remove(res / "added-during-run.txt");
  ExpectFail(Aalab("run " + kSmall + " --out " + res.string()), 1, {"was not made by aalab"}, "kept partial");
  EXPECT_TRUE(fs::exists(res.string() + ".partial/report.json"));
  fs::remove_all(dir);
}

TEST(NothingLost, ARunNeverReplacesASweepsFolder) {
  // (Planted bug: dropping the kind check lets the run replace the sweep; this test fails then.)
  const fs::path dir = TempDir("nl-kind");
  const fs::path sw = dir / "sweep";
  ASSERT_EQ(Aalab("sweep --scenes circle --method fxaa311-p39 --grid subpix=0,1 --objective psnr_db --size 24x16 "
                  "--ref-spp 4 --repeat 1 --quiet --out " +
                  sw.string())
                .code,
            0);
  const auto before = FilesUnder(sw);
  const std::string sweep_json = Bytes(sw / "sweep.json");
  ASSERT_FALSE(sweep_json.empty());
  ExpectFail(Aalab("run " + kSmall + " --out " + sw.string()), 1, {"another kind (sweep", "writes a run output"},
             "run onto a sweep");
  EXPECT_EQ(FilesUnder(sw), before);
  EXPECT_EQ(Bytes(sw / "sweep.json"), sweep_json);
  // And the other way round.
  const fs::path run = dir / "run";
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + run.string()).code, 0);
  ExpectFail(Aalab("sweep --scenes circle --method fxaa311-p39 --grid subpix=0,1 --objective psnr_db --size 24x16 "
                   "--ref-spp 4 --repeat 1 --quiet --out " +
                   run.string()),
             1, {"another kind (run"}, "sweep onto a run");
  EXPECT_TRUE(fs::exists(run / "report.json"));
  fs::remove_all(dir);
}

TEST(NothingLost, AMountPointOutIsRefusedBeforeTheWork) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root for mount --bind (runs as root in CI's container)";
  const fs::path dir = TempDir("nl-mount");
  const fs::path mnt = dir / "mnt", src = dir / "src";
  fs::create_directories(mnt);
  fs::create_directories(src);
  WriteText(src / "keep.txt", "on the mounted file system");
  if (::mount(src.c_str(), mnt.c_str(), nullptr, MS_BIND, nullptr) != 0) {
    GTEST_SKIP() << "mount --bind refused here (" << std::strerror(errno) << "): a container without CAP_SYS_ADMIN";
  }
  const auto t0 = std::chrono::steady_clock::now();
  // Refused at once, naming the reason and what to do; the mounted content is untouched.
  const CmdResult r = Aalab("run --suite quick --size 320x240 --ref-spp 256 --quiet --out " + mnt.string());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ::umount(mnt.c_str());
  ExpectFail(r, 1, {"is a mount point", "Give a folder inside it"}, "mount point");
  EXPECT_LT(seconds, 5.0);
  EXPECT_EQ(Bytes(src / "keep.txt"), "on the mounted file system");
  EXPECT_FALSE(fs::exists(mnt.string() + ".partial"));
  fs::remove_all(dir);
}

// ---- Signals and a closed stdout ------------------------------------------------------------

TEST(NothingLost, SighupCleansUpLikeSigterm) {
  const fs::path dir = TempDir("nl-hup");
  const std::string res = (dir / "res").string();
  const pid_t pid = SpawnAalab("run --suite quick --size 320x240 --ref-spp 256 --quiet --out " + res, dir / "log.txt");
  ASSERT_TRUE(WaitForPath(res + ".partial"));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ::kill(pid, SIGHUP);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string log = Bytes(dir / "log.txt");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 129) << log;
  EXPECT_NE(log.find("aalab: hung up (SIGHUP): stopped"), std::string::npos) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
  EXPECT_FALSE(fs::exists(res + ".partial"));
  EXPECT_FALSE(fs::exists(res));
  fs::remove_all(dir);
}

TEST(NothingLost, AClosedStdoutNeverLosesTheReport) {
  // `aalab run ... | true`: the reader is gone before aalab prints. Before: killed by SIGPIPE
  // (status 141). Now: the run finishes, commits, exits 0 and says on stderr what was lost.
  const fs::path dir = TempDir("nl-pipe");
  const std::string res = (dir / "res").string();
  const CmdResult r =
      RunCommand("bash -c '" + std::string(AALAB_BINARY_DIR) + "/aalab run " + kSmall + " --out " + res + " 2>" +
                 (dir / "err.txt").string() + " | (exec 0<&-; sleep 0.1); echo status=${PIPESTATUS[0]}'");
  EXPECT_NE(r.output.find("status=0"), std::string::npos) << r.output << Bytes(dir / "err.txt");
  EXPECT_TRUE(fs::exists(dir / "res" / "report.json"));
  EXPECT_NE(Bytes(dir / "err.txt").find("standard output was closed"), std::string::npos) << Bytes(dir / "err.txt");
  fs::remove_all(dir);
}

// ---- Conditions, exit codes ------------------------------------------------------------------

TEST(NothingLost, TheSamplerIsAConditionOfCompareHistoryAndExport) {
  const fs::path dir = TempDir("nl-sampler");
  ASSERT_EQ(Aalab("run " + kSmall + " --out " + (dir / "gl").string()).code, 0);
  ASSERT_EQ(
      Aalab("run " + kSmall + " --sampler gpu-texture --viewing tv-1080p-2m --out " + (dir / "tex").string()).code, 0);
  ExpectFail(Aalab("compare " + (dir / "gl" / "report.json").string() + " " + (dir / "tex" / "report.json").string()),
             2, {"setting 'sampler' differs: baseline gl, current gpu-texture"}, "compare gl vs gpu-texture");
  const std::string db = (dir / "db.jsonl").string();
  ASSERT_EQ(Aalab("history add " + (dir / "gl" / "report.json").string() + " --db " + db + " --date 2026-01-01").code,
            0);
  ExpectFail(Aalab("history add " + (dir / "tex" / "report.json").string() + " --db " + db + " --date 2026-01-02"), 1,
             {"sampler: series gl, report gpu-texture"}, "history add across samplers");
  ASSERT_EQ(
      Aalab("export " + (dir / "gl").string() + " " + (dir / "tex").string() + " --out " + (dir / "pub").string()).code,
      0);
  const std::string tex = Bytes(dir / "pub" / "figure_crops.tex");
  EXPECT_NE(tex.find("gl: "), std::string::npos) << tex;
  EXPECT_NE(tex.find("Post-filter sampler: gl."), std::string::npos) << tex;
  EXPECT_NE(tex.find("tex: "), std::string::npos) << tex;
  EXPECT_NE(tex.find("Post-filter sampler: gpu-texture."), std::string::npos) << tex;
  EXPECT_NE(tex.find("tv-1080p-2m"), std::string::npos) << tex;
  fs::remove_all(dir);
}

TEST(NothingLost, OptionErrorsExitWithEachCommandsOwnCode) {
  const fs::path dir = TempDir("nl-codes");
  WriteText(dir / "r.json", "{}");
  const std::string r = (dir / "r.json").string();
  ExpectFail(Aalab("compare " + r + " " + r + " --bogus"), 2, {"--bogus"}, "compare unknown option");
  ExpectFail(Aalab("compare " + r), 2, {"current"}, "compare missing argument");
  ExpectFail(Aalab("same-results " + r + " " + r + " --bogus"), 2, {"--bogus"}, "same-results unknown option");
  ExpectFail(Aalab("run --bogus"), 1, {"--bogus"}, "run unknown option");
  ExpectFail(Aalab("export " + r + " --out " + (dir / "x").string() + " --zoom 0"), 1, {"--zoom", "1..32"}, "zoom 0");
  ExpectFail(Aalab("run --seed=-1 --out " + (dir / "x").string()), 1, {"--seed", "not a whole number >= 0"}, "seed -1");
  ExpectFail(Aalab("render --scene circle --seed=-5 --out " + (dir / "x.png").string()), 1, {"--seed"}, "render seed");
  ExpectFail(Aalab("run --seed 18446744073709551616 --out " + (dir / "x").string()), 1, {"--seed", "larger than"},
             "seed 2^64");
  EXPECT_FALSE(fs::exists(dir / "x"));
  const CmdResult h = Aalab("history");
  EXPECT_EQ(h.code, 1) << h.output;
  EXPECT_NE(h.output.find("'aalab history' needs a sub-command (add, report)"), std::string::npos) << h.output;
  EXPECT_EQ(h.output.find("same-results"), std::string::npos) << h.output;  // not the top-level list
  // A FIFO, a folder, a device where a file is expected: said as what they are.
  ASSERT_EQ(::mkfifo((dir / "pipe.json").c_str(), 0644), 0);
  ExpectFail(Aalab("run --scenes " + (dir / "pipe.json").string() + " --out " + (dir / "x").string()), 1,
             {"is not a regular file"}, "fifo scene");
  // history and merge-gpu read their FIFO argument without ever blocking on it.
  ExpectFail(Aalab("history report --db " + (dir / "pipe.json").string() + " --out " + (dir / "h").string()), 1,
             {"history database", "is a FIFO (named pipe)"}, "fifo history db");
  ExpectFail(Aalab("history add " + r + " --db " + (dir / "pipe.json").string()), 1,
             {"history database", "is a FIFO (named pipe)"}, "fifo history add db");
  ExpectFail(Aalab("export-sequences " + (dir / "pipe.json").string() + " --out " + (dir / "x").string()), 1,
             {"is a FIFO (named pipe), not a run folder"}, "fifo export-sequences");
  WriteText(dir / "s" / "mesh.json",
            R"({"name": "m", "effects": ["unlit"], "camera": {"type": "orthographic", "position": [0,0,10], )"
            R"("look_at": [0,0,0], "height": 4}, "materials": {"w": {"shading": "unlit"}}, )"
            R"("objects": [{"shape": "mesh", "file": "dir.obj", "material": "w"}]})");
  fs::create_directories(dir / "s" / "dir.obj");
  ExpectFail(Aalab("run --scenes " + (dir / "s" / "mesh.json").string() + " --out " + (dir / "x").string()), 1,
             {"dir.obj' is a folder"}, "folder mesh");
  fs::remove_all(dir);
}

TEST(NothingLost, TheDecodeBudgetBoundsEveryImageRead) {
  const fs::path dir = TempDir("nl-budget");
  Image8 img(1200, 1000, 4, 255);  // 1.2 megapixels
  WriteImage8((dir / "big.png").string(), img);
  ExpectFail(
      RunCommand("AALAB_DECODE_BUDGET_MP=1 " + std::string(AALAB_BINARY_DIR) + "/aalab apply --method fxaa1-p3 " +
                 (dir / "big.png").string() + " " + (dir / "out.png").string() + " 2>&1"),
      1, {"big.png' (1200000 pixels)", "past the budget of 1000000", "AALAB_DECODE_BUDGET_MP"}, "budget");
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  EXPECT_EQ(RunCommand("AALAB_DECODE_BUDGET_MP=2 " + std::string(AALAB_BINARY_DIR) + "/aalab apply --method fxaa1-p3 " +
                       (dir / "big.png").string() + " " + (dir / "out.png").string() + " 2>&1")
                .code,
            0);
  ExpectFail(
      RunCommand("AALAB_DECODE_BUDGET_MP=lots " + std::string(AALAB_BINARY_DIR) + "/aalab apply --method fxaa1-p3 " +
                 (dir / "big.png").string() + " " + (dir / "o2.png").string() + " 2>&1"),
      1, {"AALAB_DECODE_BUDGET_MP='lots' must be a whole number of megapixels"}, "bad budget");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
