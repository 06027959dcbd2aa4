// fibra study end to end (app/study.h): the cantilever's tip error against the mesh (it must
// fall as the elements grow, and the finest mesh must give the elastica's tip), the CSV's rows
// and the picture, errors sampled at other pseudo-times (increments), a categorical knob with
// its reference, failed variants, and bad input refused before anything runs (exit 2).
#include "bench/elastica.h"
#include "io/plot.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

using namespace fibra::test;
using Json = nlohmann::json;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool isPng(const std::string& path) {
  const std::string bytes = readFile(path);
  return bytes.size() > 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

// study.csv as rows of named cells.
struct StudyCsv {
  std::vector<std::vector<std::string>> rows;  // header first
  std::string at(size_t row, const std::string& column) const {
    const auto it = std::find(rows[0].begin(), rows[0].end(), column);
    REQUIRE_MESSAGE(it != rows[0].end(), "no column " << column);
    const size_t c = size_t(it - rows[0].begin());
    return c < rows[row].size() ? rows[row][c] : "";  // a trailing empty cell is not read
  }
  double number(size_t row, const std::string& column) const { return std::stod(at(row, column)); }
};

const std::string kCantilever = sourcePath("samples/cantilever.json");

// The cantilever with `change` applied, written into `dir`.
std::string cantileverWith(const TempDir& dir, const std::function<void(Json&)>& change) {
  Json s = Json::parse(readFile(kCantilever), nullptr, true, true);
  change(s);
  fs::create_directories(dir.path());
  writeFile(dir / "scene.json", s.dump());
  return dir / "scene.json";
}

}  // namespace

TEST_CASE("study: the cantilever's tip error falls as the elements grow, against the finest") {
  TempDir dir("study_elements");
  const std::string out = dir / "study";
  const RunResult r =
      runFibra({"study", kCantilever, "--vary", "fibres[0].elements=2,4,8,16", "--observe",
                "probe.tip.y,probe.tip.x", "--out", out, "--threads", "1"},
               dir);
  const bool gnuplot = !fibra::findGnuplot().empty();
  REQUIRE_MESSAGE(r.status == (gnuplot ? 0 : 1), r.output);
  CHECK(contains(r.output, "reference fibres[0].elements=16 (the finest: the largest value of elements)"));
  CHECK(contains(r.output, "fibra: variant 4/4 fibres[0].elements=16: "));
  const StudyCsv csv{readCsv(out + "/study.csv")};
  REQUIRE(csv.rows.size() == 5);
  for (size_t i = 1; i <= 4; ++i) {
    CHECK(csv.at(i, "field") == "fibres[0].elements");
    CHECK(csv.at(i, "status") == "converged");
    CHECK(csv.at(i, "reference") == (i == 4 ? "1" : "0"));
    CHECK(csv.number(i, "iterations") > 0);
    CHECK(csv.number(i, "increments") == 10);
    CHECK(fs::exists(out + "/fibres[0].elements=" + csv.at(i, "value") + "/history.csv"));
  }
  CHECK(csv.number(4, "error_max") == 0);
  // Refining the mesh: each error (over the load path, and at the end) smaller than the last.
  for (const std::string column :
       {"error_probe.tip.y", "final_probe.tip.y", "error_probe.tip.x", "error_max"}) {
    CAPTURE(column);
    for (size_t i = 1; i < 3; ++i) CHECK(csv.number(i, column) > csv.number(i + 1, column));
    CHECK(csv.number(3, column) > 0);
  }
  CHECK(csv.number(3, "error_max") < 1e-3);  // 8 quadratic elements: 4e-4 measured
  // The reference's tip is the elastica's (PL^2/EI = 3, bench/elastica.h: x 7.4558, y -6.0325
  // mm) within 1e-3 of the displacement: fibra's beam stretches and shears where the elastica
  // does not (2.7e-4 measured on y, 4.3e-4 on L - x); 16 elements are within 1.2e-5 of 32.
  const Eigen::Vector2d tip = fibra::elasticaTip(3) * 10;
  CHECK(std::abs(csv.number(4, "value_probe.tip.y") / tip.y() - 1) < 1e-3);
  CHECK(std::abs((10 - csv.number(4, "value_probe.tip.x")) / (10 - tip.x()) - 1) < 1e-3);
  if (!gnuplot) {
    MESSAGE("gnuplot is not installed: the PNG is not checked (scripts/setup.sh installs it)");
    CHECK(contains(r.output, "gnuplot not found"));
    return;
  }
  CHECK(isPng(out + "/study.png"));
  const std::string script = readFile(out + "/study.gp");
  CHECK(contains(script, "set logscale y"));
  CHECK(contains(script, "\"8\"\n"));    // a labelled point
  CHECK(!contains(script, "\"16\"\n"));  // the reference is not drawn
}

