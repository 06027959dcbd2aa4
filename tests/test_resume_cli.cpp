// fibra run --resume DIR: a run killed (SIGKILL, nothing written at the end) or stopped
// (SIGTERM) part-way and resumed ends bitwise where the uninterrupted run ends: final state,
// history (but for the columns that time or count the broadphase's work, docs/SCENE.md), frames;
// a directory that holds no run, a corrupt checkpoint and mixed options are refused (exit 2).
#include "scene_test_util.h"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <csignal>
#include <set>
#include <string>
#include <vector>

using namespace fibra;
using namespace fibra::test;
using Json = nlohmann::json;

namespace {

const std::set<std::string> kRunDependent{"wall_s", "contact.broadphase_rebuilds",
                                          "contact.candidate_pairs"};

// The history without the columns that depend on the run rather than on the state.
std::vector<std::vector<std::string>> history(const std::string& dir) {
  auto rows = readCsv(dir + "/history.csv");
  REQUIRE(!rows.empty());
  std::vector<size_t> keep;
  for (size_t i = 0; i < rows[0].size(); ++i)
    if (!kRunDependent.count(rows[0][i])) keep.push_back(i);
  for (auto& row : rows) {
    std::vector<std::string> kept;
    for (size_t i : keep) kept.push_back(i < row.size() ? row[i] : "");
    row = kept;
  }
  return rows;
}

// Starts `fibra run SCENE --out OUT`, sends `signal` once `rows` increments have converged,
// and returns the exit status (256 + signal when the signal ended it).
int stopAfter(const std::string& scene, const std::string& out, const std::string& log, int rows,
              int signal) {
  const pid_t pid = startFibra({"run", scene, "--out", out, "--threads", "1", "--quiet"}, log);
  bool reached = false;
  for (int waited = 0; waited < 60000 && !reached; waited += 5) {
    const std::string part = out + "/history.csv.part";
    reached = fs::exists(part) && readCsv(part).size() >= size_t(rows) + 1;
    if (!reached) ::usleep(5000);
  }
  ::kill(pid, reached ? signal : SIGKILL);
  const int status = waitStatusWithin(pid, 60);
  REQUIRE(reached);
  return status;
}

}  // namespace

TEST_CASE("fibra run --resume: a run killed or stopped part-way ends bitwise where the uninterrupted one ends") {
  TempDir scratch("cli_resume");
  fs::create_directories(scratch.path());
  const std::string scene = sourcePath("samples/bundle_squeeze.json");
  const std::string full = scratch / "full";
  const RunResult ref = runFibra({"run", scene, "--out", full, "--threads", "1", "--quiet"}, scratch);
  REQUIRE(ref.status == 0);
  const auto fullHistory = history(full);
  REQUIRE(fullHistory.size() == 11);  // header and 10 increments

  for (const int signal : {SIGKILL, SIGTERM}) {
    CAPTURE(signal);
    const std::string out = scratch / ("stopped_" + std::to_string(signal));
    const int status = stopAfter(scene, out, scratch / "stopped.log", 3, signal);
    CHECK(status == (signal == SIGKILL ? 256 + SIGKILL : 128 + SIGTERM));
    CHECK(fs::exists(out + "/resume_state.bin"));
    CHECK(fs::exists(out + "/resume_scene.json"));

    if (signal == SIGTERM) {
      // A resume killed in its turn leaves history.csv (of the first stop) beside the newer
      // history.csv.part: the next resume continues the newer.
      const pid_t pid = startFibra({"run", "--resume", out, "--threads", "1"}, scratch / "r.log");
      bool more = false;
      for (int waited = 0; waited < 60000 && !more; waited += 5) {
        const std::string part = out + "/history.csv.part";
        more = fs::exists(part) && readCsv(part).size() >= 7;
        if (!more) ::usleep(5000);
      }
      ::kill(pid, SIGKILL);
      waitStatus(pid);
      REQUIRE(more);
      CHECK(fs::exists(out + "/history.csv"));
    }
    const RunResult resumed = runFibra({"run", "--resume", out, "--threads", "1"}, scratch);
    CAPTURE(resumed.output);
    REQUIRE(resumed.status == 0);
    CHECK(resumed.output.find("fibra: resuming " + out + " at t = ") != std::string::npos);
    CHECK(readFile(out + "/final_state.csv") == readFile(full + "/final_state.csv"));
    CHECK(history(out) == fullHistory);
    if (signal == SIGKILL) {  // the same frames (SIGTERM adds one at the state it stopped at)
      CHECK(readFile(out + "/result.pvd") == readFile(full + "/result.pvd"));
      int frames = 0;
      for (const auto& entry : fs::directory_iterator(full))
        if (entry.path().extension() == ".vtu") {
          CAPTURE(entry.path().filename());
          CHECK(readFile(entry.path()) == readFile(out + "/" + entry.path().filename().string()));
          ++frames;
        }
      CHECK(frames == 33);  // 11 frames of fibres, contacts and tools
    }
    for (const auto& entry : fs::directory_iterator(out))
      CHECK(entry.path().extension() != ".part");
    // Resuming a finished run solves nothing and changes no result.
    const RunResult again = runFibra({"run", "--resume", out, "--threads", "1"}, scratch);
    CHECK(again.status == 0);
    CHECK(history(out) == fullHistory);
    CHECK(readFile(out + "/final_state.csv") == readFile(full + "/final_state.csv"));
  }
}

