// The fibra program's terminal: --version, check, the default one line per increment, --quiet,
// the header and summary, and a re-run into a used output directory.
#include "fibra/version.h"
#include "scene_test_util.h"
#include "twisted_rod.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <map>
#include <regex>

using namespace fibra::test;

namespace {

// Lines of `text` that match `pattern` (from their start).
int countLines(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += std::regex_search(line, re) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("fibra --version prints the version of the build") {
  TempDir scratch("cli_version");
  const RunResult r = runFibra({"--version"}, scratch);
  CHECK(r.status == 0);
  CHECK(r.output == std::string("fibra ") + FIBRA_VERSION_STRING + "\n");
  CHECK(std::string(FIBRA_VERSION_STRING) ==
        std::to_string(FIBRA_VERSION_MAJOR) + "." + std::to_string(FIBRA_VERSION_MINOR));
}

TEST_CASE("fibra check validates a scene and prints its size without solving") {
  TempDir scratch("cli_check");
  const std::string scene = sourcePath("samples/bundle_squeeze.json");
  const RunResult r = runFibra({"check", scene}, scratch);
  CHECK(r.status == 0);
  CHECK(r.output.starts_with(std::string("fibra ") + FIBRA_VERSION_STRING + ": " + scene + "\n"));
  CHECK(countLines(r.output, R"(^  7 fibres, \d+ nodes, \d+ elements, \d+ DOFs$)") == 1);
  CHECK(countLines(r.output, R"(^  contact: fibre-fibre, p_max [0-9.e-]+ mm, mu 0.1, )") == 1);
  CHECK(countLines(r.output, R"(^  tools: 2$)") == 1);
  CHECK(countLines(r.output, R"(^    (bottom|top): plane, mu 0.1, p_max [0-9.e-]+ mm, 2 points per fibre element$)") == 2);
  CHECK(r.output.ends_with("fibra: " + scene + ": the scene is valid\n"));
  // A cylinder takes the points its curvature needs (systems/tool_detection.h): R = 0.1 mm
  // against elements of 0.0625 mm and p_max 1e-4 mm, 22.
  const RunResult y = runFibra({"check", sourcePath("samples/yarn_procedure.json")}, scratch);
  CHECK(y.status == 0);
  CHECK(countLines(y.output, R"(^    (bottom|top): cylinder, mu 0, p_max 0.0001 mm, 22 points per fibre element$)") == 2);
  CHECK(y.output.find("caps at") == std::string::npos);
  // Its fibres have bending stiffness (bending factor 0.1): no note. With Table 2's 0 and the
  // end sections turned a quarter turn with the full torsion, G J phi / L = 28 077 MPa x
  // 1.571e-8 mm^4 x (pi / 2) / 0.5 mm = 1.39e-3 N mm, noted (engine/torqued_strings.h).
  CHECK(countLines(y.output, "without bending stiffness") == 0);
  std::filesystem::create_directories(scratch.path());
  nlohmann::json strings = nlohmann::json::parse(
      readFile(sourcePath("samples/yarn_procedure.json")), nullptr, true, true);
  strings["materials"][0]["bending_factor"] = 0;
  strings["tables"]["twist"] = {{0, 0}, {2, 0}, {3, 1.5707963267948966}};
  writeFile(scratch / "strings.json", strings.dump());
  const RunResult z = runFibra({"check", scratch / "strings.json"}, scratch);
  CHECK(z.status == 0);
  CHECK(countLines(z.output, R"(^  note: 19 fibres \(yarn.f0, yarn.f1, yarn.f2, yarn.f3, \.\.\.\) without )"
                             R"(bending stiffness are twisted about their axis, up to 0.00139 N mm of )"
                             R"(torque \(yarn.f[0-9]+, R = 0.01 mm\): a string holds its straight state only up )"
                             R"(to about T R .*, beyond which it zigzags from node to node .*"Strings )"
                             R"(under torque"\)$)") == 1);
  CHECK(countLines(r.output, "without bending stiffness") == 0);
  // The roller sample with a roller 20x thinner and p_max 1e-5 mm: the 32 points of the cap leave
  // a sagitta of (0.25 mm x 0.0966 / 2)^2 / (8 x 0.05 mm) = 3.65e-4 mm = 36.5 p_max, said.
  nlohmann::json roller = nlohmann::json::parse(readFile(sourcePath("samples/roller_drag.json")),
                                                nullptr, true, true);
  roller["tools"][0]["radius"] = 0.05;
  roller["tools"][0]["max_penetration"] = 1e-5;
  writeFile(scratch / "thin_roller.json", roller.dump());
  const RunResult t = runFibra({"check", scratch / "thin_roller.json"}, scratch);
  CHECK(t.status == 0);
  CHECK(countLines(t.output, R"(^    roller: cylinder, mu 0.2, p_max 1e-05 mm, 32 points per fibre element$)") == 1);
  CHECK(countLines(t.output, R"(^    note: roller caps at 32 points per element: a fibre across it may be )"
                             R"(overlapped by up to 36.5 p_max between two points \(finer elements or a larger )"
                             R"(p_max bring it to 0.25\)$)") == 1);
  // The roller 0.05 mm thicker starts 0.05 mm inside the fibre (centreline 1.1 mm from the
  // axis, R = 0.1 mm), over its crest at s = 2 mm of the 4 mm fibre; 0.0004 mm thicker, 0.8 p_max:
  // in light contact, no warning. --quiet prints the warning alone.
  roller = nlohmann::json::parse(readFile(sourcePath("samples/roller_drag.json")), nullptr, true, true);
  roller["tools"][0]["radius"] = 1.05;
  roller["tools"][0]["max_penetration"] = 5e-4;
  writeFile(scratch / "inside_roller.json", roller.dump());
  const std::string inside = runFibra({"check", scratch / "inside_roller.json"}, scratch).output;
  CHECK(countLines(inside, R"(^    warning: roller overlaps the fibres by 0.05 mm \(100 p_max\) at the start, )"
                           R"(deepest at s = 2 mm along fibre 'f': the first increment has to push it )"
                           R"(out at once )") == 1);
  const RunResult quiet =
      runFibra({"run", scratch / "inside_roller.json", "--out", scratch / "inside", "--quiet"}, scratch);
  CHECK(countLines(quiet.output, R"(^    warning: roller overlaps the fibres by 0.05 mm)") == 1);
  roller["tools"][0]["radius"] = 1.0004;
  writeFile(scratch / "touching_roller.json", roller.dump());
  CHECK(runFibra({"check", scratch / "touching_roller.json"}, scratch).output.find("warning") ==
        std::string::npos);
  CHECK(countLines(r.output, "^step ") == 0);  // nothing solved
  const std::string bad = sourcePath("samples/bad/negative_radius.json");
  const RunResult b = runFibra({"check", bad}, scratch);
  CHECK(b.status == 2);
  CHECK(b.output == "fibra: error: " + bad + ": fibres[0].radius: must be > 0, got -1\n");
}

TEST_CASE("fibra check notes the fibres whose spin only friction holds") {
  // The bundle sample's straight fibres (along x, director g1 along z) are held at their two
  // end nodes in x and y only: their spin about x moves no held DOF. The spin turns g1 towards
  // -y and g2 towards -z, so holding g1y (or g2z) at an end holds it, and g1x, g1z or g2y do not.
  TempDir scratch("cli_spin");
  std::filesystem::create_directories(scratch.path());
  const std::string scene = sourcePath("samples/bundle_squeeze.json");
  const auto check = [&](const nlohmann::json& j, const char* name) {
    writeFile(scratch / name, j.dump());
    const RunResult r = runFibra({"check", scratch / name}, scratch);
    REQUIRE_MESSAGE(r.status == 0, r.output);
    return r.output;
  };
  const nlohmann::json sample = nlohmann::json::parse(readFile(scene), nullptr, true, true);
  CHECK(countLines(check(sample, "sample.json"),
                   R"(^  note: 7 fibres \(f0, f1, f2, f3, \.\.\.\) can spin freely: only )"
                   R"(friction holds their spin about their axis, none once all their )"
                   R"(contacts slip; if Newton stagnates, hold at an end a director component )"
                   R"(the spin turns \(docs/METHOD.md "Free spin"\)$)") == 1);
  for (const char* held : {"g1y", "g2z"}) {
    CAPTURE(held);
    nlohmann::json j = sample;
    for (auto& b : j["boundary_conditions"]) b["dofs"] = {"x", "y", held};
    CHECK(check(j, "gripped.json").find("note: ") == std::string::npos);
  }
  for (const char* held : {"g1x", "g1z", "g2y"}) {  // components the spin leaves alone
    CAPTURE(held);
    nlohmann::json j = sample;
    for (auto& b : j["boundary_conditions"]) b["dofs"] = {"x", "y", held};
    CHECK(countLines(check(j, "not_gripped.json"), R"(^  note: 7 fibres )") == 1);
  }
  // One fibre left free to spin: the singular.
  nlohmann::json one = sample;
  for (auto& b : one["boundary_conditions"])
    if (b["group"] != "f3.start" && b["group"] != "f3.end") b["dofs"] = {"x", "y", "g1y"};
  CHECK(countLines(check(one, "one.json"), R"(^  note: 1 fibre \(f3\) can spin freely: only )"
                                           R"(friction holds its spin about its axis, none once )"
                                           R"(all its contacts slip;)") == 1);
  // Held at every node (positions only): still free to spin.
  nlohmann::json all = one;
  all["boundary_conditions"].push_back({{"type", "pin"}, {"group", "f1.all"}});
  all["boundary_conditions"].erase(2);
  all["boundary_conditions"].erase(2);  // f1's two ends, now in the pin
  CHECK(countLines(check(all, "pinned.json"), R"(^  note: 2 fibres \(f1, f3\) can spin)") == 1);
  // No friction that can act: no note (without friction anywhere, or with every step's
  // friction factor 0).
  nlohmann::json frictionless = sample;
  frictionless["contact"]["friction"] = 0;
  for (auto& t : frictionless["tools"]) t["friction"] = 0;
  CHECK(check(frictionless, "frictionless.json").find("note: ") == std::string::npos);
  nlohmann::json factor = sample;
  factor["steps"][0]["friction_factor"] = 0;
  CHECK(check(factor, "factor.json").find("note: ") == std::string::npos);
}

TEST_CASE("fibra check and run show the pair rules, classes, contact laws and forced normals") {
  TempDir scratch("cli_pairs");
  const std::string scene = sourcePath("samples/forced_normals.json");
  const RunResult r = runFibra({"check", scene}, scratch);
  REQUIRE(r.status == 0);
  // Before, one line with "mu 0.1" (the largest rule's): the section's mu is 0, the warp-weft
  // rule's 0.1, and nothing said which pairs took which.
  for (const char* line :
       {"  contact: fibre-fibre, p_max 0.0005 mm, mu 0, theta_cross 20 deg, ",
        "  contact law: penalty 1 .. 10000 x E R, initial penalty E R, change <= x10, p_reg 0.5 "
        "p_max, step limit 10 p_max, g_T,max 0.0005 mm, friction tangent consistent, element "
        "placement weighted (Lobatto in the zones the acceptance refines), normals "
        "updated by loop B (Anderson memory 3 when unstable), frictionless parallel normals "
        "linearised in Newton once loop B diverges, every fibre normal linearised after a failed "
        "attempt (retried) or a slow loop B (kept while it converges; a failed linearised attempt "
        "goes back to loop B for the step), stick/slip "
        "held after 2 "
        "changes (tolerance 0.01)\n",
        "  contact classes: warp (3 fibres), weft (3 fibres)\n",
        "  contact pairs (other pairs: the section's mu, p_max and penalty above):\n"
        "    [warp, weft]: mu 0.1, p_max 0.0005 mm, penalty 1 .. 10000 x E R\n"
        "    within: mu 0, p_max 0.001 mm, penalty 1 .. 10000 x E R\n",
        "  forced normals: step 1 (initial_geometry) along [0, 0, 1]\n"}) {
    CAPTURE(line);
    CHECK(r.output.find(line) != std::string::npos);
  }
  // Other choices that change results, and a rule's own penalty bounds.
  nlohmann::json j = nlohmann::json::parse(readFile(scene), nullptr, true, true);
  j["contact"]["element_placement"] = "paper";
  j["contact"]["friction_tangent"] = "symmetrised";
  j["contact"]["initial_penalty"] = 100;
  j["contact"]["pairs"][0]["penalty_min"] = 0.01;
  j["contact"]["pairs"][0]["penalty_max"] = 50;
  j["contact"]["pairs"][1]["classes"] = "between";
  j["fibres"][5]["class"] = "";
  j["contact"]["follow_crossings"] = true;
  j["contact"]["facing_particles"] = false;
  j["contact"]["normal_update"] = "loop";
  j["solver"] = {{"strategy", "mumps"}, {"ordering", "metis"}, {"blr_tolerance", 1e-6}};
  j["steps"][0]["forced_normals"]["allowance"] = 0.2;
  writeFile(scratch / "choices.json", j.dump());
  const RunResult c = runFibra({"check", scratch / "choices.json"}, scratch);
  REQUIRE(c.status == 0);
  CHECK(c.output.find("initial penalty 100 N/mm, ") != std::string::npos);
  CHECK(c.output.find("  forced normals: step 1 (initial_geometry) along [0, 0, 1], allowance 0.2 "
                      "mm released over the step\n") != std::string::npos);
  // 0.2 mm is the flat yarns' whole height along z (2R, their centres in z = 0): no warning.
  CHECK(c.output.find("warning: the allowance") == std::string::npos);
  // 1 mm leaves the first 3 of the 4 increments (allowances 0.75, 0.5, 0.25 mm) with nothing to
  // push out.
  j["steps"][0]["forced_normals"]["allowance"] = 1.0;
  writeFile(scratch / "huge.json", j.dump());
  const RunResult huge = runFibra({"check", scratch / "huge.json"}, scratch);
  REQUIRE(huge.status == 0);
  CHECK(huge.output.find("    warning: the allowance 1 mm exceeds the fibres' whole height along "
                         "the direction at the start, 0.2 mm (their centres' spread and 2 R): no "
                         "overlap can be that deep, and the step's first 3 increments (of 4) "
                         "have nothing to do") != std::string::npos);
  // --quiet prints no description but still the start warnings.
  const RunResult quiet =
      runFibra({"run", scratch / "huge.json", "--out", scratch / "huge", "--quiet"}, scratch);
  CHECK(countLines(quiet.output, R"(^    warning: the allowance 1 mm exceeds)") == 1);
  // One idle increment is said in the singular; never all of them (the last ends at the plain
  // forced gap): 0.3 mm idles 1 of 4 (0.225 >= 0.2), 1e300 mm 3 of 4.
  for (const auto& [a, said] : {std::pair{0.3, "the step's first increment (of 4) has nothing"},
                                std::pair{1e300, "the step's first 3 increments (of 4) have"}}) {
    j["steps"][0]["forced_normals"]["allowance"] = a;
    writeFile(scratch / "idle.json", j.dump());
    CHECK(runFibra({"check", scratch / "idle.json"}, scratch).output.find(said) !=
          std::string::npos);
  }
  CHECK(huge.output.find("centres spread") == std::string::npos);  // every centre in z = 0
  // The thick yarns' bench scene: centres spread 2 x 0.0468 = 0.0935 mm along z (three rows of
  // the hexagonal section), beyond Delta_prox = 3R = 0.078 mm; with 0.1 mm given, no warning.
  const std::string thick = sourcePath("bench/woven_thick_7.json");
  const RunResult t = runFibra({"check", thick}, scratch);
  REQUIRE(t.status == 0);
  CHECK(countLines(t.output, R"(^    warning: the fibres' centres spread 0\.0935 mm along the )"
                             R"(direction, more than the proximity distance 0\.078 mm: .* a )"
                             R"(`proximity_distance` of at least 0\.0935 mm sees every pair)") == 1);
  nlohmann::json wide = nlohmann::json::parse(readFile(thick), nullptr, true, true);
  wide["contact"]["proximity_distance"] = 0.1;
  writeFile(scratch / "wide.json", wide.dump());
  CHECK(runFibra({"check", scratch / "wide.json"}, scratch).output.find("warning") ==
        std::string::npos);
  CHECK(c.output.find(", loops A <= 3, B <= 3, crossings follow the closest points, normal "
                      "forces on material particles (the paper's)\n") != std::string::npos);
  CHECK(c.output.find("  linear solver: mumps, ordering metis, block low-rank 1e-06, on K's "
                      "non-zeros (pattern slack 1.5), GMRES to 1e-08 (restart 40, <= 200 "
                      "iterations)\n") != std::string::npos);
  CHECK(r.output.find("  linear solver: auto (direct below 7000 free equations, from there mumps, "
                      "or schwarz where MUMPS's analysis estimates >= 500 flops per non-zero), "
                      "ordering auto, on K's non-zeros (pattern slack 1.5), schwarz's coarse level "
                      "of 8 segments per fibre, rotations auto, GMRES to 1e-08 (restart 40, <= 200 "
                      "iterations)\n") != std::string::npos);
  CHECK(r.output.find("crossings follow") == std::string::npos);
  // one coarse segment is said in the singular
  wide["solver"] = {{"strategy", "schwarz"}, {"coarse_segments", 1}};
  writeFile(scratch / "one_segment.json", wide.dump());
  CHECK(runFibra({"check", scratch / "one_segment.json"}, scratch)
            .output.find("schwarz's coarse level of 1 segment per fibre, rotations auto") !=
        std::string::npos);
  CHECK(r.output.find(", normal forces on facing particles (friction on material ones)\n") !=
        std::string::npos);  // default
  CHECK(c.output.find("friction tangent symmetrised, element placement paper, normals updated by "
                      "loop B (Anderson memory 3 when unstable), stick/slip held "
                      "after 2 changes (tolerance 0.01)\n") !=
        std::string::npos);
  CHECK(c.output.find("  contact classes: warp (3 fibres), weft (2 fibres), (default) (1 "
                      "fibres)\n") != std::string::npos);
  CHECK(c.output.find("    [warp, weft]: mu 0.1, p_max 0.0005 mm, penalty 0.01 .. 50 x E R\n"
                      "    between: mu 0, p_max 0.001 mm, penalty 1 .. 10000 x E R\n") !=
        std::string::npos);
  // The run prints the same header as check (before its threads line).
  const RunResult run =
      runFibra({"run", scene, "--out", scratch / "out", "--threads", "1"}, scratch);
  REQUIRE(run.status == 0);
  const std::string header = r.output.substr(0, r.output.find("fibra: " + scene + ": the scene"));
  CHECK(run.output.starts_with(header + "  threads: 1\n"));
}

TEST_CASE("fibra run prints a header, one line per increment and a summary, --quiet only the summary") {
  TempDir scratch("cli_lines");
  const std::string scene = sourcePath("samples/cantilever.json"), out = scratch / "out";
  const RunResult r = runFibra({"run", scene, "--out", out}, scratch);
  REQUIRE(r.status == 0);
  CHECK(r.output.starts_with(std::string("fibra ") + FIBRA_VERSION_STRING + ": " + scene + "\n"));
  CHECK(countLines(r.output, R"(^  1 fibres, 21 nodes, 10 elements, 189 DOFs$)") == 1);
  CHECK(countLines(r.output, R"(^step 1/1  increment \d+/10  t = )") == 10);
  CHECK(countLines(r.output, "iteration ") == 0);
  CHECK(countLines(r.output, R"(^fibra: solved: t = 1, 10 increments, \d+ Newton iterations, )"
                             R"(0 cutbacks, [0-9.e-]+ s; 11 frames, history and final state in )") ==
        1);
  const RunResult q = runFibra({"run", scene, "--out", out, "--quiet"}, scratch);
  REQUIRE(q.status == 0);
  CHECK(q.output.starts_with("fibra: solved: t = 1, 10 increments"));
  CHECK(countLines(q.output, ".") == 1);
}

TEST_CASE("fibra run into a used --out replaces the earlier run's files and keeps the others") {
  TempDir scratch("cli_rerun");
  fs::create_directories(scratch.path());
  const std::string out = scratch / "out";
  REQUIRE(runFibra({"run", sourcePath("samples/cantilever.json"), "--out", out, "--quiet"},
                   scratch).status == 0);
  REQUIRE(fs::exists(fs::path(out) / "result_0010.vtu"));
  writeFile(out + "/notes.txt", "mine");
  auto scene = nlohmann::json::parse(readFile(sourcePath("samples/cantilever.json")), nullptr,
                                     true, true);
  scene["steps"][0]["output_every"] = 5;  // frames 0, 5, 10: written as 0000, 0001, 0002
  writeFile(scratch / "sparse.json", scene.dump());
  const RunResult r =
      runFibra({"run", scratch / "sparse.json", "--out", out, "--vtu-format", "ascii"}, scratch);
  REQUIRE(r.status == 0);
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(out)) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  CHECK(files == std::vector<std::string>{"final_state.csv", "history.csv", "notes.txt",
                                          "result.pvd", "result_0000.vtu", "result_0001.vtu",
                                          "result_0002.vtu", "resume_scene.json",
                                          "resume_state.bin"});
  CHECK(readFile(out + "/resume_scene.json") == readFile(scratch / "sparse.json"));
  CHECK(readFile(out + "/result_0002.vtu").find("format=\"ascii\"") != std::string::npos);
  CHECK(readFile(out + "/notes.txt") == "mine");
  const RunResult bad = runFibra({"run", sourcePath("samples/cantilever.json"), "--out", out,
                                  "--vtu-format", "xml"}, scratch);
  CHECK(bad.status == 2);
  CHECK(bad.output.starts_with("fibra: --vtu-format: expected binary or ascii, got 'xml'\n"));
}