TEST_CASE("study: increments compare curves at the reference's times, the ends agree") {
  TempDir dir("study_increments");
  const std::string out = dir / "study";
  const RunResult r = runFibra({"study", kCantilever, "--vary", "steps[0].increments=1,2,4,8",
                                "--observe", "probe.tip.y", "--out", out, "--threads", "1"},
                               dir);
  REQUIRE_MESSAGE(r.status <= 1, r.output);
  const StudyCsv csv{readCsv(out + "/study.csv")};
  REQUIRE(csv.rows.size() == 5);
  CHECK(csv.at(4, "reference") == "1");
  // An elastic dead load: the end state does not depend on the path's steps, the coarse
  // curves' chords do (interpolated between their rows at the reference's times, from the
  // initial state: one increment is a single chord, compared along the whole curve).
  for (size_t i = 1; i <= 3; ++i) CHECK(csv.number(i, "final_probe.tip.y") < 1e-10);
  CHECK(csv.number(1, "error_probe.tip.y") > csv.number(2, "error_probe.tip.y"));
  CHECK(csv.number(2, "error_probe.tip.y") > csv.number(3, "error_probe.tip.y"));
  CHECK(csv.number(3, "error_probe.tip.y") > 1e-4);
}

TEST_CASE("study: a categorical knob needs --reference, a failed variant is kept in the CSV") {
  TempDir dir("study_categorical");
  const std::string scene = cantileverWith(dir, [](Json& s) { s["solver"] = Json::object(); });
  const std::string out = dir / "study";
  const std::vector<std::string> vary{
      "study",     scene,         "--vary", "solver.strategy=direct,umfpack",
      "--observe", "probe.tip.y", "--out",  out};
  RunResult r = runFibra(vary, dir);
  CHECK(r.status == 2);
  CHECK_MESSAGE(contains(r.output,
                         "solver.strategy: the values are not all numbers: name the "
                         "reference with --reference V"),
                r.output);
  CHECK(!fs::exists(out));
  std::vector<std::string> withReference = vary;
  withReference.insert(withReference.end(), {"--reference", "direct"});
  r = runFibra(withReference, dir);
  CHECK_MESSAGE(r.status == 0, r.output);  // equal solutions: nothing on a log axis, a warning
  StudyCsv csv{readCsv(out + "/study.csv")};
  REQUIRE(csv.rows.size() == 3);
  CHECK(csv.at(1, "reference") == "1");
  CHECK(csv.number(2, "error_probe.tip.y") < 1e-9);
  // Two Newton iterations per attempt cannot solve an increment: that variant fails, stays in
  // the CSV without errors, and only a failed reference makes the study fail.
  r = runFibra({"study", kCantilever, "--vary", "steps[0].max_iterations=2,30", "--observe",
                "probe.tip.y", "--out", out},
               dir);
  CHECK_MESSAGE(r.status == 0, r.output);  // nothing to draw: no gnuplot needed
  CHECK(contains(r.output, "warning: steps[0].max_iterations=2 failed: left out"));
  csv = StudyCsv{readCsv(out + "/study.csv")};
  REQUIRE(csv.rows.size() == 3);
  CHECK(csv.at(1, "status") == "failed");
  CHECK(csv.at(1, "error_max").empty());
  CHECK(csv.at(2, "reference") == "1");
  r = runFibra({"study", kCantilever, "--vary", "steps[0].max_iterations=2,30", "--observe",
                "probe.tip.y", "--out", out, "--reference", "2"},
               dir);
  CHECK(r.status == 1);
  CHECK(contains(r.output, "error: the reference steps[0].max_iterations=2 failed"));
}

