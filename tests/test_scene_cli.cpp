// The fibra program end to end: bad input (exit 2, a message naming file, field and problem, no
// output directory), usage errors, solved samples (every file written and consistent with the
// others and with the mechanics), a failing increment (exit 1) and Ctrl-C (exit 130 with the last
// converged state on disk).
#include "bench/elastica.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <regex>

using namespace fibra::test;
using Json = nlohmann::json;

namespace {

// Index of a named column in a CSV header (fails the test when it is missing).
size_t columnIndex(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  REQUIRE_MESSAGE(it != header.end(), "no column " << name);
  return size_t(it - header.begin());
}

Json sampleJson(const std::string& name) {
  return Json::parse(readFile(sourcePath("samples/" + name + ".json")), nullptr, true, true);
}

// Column `name` of a CSV's rows (header first) as numbers, one per data row.
std::vector<double> column(const std::vector<std::vector<std::string>>& rows,
                           const std::string& name) {
  const auto& header = rows.at(0);
  const size_t c = std::find(header.begin(), header.end(), name) - header.begin();
  REQUIRE(c < header.size());
  std::vector<double> v;
  for (size_t i = 1; i < rows.size(); ++i) v.push_back(std::stod(rows[i].at(c)));
  return v;
}

// (timestep, file) of every DataSet of a PVD.
std::vector<std::pair<std::string, std::string>> pvdFrames(const std::string& path) {
  const std::string pvd = readFile(path);
  const std::regex dataset("<DataSet timestep=\"([^\"]+)\" part=\"0\" file=\"([^\"]+)\"/>");
  std::vector<std::pair<std::string, std::string>> frames;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset);
       it != std::sregex_iterator(); ++it)
    frames.emplace_back((*it)[1], (*it)[2]);
  return frames;
}

// The final-state row of `fibre`'s node `node`.
std::vector<std::string> stateRow(const std::string& path, const std::string& fibre, int node) {
  for (const auto& row : readCsv(path))
    if (row.size() == 11 && row[0] == fibre && row[1] == std::to_string(node)) return row;
  FAIL("no row for node " << node << " of " << fibre << " in " << path);
  return {};
}

void checkNoPartFiles(const std::string& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) CHECK(entry.path().extension() != ".part");
}

}  // namespace

TEST_CASE("fibra: a bad scene exits 2 with file, field and reason, and creates nothing") {
  TempDir scratch("cli_bad");
  const std::string scene = sourcePath("samples/bad/negative_radius.json");
  const RunResult r = runFibra({"run", scene, "--out", scratch / "out"}, scratch);
  CHECK(r.status == 2);
  CHECK(r.output == "fibra: error: " + scene + ": fibres[0].radius: must be > 0, got -1\n");
  CHECK_FALSE(fs::exists(scratch / "out"));
}

TEST_CASE("fibra: a self-contact separation that would have no effect exits 2 from run and check") {
  TempDir scratch("cli_self_separation");
  fs::create_directories(scratch.path());
  Json j = sampleJson("cantilever");  // one fibre, 'beam', 10 mm long
  j["contact"] = {{"self_contact", true}, {"self_contact_separation", 100}};
  const std::string longer = scratch / "longer.json";
  writeFile(longer, j.dump());
  j["contact"] = {{"self_contact_separation", 0.5}};
  const std::string off = scratch / "off.json";
  writeFile(off, j.dump());
  const std::pair<std::string, std::string> cases[] = {
      {longer,
       "must be less than the shortest fibre's length, 10 mm (fibre 'beam'), got 100: with "
       "self-contact on, no two points of that fibre are that far apart along it, so it would pass "
       "through itself unseen; give a separation below 10 mm, or leave it out for the derived "
       "default"},
      {off,
       "given (0.5 mm) while self_contact is off (false, or absent: its default), where it has no "
       "effect; set \"self_contact\": true, or remove the separation"},
  };
  for (const auto& [scene, reason] : cases) {
    CAPTURE(scene);
    const std::string expected =
        "fibra: error: " + scene + ": contact.self_contact_separation: " + reason + "\n";
    const RunResult r = runFibra({"run", scene, "--out", scratch / "out"}, scratch);
    CHECK(r.status == 2);
    CHECK(r.output == expected);
    CHECK_FALSE(fs::exists(scratch / "out"));
    const RunResult c = runFibra({"check", scene}, scratch);
    CHECK(c.status == 2);
    CHECK(c.output == expected);
  }
}