TEST_CASE("fibra --trace writes every span's start and length to the nanosecond, nested") {
  TempDir scratch("cli_trace");
  fs::create_directories(scratch.path());
  const std::string trace = scratch / "t.json";
  REQUIRE(runFibra({"run", sourcePath("samples/roller_drag.json"), "--out", scratch / "out",
                    "--quiet", "--trace", trace, "--threads", "2"},
                   scratch).status == 0);
  const auto json = nlohmann::json::parse(readFile(trace));
  const std::regex exact(R"("ts":\d+\.\d{3},"dur":\d+\.\d{3})");
  const std::string text = readFile(trace);
  const auto spans = json.at("traceEvents");
  REQUIRE(spans.size() > 100);
  CHECK(std::distance(std::sregex_iterator(text.begin(), text.end(), exact),
                      std::sregex_iterator()) == std::ptrdiff_t(spans.size()));
  // Per thread, spans sorted by start either nest in the enclosing one or follow it.
  std::map<int, std::vector<std::pair<double, double>>> byThread;
  for (const auto& e : spans)
    byThread[e.at("tid").get<int>()].emplace_back(e.at("ts").get<double>(),
                                                  e.at("ts").get<double>() + e.at("dur").get<double>());
  int crossed = 0;
  for (auto& [thread, list] : byThread) {
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
      return a.first < b.first || (a.first == b.first && a.second > b.second);
    });
    std::vector<double> open;  // ends of the enclosing spans
    for (const auto& [begin, end] : list) {
      while (!open.empty() && begin >= open.back() - 0.002) open.pop_back();
      if (!open.empty() && end > open.back() + 0.002) ++crossed;
      open.push_back(end);
    }
  }
  CHECK(crossed == 0);
}