TEST_CASE("fibra run --resume: no run, a corrupt checkpoint or mixed options are refused with exit 2") {
  TempDir scratch("cli_resume_bad");
  fs::create_directories(scratch.path());
  const std::string empty = scratch / "empty";
  fs::create_directories(empty);
  const auto refused = [&](const std::vector<std::string>& args, const std::string& message) {
    CAPTURE(message);
    const RunResult r = runFibra(args, scratch);
    CAPTURE(r.output);
    CHECK(r.status == 2);
    CHECK(r.output.find(message) != std::string::npos);
  };
  refused({"run", "--resume", scratch / "none"}, "--resume: no directory");
  refused({"run", "--resume", empty}, "resume_state.bin: missing: '" + empty +
                                          "' is not the directory of a fibra run");
  refused({"run", sourcePath("samples/cantilever.json"), "--resume", empty},
          "--resume: the scene is the one in DIR, give no scene file");
  refused({"run", "--out", empty, "--resume", empty}, "--out and --resume: give one of them");

  const std::string run = scratch / "run";
  REQUIRE(runFibra({"run", sourcePath("samples/cantilever.json"), "--out", run, "--quiet"},
                   scratch)
              .status == 0);
  // Missing history rows (a history cut short by hand) are not papered over.
  const std::string history = readFile(run + "/history.csv");
  std::string cut = history.substr(0, history.find('\n', history.find('\n') + 1) + 1);
  writeFile(run + "/history.csv", cut);
  refused({"run", "--resume", run}, "history.csv: its rows end at t = 0.1, before the checkpoint's "
                                    "t = 1 (rows are missing)");
  writeFile(run + "/history.csv", history);
  // A row cut by hand in the middle.
  writeFile(run + "/history.csv", history.substr(0, history.size() - 40));
  refused({"run", "--resume", run}, "is not a whole row after t = ");
  writeFile(run + "/history.csv", history);
  // A PVD cut short while later frames are on disk, a frame's file deleted.
  const std::string pvd = readFile(run + "/result.pvd");
  writeFile(run + "/result.pvd", pvd.substr(0, pvd.find("result_0005.vtu")) + "\"/>\n");
  refused({"run", "--resume", run}, "frames up to the checkpoint, but result_0");
  writeFile(run + "/result.pvd", pvd);
  const std::string frame = readFile(run + "/result_0004.vtu");
  fs::remove(run + "/result_0004.vtu");
  refused({"run", "--resume", run}, "lists frame 4, whose result_0004.vtu is missing");
  writeFile(run + "/result_0004.vtu", frame);
  // A checkpoint without its scene: a run written by a program embedding fibra.
  const std::string kept = readFile(run + "/resume_scene.json");
  fs::remove(run + "/resume_scene.json");
  refused({"run", "--resume", run}, "the checkpoint is there but not the scene");
  writeFile(run + "/resume_scene.json", kept);
  std::string state = readFile(run + "/resume_state.bin");
  state[state.size() / 2] = char(state[state.size() / 2] ^ 1);
  writeFile(run + "/resume_state.bin", state);
  refused({"run", "--resume", run}, "resume_state.bin: the file is corrupt (checksum)");
  writeFile(run + "/resume_state.bin", state.substr(0, 40));
  refused({"run", "--resume", run}, "resume_state.bin: the file is truncated");
  // A scene with output.checkpoint false keeps neither file.
  Json scene = Json::parse(readFile(sourcePath("samples/roller_drag.json")), nullptr, true, true);
  scene["output"]["checkpoint"] = false;
  writeFile(scratch / "plain.json", scene.dump());
  const std::string plain = scratch / "plain";
  REQUIRE(runFibra({"run", scratch / "plain.json", "--out", plain, "--quiet"}, scratch).status == 0);
  CHECK(!fs::exists(plain + "/resume_state.bin"));
  CHECK(!fs::exists(plain + "/resume_scene.json"));
  refused({"run", "--resume", plain}, "is not the directory of a fibra run, or its scene has "
                                      "output.checkpoint false");
}

TEST_CASE("fibra run: two runs cannot write into one directory at once") {
  TempDir scratch("cli_lock");
  fs::create_directories(scratch.path());
  const std::string out = scratch / "out";
  const pid_t first = startFibra({"run", sourcePath("samples/bundle_squeeze.json"), "--out", out,
                                  "--threads", "1", "--quiet"},
                                 scratch / "first.log");
  bool running = false;
  for (int waited = 0; waited < 60000 && !running; waited += 5) {
    running = fs::exists(out + "/history.csv.part");
    if (!running) ::usleep(5000);
  }
  const RunResult second =
      runFibra({"run", sourcePath("samples/cantilever.json"), "--out", out, "--quiet"}, scratch);
  const RunResult resume = runFibra({"run", "--resume", out, "--quiet"}, scratch);
  ::kill(first, SIGKILL);
  waitStatus(first);
  REQUIRE(running);
  for (const RunResult& r : {second, resume}) {
    CAPTURE(r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find("another fibra run is writing into '" + out + "'") != std::string::npos);
  }
  // The first run's files were left alone, and once it is gone the directory is free again.
  CHECK(readFile(out + "/resume_scene.json") ==
        readFile(sourcePath("samples/bundle_squeeze.json")));
  CHECK(runFibra({"run", "--resume", out, "--threads", "1", "--quiet"}, scratch).status == 0);
}