TEST_CASE("fibra describe prints the scene's stages, a bad scene or a bad call exits 2") {
  TempDir scratch("cli_describe");
  const RunResult r = runFibra({"describe", sourcePath("samples/roller_drag.json")}, scratch);
  CHECK(r.status == 0);
  CHECK(r.output.starts_with("### detect (loop A)\n"));
  CHECK(r.output.find("| tool contact law |") != std::string::npos);
  CHECK(r.output.find("fibre contact law") == std::string::npos);  // the roller scene has no
                                                                   // fibre-fibre contact
  const std::string bad = sourcePath("samples/bad/negative_radius.json");
  const RunResult b = runFibra({"describe", bad}, scratch);
  CHECK(b.status == 2);
  CHECK(b.output == "fibra: error: " + bad + ": fibres[0].radius: must be > 0, got -1\n");
  const RunResult none = runFibra({"describe"}, scratch);
  CHECK(none.status == 2);
  CHECK(none.output.starts_with("fibra: describe: expected exactly one scene file\n"));
  const RunResult option = runFibra({"check", bad, "--out", "x"}, scratch);
  CHECK(option.status == 2);
  CHECK(option.output.starts_with(
      "fibra: check: unknown option '--out' (it takes a scene file only)\n"));
}

TEST_CASE("fibra: usage errors exit 2 and create nothing, --help exits 0") {
  TempDir scratch("cli_usage");
  const std::string scene = sourcePath("samples/cantilever.json"), out = scratch / "out";
  fs::create_directories(scratch.path());
  writeFile(scratch / "file", "");
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"run", scene}, "fibra: missing --out DIR\n"},
      {{"run", "--out", out}, "fibra: missing the scene file\n"},
      {{"run", scene, "--out", out, "--threads", "0"},
       "fibra: --threads: expected a positive integer, got '0'\n"},
      {{"run", scene, "--out", out, "--threads", "2x"},
       "fibra: --threads: expected a positive integer, got '2x'\n"},
      {{"run", scene, "--out", out, "--bogus"}, "fibra: unknown option '--bogus'\n"},
      {{"run", scene, scene, "--out", out},
       "fibra: more than one scene file ('" + scene + "', '" + scene + "')\n"},
      {{"run", scene, "--out", scratch / "file"},
       "fibra: --out: '" + scratch / "file" + "' exists and is not a directory\n"},
      {{"run", scene, "--out", out, "--trace", scratch / "nowhere/t.json"},
       "fibra: --trace: no directory '" + scratch / "nowhere" + "'\n"},
      {{"walk"}, "fibra: unknown command 'walk'\n"},
      {{}, "fibra: missing command\n"},
  };
  for (const auto& [args, message] : cases) {
    CAPTURE(message);
    const RunResult r = runFibra(args, scratch);
    CHECK(r.status == 2);
    CHECK(r.output.starts_with(message + "usage: fibra run SCENE.json --out DIR"));
    CHECK_FALSE(fs::exists(out));
  }
  const RunResult help = runFibra({"--help"}, scratch);
  CHECK(help.status == 0);
  CHECK(help.output.starts_with(
      "usage: fibra run SCENE.json --out DIR [--threads N] [--trace FILE]"));
}