TEST_CASE("study: bad fields, values and columns exit 2 before anything runs or is written") {
  TempDir dir("study_errors");
  const std::string out = dir / "study";
  const auto study = [&](const std::string& vary, const std::string& observe = "probe.tip.y") {
    return runFibra({"study", kCantilever, "--vary", vary, "--observe", observe, "--out", out},
                    dir);
  };
  for (const auto& [vary, message] : std::vector<std::pair<std::string, std::string>>{
           {"contact.max_penetration=0.01,0.001",
            "--vary contact.max_penetration: " + kCantilever + " has no 'contact'"},
           {"fibres[1].elements=2,4", "has no 'fibres[1]'"},
           {"fibres[0].elemnts=2,4",
            "variant fibres[0].elemnts=2: " + kCantilever +
                ": fibres[0].elemnts: unknown field (did you mean 'elements'?)"},
           {"fibres[0].elements=4,0",
            "variant fibres[0].elements=0: " + kCantilever + ": fibres[0].elements: must be >= 1"},
           {"steps[0].damping=0,0.1", "which end of 'damping' is the finer is not known"}}) {
    const RunResult r = study(vary);
    CHECK_MESSAGE(r.status == 2, r.output);
    CHECK_MESSAGE(contains(r.output, message), r.output);
    CHECK(!fs::exists(out));
  }
  RunResult r = study("fibres[0].elements=2,4", "probe.tip.w");
  CHECK(r.status == 2);
  CHECK(contains(r.output, "--observe: unknown column 'probe.tip.w' (did you mean"));
  CHECK(!fs::exists(out));
  // Usage: exit 2 with the usage line.
  for (const auto& [vary, message] : std::vector<std::pair<std::string, std::string>>{
           {"fibres[0].elements=2", "--vary: give at least two values"},
           {"fibres[0]..elements=2,4", "--vary: expected a field path"},
           {"fibres[0].elements", "--vary: expected FIELD=V1,V2,..."},
           {"fibres[0].elements=2,2", "--vary: '2' twice"},
           {"fibres[0].elements=4,4.0", "--vary: '4.0' is the value of '4'"}}) {
    r = study(vary);
    CHECK_MESSAGE(r.status == 2, r.output);
    CHECK_MESSAGE(contains(r.output, message), r.output);
    CHECK(contains(r.output, "\nusage: fibra study SCENE.json --vary FIELD=V1,V2,..."));
  }
  r = runFibra({"study", kCantilever, "--vary", "fibres[0].elements=2,4", "--out", out}, dir);
  CHECK(r.status == 2);
  CHECK(contains(r.output, "study: missing --observe"));
  CHECK(!fs::exists(out));
}

TEST_CASE("study: without gnuplot the CSV is written and the exit status is 1") {
  TempDir dir("study_no_gnuplot");
  const std::string out = dir / "study";
  ::setenv("FIBRA_GNUPLOT", (dir / "no-gnuplot-here").c_str(), 1);
  const RunResult r = runFibra({"study", kCantilever, "--vary", "fibres[0].elements=2,4",
                                "--observe", "probe.tip.y", "--out", out},
                               dir);
  ::unsetenv("FIBRA_GNUPLOT");
  CHECK(r.status == 1);
  CHECK_MESSAGE(contains(r.output, "gnuplot not found"), r.output);
  CHECK(readCsv(out + "/study.csv").size() == 3);
  CHECK(fs::exists(out + "/study.gp"));
  CHECK(!fs::exists(out + "/study.png"));
}