TEST_CASE("fibra run refuses repeated or conflicting options and an unwritable trace before solving") {
  TempDir scratch("cli_options");
  const std::string scene = sourcePath("samples/cantilever.json");
  const std::string out = (scratch.path() / "o").string();
  const RunResult twice = runFibra({"run", scene, "--out", out, "--out", out}, scratch);
  CHECK(twice.status == 2);
  CHECK(twice.output.find("--out: given twice") != std::string::npos);
  const RunResult both = runFibra({"run", scene, "--out", out, "--quiet", "--verbose"}, scratch);
  CHECK(both.status == 2);
  CHECK(both.output.find("--quiet and --verbose") != std::string::npos);
  const RunResult trace = runFibra({"run", scene, "--out", out, "--trace", "/proc/nope.json"}, scratch);
  CHECK(trace.status == 2);
  CHECK(trace.output.find("--trace: cannot write") != std::string::npos);
  CHECK(trace.output.find("solved") == std::string::npos);  // refused before the run
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("fibra run explains a capped loop A once and counts in the singular for one") {
  // The forced-normals sample with one detection per increment: its pass solves with the elements
  // of the increment's first detection while the yarns still move, in increments 1 and 5.
  TempDir scratch("cli_capped");
  fs::create_directories(scratch.path());
  nlohmann::json j = nlohmann::json::parse(readFile(sourcePath("samples/forced_normals.json")),
                                           nullptr, true, true);
  j["contact"]["max_detection_loops"] = 1;
  writeFile(scratch / "capped.json", j.dump());
  const RunResult r = runFibra({"run", scratch / "capped.json", "--out", scratch / "out"}, scratch);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(countLines(r.output, R"(^step .*  loop A capped  )") >= 2);
  CHECK(countLines(r.output, R"(^  note: loop A capped: .* of its detection 1 )"
                             R"(\(contact.max_detection_loops\))") == 1);
  // "1 iteration", never "1 iterations"; and the plural elsewhere.
  CHECK(countLines(r.output, R"(^step .* t = \S+ +1 iteration   residual)") >= 1);
  CHECK(countLines(r.output, R"( 1 iterations )") == 0);
  CHECK(countLines(r.output, R"(^step .* t = \S+ +[2-9] iterations  residual)") >= 1);
}

TEST_CASE("fibra run says how the fibre normals change in a step, the rules once") {
  // A 7-fibre bundle clamped at both ends, pulled and twisted a quarter turn in 4 increments,
  // mu = 0.3, p_max 5e-4 (the scenes of tests/test_normal_update_auto.cpp): the twist's first
  // attempt fails with loop B's normals and converges linearised (contact normal_update
  // "auto"); in 6 increments its first increment converges slowly with loop B's normals and the
  // step switches to linearised ones; at mu = 0.1, p_max 2e-4 the switch comes first and the
  // last increment goes back to loop B's normals.
  TempDir scratch("cli_normal_retry");
  fs::create_directories(scratch.path());
  const auto run = [&](const nlohmann::json& scene, const std::string& name) {
    writeFile(scratch / (name + ".json"), scene.dump());
    const RunResult r =
        runFibra({"run", scratch / (name + ".json"), "--out", scratch / name}, scratch);
    REQUIRE_MESSAGE(r.status == 0, r.output);
    return r.output;
  };
  nlohmann::json j = {{"units", "mm-N-MPa"},
                      {"materials", {{{"name", "m"}, {"young_modulus", 4000}, {"poisson_ratio", 0.3}}}},
                      {"tables", {{"twist", {{0, 0}, {1, 0}, {2, 1.5707963267948966}}}}},
                      {"contact", {{"friction", 0.3}, {"max_penetration", 5e-4}}},
                      {"steps", {{{"end_time", 1}, {"increments", 2}},
                                 {{"end_time", 2}, {"increments", 4}}}},
                      {"output", {{"vtu", false}}}};
  for (int i = 0; i < 7; ++i) {
    const double a = (i - 1) * 3.14159265358979323846 / 3, y = i ? 0.2 * std::cos(a) : 0,
                 z = i ? 0.2 * std::sin(a) : 0;
    const std::string f = "f" + std::to_string(i);
    j["fibres"].push_back({{"name", f}, {"material", "m"}, {"radius", 0.1}, {"elements", 10},
                           {"geometry", {{"type", "line"}, {"points", {{-2, y, z}, {2, y, z}}},
                                         {"director", {0, 0, 1}}}}});
    j["boundary_conditions"].push_back({{"type", "clamp"}, {"group", f + ".start"}});
    j["boundary_conditions"].push_back(
        {{"type", "clamp"}, {"group", f + ".end"}, {"displacement", {0.004, 0, 0}},
         {"rotation", {{"axis", {1, 0, 0}}, {"centre", {2, 0, 0}}, {"angle", "twist"}}}});
  }
  const std::string twist = run(j, "twist");
  CHECK(countLines(twist, R"(^  normals: an attempt that failed with loop B's normals converged )"
                             R"(with every fibre normal linearised; the step goes on with every )"
                             R"(fibre normal linearised in Newton \(contact.normal_update "auto": )") == 1);
  CHECK(countLines(twist, R"(every fibre normal linearised after a failed attempt \(retried\) or )"
                             R"(a slow loop B \(kept while it converges; a failed linearised )"
                             R"(attempt goes back to loop B for the step\))") == 1);
  CHECK(countLines(twist, "converged slowly with loop B's normals") == 0);
  const auto history = readCsv(scratch / "twist" + "/history.csv");
  REQUIRE(history.size() == 7);  // the header and 6 increments
  const auto column = std::find(history[0].begin(), history[0].end(), "normal_retries");
  REQUIRE(column != history[0].end());
  int retries = 0;
  for (size_t row = 1; row < history.size(); ++row)
    retries += std::stoi(history[row][size_t(column - history[0].begin())]);
  CHECK(retries >= 1);

  j["steps"][1]["increments"] = 6;
  const std::string slow = run(j, "slow");
  CHECK(countLines(slow, R"(^  normals: an attempt converged slowly with loop B's normals; the )"
                            R"(step goes on with every fibre normal linearised in Newton )"
                            R"(\(contact.normal_update "auto": )") == 1);
  CHECK(countLines(slow, "^  normals: ") == 1);  // nothing failed: one change, one line

  // mu = 0.1, p_max 2e-4, 4 increments: the first switches, the last one's linearised attempt
  // fails and is tried again with loop B's normals; the rules were said at the switch, not again.
  j["contact"]["friction"] = 0.1;
  j["contact"]["max_penetration"] = 2e-4;
  j["steps"][1]["increments"] = 4;
  const std::string back = run(j, "back");
  CHECK(countLines(back, R"(^  normals: an attempt converged slowly with loop B's normals; )") == 1);
  CHECK(countLines(back, R"(^  normals: an attempt with every fibre normal linearised failed and )"
                            R"(was tried again with loop B's normals; the step ends here$)") == 1);
  CHECK(countLines(back, R"(^  failed attempts \(what followed at t: why\): loop B's normals )"
                            R"(again at t = 2: )") == 1);

  // The sliding beams' first increment: the retry fails as well, and the note says so.
  nlohmann::json beams =
      nlohmann::json::parse(readFile(sourcePath("samples/two_beams_sliding.json")), nullptr, true,
                            true);
  beams["output"]["plots"] = nlohmann::json::array();
  beams["output"]["vtu"] = false;
  const std::string sliding = run(beams, "beams");
  CHECK(countLines(sliding, R"(^  normals: an attempt that failed with loop B's normals failed )"
                             R"(again with every fibre normal linearised \(no more such retries )"
                             R"(in this step\); the step goes on with loop B's normals \(a slow )"
                             R"(loop B may still switch\) \(contact.normal_update)") == 1);
  // The increment's failed attempts, each under what followed it: the retry, then cutbacks.
  CHECK(countLines(sliding, R"(^  failed attempts \(what followed at t: why\): every fibre )"
                             R"(normal linearised at t = 0\.04: .*; cutback at t = 0\.04: )") == 1);
}

TEST_CASE("fibra check names neo-Hookean fibres and the continuation, run says when it comes on") {
  // The twisted rod of tests/test_continuation.cpp (no contact), its step damped from the first
  // increment that fails without: load control fails at the snap, and the continuation takes
  // over there.
  TempDir scratch("cli_damping_from");
  std::filesystem::create_directories(scratch.path());
  const std::string rod =
      twistedRodScene(50, R"("damping": 0.01, "damping_from": "failure")");
  writeFile(scratch / "rod.json", rod);
  nlohmann::json soft = nlohmann::json::parse(rod);
  soft["materials"][0]["law"] = "neo_hookean";
  writeFile(scratch / "soft.json", soft.dump());
  const RunResult c = runFibra({"check", scratch / "soft.json"}, scratch);
  REQUIRE_MESSAGE(c.status == 0, c.output);
  CHECK(countLines(c.output, R"(^  sections: neo-Hookean for 1 fibre \(rod\) \(integrated point )"
                             R"(by point at every iteration, enhanced transverse strains\)$)") == 1);
  CHECK(countLines(c.output, R"(^  viscous continuation: step 1 damping 0.01 from its first )"
                             R"(failed increment$)") == 1);
  const RunResult b = runFibra({"check", sourcePath("samples/bundle_squeeze.json")}, scratch);
  CHECK(countLines(b.output, "sections:|viscous continuation:") == 0);
  CHECK(countLines(runFibra({"check", scratch / "rod.json"}, scratch).output, "sections:") == 0);

  const RunResult r = runFibra({"run", scratch / "rod.json", "--out", scratch / "out"}, scratch);
  REQUIRE_MESSAGE(r.status == 0, r.output);
  CHECK(countLines(r.output, R"(^  note: the increment failed without the viscous continuation; )"
                             R"(it acts from t = [0-9.]+ to the step's end \(damping_from )"
                             R"("failure", damping 0.01\)$)") == 1);
  CHECK(countLines(r.output, R"(damping on at t = [0-9.]+: )") == 1);
}

TEST_CASE("fibra check prints the resolved self-contact separation, per fibre where it differs") {
  // Parallel fibres of 10 mm in 40 elements (h = 0.25 mm): the derived separation is
  // max(6 R, h) per fibre (engine/contact_setup.cpp), a given one max(it, h).
  TempDir scratch("cli_self_separation");
  std::filesystem::create_directories(scratch.path());
  nlohmann::json j = nlohmann::json::parse(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000}],
    "fibres": [],
    "boundary_conditions": [{"type": "clamp", "group": "a.start"}],
    "steps": [{"end_time": 1}],
    "contact": {"self_contact": true}
  })");
  const auto fibres = [&](const std::vector<double>& radii) {
    j["fibres"] = nlohmann::json::array();
    for (size_t i = 0; i < radii.size(); ++i)
      j["fibres"].push_back({{"name", std::string(1, char('a' + i))}, {"material", "m"},
                             {"radius", radii[i]}, {"elements", 40},
                             {"geometry", {{"type", "line"},
                                           {"points", {{0, 2.0 * i, 0}, {10, 2.0 * i, 0}}}}}});
  };
  const auto separationLines = [&](const char* name) {
    writeFile(scratch / name, j.dump());
    const RunResult r = runFibra({"check", scratch / name}, scratch);
    REQUIRE_MESSAGE(r.status == 0, r.output);
    std::string lines;
    std::istringstream in(r.output);
    for (std::string line; std::getline(in, line);)
      if (line.find("self-contact separation") != std::string::npos) lines += line + "\n";
    return lines;
  };
  fibres({0.1, 0.1});
  CHECK(separationLines("same.json") == "  self-contact separation: 0.6 mm\n");
  fibres({0.05, 0.1, 0.02, 0.05});  // 0.3, 0.6 and h = 0.25 (above 6 R = 0.12)
  CHECK(separationLines("per_fibre.json") ==
        "  self-contact separation: 0.3 mm for 2 fibres (a, d), 0.6 mm for 1 fibre (b), 0.25 mm "
        "for 1 fibre (c)\n");
  fibres({0.05, 0.06, 0.07, 0.08, 0.09});  // five values: their range
  CHECK(separationLines("range.json") == "  self-contact separation: 0.3 .. 0.54 mm over the fibres\n");
  j["contact"]["self_contact_separation"] = 2;
  CHECK(separationLines("given.json") == "  self-contact separation: 2 mm\n");
  j["contact"] = {{"self_contact", false}};
  CHECK(separationLines("off.json").empty());
}