TEST_CASE(
    "fibra: the cantilever sample writes a consistent series, history, final state and trace") {
  TempDir scratch("cli_cantilever");
  const std::string out = scratch / "out", trace = scratch / "trace.json";
  const RunResult r = runFibra({"run", sourcePath("samples/cantilever.json"), "--out", out,
                                "--threads", "2", "--trace", trace, "--verbose"},
                               scratch);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("step 1/1  increment 10/10  t = 1 ") != std::string::npos);
  CHECK(r.output.find("iteration  1  residual") != std::string::npos);  // --verbose
  // a direct solve, no contact, full steps: the residual's largest component and nothing else
  CHECK(std::regex_search(r.output, std::regex(R"(iteration  1  residual [0-9.e+-]+  largest at fibre )"
                                               R"('[^']+' node \d+ (x|y|z|g[12][xyz])\n)")));
  CHECK(r.output.find("gmres") == std::string::npos);
  CHECK(r.output.find("active") == std::string::npos);

  // Frames: the initial state and the ten increments, each listed once with its time.
  const auto frames = pvdFrames(out + "/result.pvd");
  REQUIRE(frames.size() == 11);
  CHECK(frames.front() == std::pair<std::string, std::string>{"0", "result_0000.vtu"});
  CHECK(frames.back() == std::pair<std::string, std::string>{"1", "result_0010.vtu"});
  for (const auto& [time, file] : frames)
    CHECK(readFile(out + "/" + file).find("NumberOfPoints=\"" + std::to_string(21 * 13) + "\"") !=
          std::string::npos);

  const auto history = readCsv(out + "/history.csv");
  REQUIRE(history.size() == 11);
  CHECK(history[0] ==
        std::vector<std::string>{
            "time", "step", "increment", "load_factor", "iterations", "total_iterations",
            "cutbacks", "sub_increments", "smallest_increment", "predicted",
            "predictor_retries", "normal_retries", "damped_steps", "residual", "wall_s",
            "reaction.beam.start.fx", "reaction.beam.start.fy",
            "reaction.beam.start.fz", "reaction.beam.start.mx", "reaction.beam.start.my",
            "reaction.beam.start.mz", "energy.strain", "energy.external", "energy.supports",
            "energy.contact_normal", "energy.friction", "energy.tools", "energy.stabilisation",
            "energy.error", "linear.factorisations", "linear.solves", "linear.fallbacks",
            "linear.krylov_iterations", "linear.krylov_max", "linear.krylov_failures",
            "probe.tip.x", "probe.tip.y", "probe.tip.z"});
  const std::vector<double> increments = column(history, "increment");
  for (size_t i = 0; i < increments.size(); ++i) CHECK(increments[i] == i + 1);
  CHECK(history.back()[0] == "1");

  // The final state is the last row's state to the last digit, and the tip is the elastica's.
  const auto tip = stateRow(out + "/final_state.csv", "beam", 20);
  const size_t px = columnIndex(history[0], "probe.tip.x");
  CHECK(tip[2] == history.back()[px]);
  CHECK(tip[3] == history.back()[px + 1]);
  CHECK(readCsv(out + "/final_state.csv").size() == 22);
  const Eigen::Vector2d ref = fibra::elasticaTip(3) * 10;
  CHECK(std::abs((10 - std::stod(tip[2])) / (10 - ref.x()) - 1) < 0.005);
  CHECK(std::abs(std::stod(tip[3]) / ref.y() - 1) < 0.005);

  CHECK(readFile(trace).starts_with("{\"displayTimeUnit\""));
  const auto stages = readCsv(scratch / "trace.stages.csv");
  REQUIRE(stages.size() >= 2);
  CHECK(stages[0].at(0) == "stage");
  CHECK(std::find_if(stages.begin(), stages.end(),
                     [](const auto& row) { return row.at(0) == "beam evaluation"; }) != stages.end());
  checkNoPartFiles(out);
}

TEST_CASE(
    "fibra: the roll-up sample closes the beam into a circle, a frame every second increment") {
  TempDir scratch("cli_rollup");
  const std::string out = scratch / "out";
  REQUIRE(runFibra({"run", sourcePath("samples/rollup.json"), "--out", out}, scratch).status == 0);
  CHECK(pvdFrames(out + "/result.pvd").size() == 6);  // t = 0, 0.2, ..., 1
  const auto tip = stateRow(out + "/final_state.csv", "beam", 40);
  CHECK(std::hypot(std::stod(tip[2]), std::stod(tip[3]), std::stod(tip[4])) < 0.005 * 10);
}

TEST_CASE("fibra: the helix sample's end reactions balance and follow the pull") {
  TempDir scratch("cli_helix");
  const std::string out = scratch / "out";
  REQUIRE(runFibra({"run", sourcePath("samples/helix.json"), "--out", out}, scratch).status == 0);
  const auto history = readCsv(out + "/history.csv");
  REQUIRE(history.size() == 11);
  const std::vector<double> start = column(history, "reaction.coil.start.fz");
  const std::vector<double> end = column(history, "reaction.coil.end.fz");
  const std::vector<double> steps = column(history, "step");
  for (size_t i = 0; i < end.size(); ++i) {
    CAPTURE(i);
    CHECK(std::abs(start[i] + end[i]) < 1e-9 * std::abs(end[i]));  // no load: the two ends balance
    CHECK(steps[i] == (i < 5 ? 1 : 2));
  }
  // Pulled to 1 mm at t = 1, back to 0.5 mm at t = 2: the end force follows.
  CHECK(std::abs(end[4]) > std::abs(end[9]));
  CHECK(std::abs(end[9]) > std::abs(end[0]));
}

TEST_CASE("fibra: the roller sample slides at mu R_N, with contact columns and contact files") {
  TempDir scratch("cli_roller");
  const std::string out = scratch / "out";
  REQUIRE(runFibra({"run", sourcePath("samples/roller_drag.json"), "--out", out}, scratch).status ==
          0);
  const auto history = readCsv(out + "/history.csv");
  REQUIRE(history.size() == 11);
  const std::vector<double> fy = column(history, "tool.roller.fy"),
                            fz = column(history, "tool.roller.fz"),
                            tools = column(history, "contact.tool_elements"),
                            ratio = column(history, "contact.max_penetration_ratio");
  // both end loads on the roller; then Coulomb, in slip; stick first
  CHECK(fz.back() == doctest::Approx(-0.02).epsilon(1e-3).scale(0));
  CHECK(fy.back() == doctest::Approx(0.2 * 0.02).epsilon(0.01).scale(0));
  CHECK(fy.front() < 0.5 * fy.back());
  for (size_t i = 0; i < tools.size(); ++i) {
    CHECK(tools[i] > 0);
    CHECK(ratio[i] <= 1);
  }
  CHECK(pvdFrames(out + "/result.pvd").size() == 11);  // part 0, the fibres
  CHECK(readFile(out + "/result.pvd").find("part=\"1\" file=\"result_contacts_0010.vtu\"") !=
        std::string::npos);
  CHECK(fs::exists(fs::path(out) / "result_contacts_0010.vtu"));
  checkNoPartFiles(out);
}

TEST_CASE("fibra: a failing increment exits 1 and writes the last converged state") {
  TempDir scratch("cli_fail");
  fs::create_directories(scratch.path());
  Json scene = sampleJson("cantilever");
  scene["loads"][0]["vector"][1] = -100.0;  // PL^2/EI ~ 3e4 in one increment of two iterations
  scene["steps"][0] = {
      {"end_time", 1}, {"increments", 1}, {"max_iterations", 2}, {"max_cutbacks", 0}};
  writeFile(scratch / "fail.json", scene.dump());
  const std::string out = scratch / "out";
  const RunResult r = runFibra({"run", scratch / "fail.json", "--out", out}, scratch);
  CHECK(r.status == 1);
  CHECK(r.output.find("fibra: step 1/1, increment 1 failed: ") != std::string::npos);
  CHECK(r.output.find("fibra: failed, wrote the last converged state: t = 0,") !=
        std::string::npos);
  // The summary counts the failed increment's iterations (2) and no cutback (its only attempt
  // was the failure).
  CHECK(r.output.find("t = 0, 0 increments, 2 Newton iterations, 0 cutbacks,") !=
        std::string::npos);
  CHECK(readCsv(out + "/history.csv").size() == 1);   // the header: no increment converged
  CHECK(pvdFrames(out + "/result.pvd").size() == 1);  // the initial state, once
  const auto tip = stateRow(out + "/final_state.csv", "beam", 20);
  CHECK(tip[2] == "10");  // still at the reference
  CHECK(tip[3] == "0");
  checkNoPartFiles(out);
}

namespace {

// Runs a long cantilever, sends `signal` once two increments have converged, and checks that
// the run ends with `status` and `message`, the last converged state and the whole history on
// disk and no .part file.
void stopsCleanly(int signal, int expectedStatus, const std::string& message) {
  TempDir scratch("cli_cancel_" + std::to_string(signal));
  fs::create_directories(scratch.path());
  Json scene = sampleJson("cantilever");
  scene["steps"][0] = {{"end_time", 1}, {"increments", 100000}, {"output_every", 20000}};
  writeFile(scratch / "long.json", scene.dump());
  const std::string out = scratch / "out";
  struct Child {  // killed if the test stops before it has ended
    pid_t pid;
    bool ended = false;
    ~Child() {
      if (!ended) waitStatusWithin(pid, 0);
    }
  } child{
      startFibra({"run", scratch / "long.json", "--out", out, "--threads", "1"}, scratch / "log")};
  // Interrupt once two increments have converged.
  bool running = false;
  for (int waited = 0; waited < 60000 && !running; waited += 5) {
    running = readCsv(out + "/history.csv.part").size() >= 3;
    if (!running) ::usleep(5000);
  }
  REQUIRE(running);
  ::kill(child.pid, signal);
  const int status = waitStatusWithin(child.pid, 60);
  child.ended = true;
  CHECK(status == expectedStatus);
  CHECK(readFile(scratch / "log").find(message) != std::string::npos);

  const auto history = readCsv(out + "/history.csv");
  REQUIRE(history.size() >= 3);
  CHECK(history.size() < 100001);
  const auto tip = stateRow(out + "/final_state.csv", "beam", 20);
  const size_t px = columnIndex(history[0], "probe.tip.x");
  CHECK(tip[2] == history.back()[px]);  // the final state is the last converged increment's
  CHECK(tip[3] == history.back()[px + 1]);
  CHECK(tip[4] == history.back()[px + 2]);
  const auto frames = pvdFrames(out + "/result.pvd");
  REQUIRE(frames.size() == 2);  // the initial state and the state it stopped at
  CHECK(frames.back().first == history.back()[0]);
  checkNoPartFiles(out);
}

}  // namespace

TEST_CASE("fibra: Ctrl-C stops at the last converged state, writes it and exits 130") {
  stopsCleanly(SIGINT, 130, "fibra: interrupted, wrote the last converged state: t = ");
}

TEST_CASE("fibra: SIGTERM stops like Ctrl-C, with the whole history, and exits 143") {
  const std::string message = "fibra: terminated (SIGTERM), wrote the last converged state: t = ";
  stopsCleanly(SIGTERM, 143, message);
  // The documentation shows that message and status, timeout's own 124, and the resume.
  std::string doc = readFile(sourcePath("docs/SCENE.md"));
  for (char& c : doc) c = c == '\n' ? ' ' : c;
  for (const std::string& text :
       {"`" + message, std::string("and exits 143. `timeout` itself then exits 124"),
        std::string("`timeout --preserve-status` passes fibra's 143 on"),
        std::string("`fibra run --resume /tmp/x [--threads N]")}) {
    CAPTURE(text);
    CHECK(doc.find(text) != std::string::npos);
  }
}
