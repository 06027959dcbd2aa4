// The yarn generator (io/yarn_generator.h) and the scene generators around it: seeded
// reproducibility, the hexagonal section, the perturbation's bound, the twist's helix angle,
// `fibra expand` and its round trip, field-named errors, and union groups.
#include "engine/world.h"
#include "expand_roundtrip.h"
#include "io/scene_loader.h"
#include "io/scene_validate.h"
#include "io/seeded_random.h"
#include "io/yarn_generator.h"
#include "scene_test_util.h"
#include "store_bits.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

using namespace fibra;
using namespace fibra::test;
using Json = nlohmann::json;

namespace {

constexpr double kR = 0.01, kGap = 0.002, kLength = 1;  // mm

// A scene with one yarn of `fibres` fibres along z, held at its start, pulled at its end.
Json yarnScene(int fibres, double amplitude, int seed, double twist = 0) {
  Json s = Json::parse(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "glass", "young_modulus": 73000, "bending_factor": 0.12}],
    "generators": [{"type": "yarn", "name": "yarn", "material": "glass", "length": 1,
                    "elements": 8, "fibre_radius": 0.01, "gap": 0.002}],
    "boundary_conditions": [{"type": "clamp", "group": "yarn.start"}],
    "loads": [{"type": "force", "group": "yarn.end", "vector": [0, 0, 0.01]}],
    "steps": [{"increments": 1}]
  })");
  Json& y = s["generators"][0];
  y["fibres"] = fibres;
  y["twist"] = twist;
  if (amplitude > 0) y["perturbation"] = {{"amplitude", amplitude}, {"modes", 3}, {"seed", seed}};
  return s;
}

SceneDef load(const Json& j) { return loadSceneFromString(j.dump(), "s.json"); }

std::string errorAfter(const std::function<void(Json&)>& change) {
  Json j = yarnScene(7, 0.002, 1);
  change(j);
  return errorOf([&] { load(j); });
}

// The centreline vertices of every fibre of a loaded scene.
std::vector<std::vector<Vec3>> centrelines(const SceneDef& s) {
  std::vector<std::vector<Vec3>> lines;
  for (const FibreDef& f : s.fibres) lines.push_back(f.geometry.points);
  return lines;
}

bool sameFibresAndGroups(const SceneDef& a, const SceneDef& b) {
  if (a.fibres.size() != b.fibres.size() || a.groups.size() != b.groups.size()) return false;
  for (size_t i = 0; i < a.fibres.size(); ++i) {
    const FibreDef &f = a.fibres[i], &g = b.fibres[i];
    if (f.name != g.name || f.material != g.material || !sameBits(f.radius, g.radius) ||
        f.elements != g.elements || f.order != g.order || f.geometry.kind != g.geometry.kind ||
        !sameBits(f.geometry.points, g.geometry.points) ||
        !sameBits(f.geometry.director, g.geometry.director))
      return false;
  }
  for (size_t i = 0; i < a.groups.size(); ++i)
    if (a.groups[i].name != b.groups[i].name || a.groups[i].members != b.groups[i].members ||
        a.groups[i].fibre != b.groups[i].fibre || a.groups[i].nodes != b.groups[i].nodes)
      return false;
  return true;
}

}  // namespace

TEST_CASE("yarn generator: the same seed gives bitwise the same expanded scene and positions") {
  const std::string text = yarnScene(19, 0.003, 42, 0.5).dump();
  const std::string a = expandSceneFromString(text, "s.json");
  CHECK(a == expandSceneFromString(text, "s.json"));
  World w1(loadSceneFromString(text, "s.json")), w2(loadSceneFromString(text, "s.json"));
  CHECK(w1.fibres().nodes() == 19 * 17);
  CHECK(sameBits(w1.fibres().q, w2.fibres().q));
}

TEST_CASE("seeded random: xoshiro256** seeded by splitmix64 gives the pinned values on every machine") {
  // Values of the published algorithms for seed 2011, computed independently (Python integers).
  SeededRandom r(2011);
  CHECK(r.next() == 0x2e125c139e5aff33ULL);
  CHECK(r.next() == 0x516a6b062f68f3feULL);
  CHECK(r.next() == 0x42f0437d7160f626ULL);
  CHECK(SeededRandom(2011).uniform() == 0.17996764639824991);  // (first >> 11) * 2^-53, exact
  SeededRandom u(7);
  for (int i = 0; i < 1000; ++i) {
    const double x = u.uniform();
    CHECK((x >= 0 && x < 1));
    const int k = u.below(5);
    CHECK((k >= 0 && k < 5));
  }
}

TEST_CASE("yarn generator: the sample yarn_crush expands to 19 fibres and the yarn's end groups") {
  const SceneDef s = loadScene(sourcePath("samples/yarn_crush.json"));
  CHECK(s.fibres.size() == 19);
  CHECK(s.fibres[18].name == "yarn.f18");
  CHECK(s.materials[0].bendingFactor == 0);
  REQUIRE(s.groups.size() == 3);
  CHECK(s.groups[0].name == "yarn.start");
  CHECK(s.groups[0].members.size() == 19);
}

TEST_CASE("yarn generator: the seed is any whole number up to 2^53, its message says so") {
  const auto seedError = [](const Json& seed) {
    return errorAfter([&](Json& j) { j["generators"][0]["perturbation"]["seed"] = seed; });
  };
  const std::string range =
      "s.json: generators[0].perturbation.seed: must be a whole number from 0 to "
      "9007199254740992 (2^53), got ";
  // Before: "must be >= 0, got -1" for -1, "expected an integer, got the number 3000000000"
  // for a seed beyond 2^31 that the documentation allowed.
  CHECK(seedError(-1) == range + "-1");
  CHECK(seedError(1.5) == range + "1.5");
  CHECK(seedError(1e300) == range + "1e+300");
  CHECK(seedError(std::uint64_t(1) << 60) == range + "1152921504606846976");
  CHECK(seedError("7") == "s.json: generators[0].perturbation.seed: expected a whole number "
                          "from 0 to 9007199254740992 (2^53), got a string \"7\"");
  for (const Json& fine : {Json(3000000000u), Json(std::uint64_t(1) << 53), Json(5e6)})
    CHECK(seedError(fine) == "(no error)");
  // 5e6 and 5000000 are one seed.
  Json a = yarnScene(7, 0.003, 0), b = a;
  a["generators"][0]["perturbation"]["seed"] = 5e6;
  b["generators"][0]["perturbation"]["seed"] = 5000000;
  CHECK(sameBits(load(a).fibres[3].geometry.points, load(b).fibres[3].geometry.points));
}

TEST_CASE("generated groups: a scene union names a yarn's end groups") {
  Json j = yarnScene(7, 0, 0);
  // The scene's own union, listed before the groups the generator appends.
  j["groups"] = {{{"name", "both_ends"}, {"union", {"yarn.start", "yarn.end"}}}};
  j["boundary_conditions"][0]["group"] = "both_ends";
  j.erase("loads");
  const SceneDef s = load(j);
  World w(s);
  CHECK(w.constraints().dof.size() == size_t(2 * 7 * 9));  // every fibre's two ends clamped
  // A cycle through a generated group is refused, naming the scene's group.
  j["groups"][0]["union"] = {"yarn.start"};
  j["groups"].push_back({{"name", "loop"}, {"union", {"both_ends"}}});
  j["groups"][0]["union"].push_back("loop");
  CHECK(errorOf([&] { load(j); }) ==
        "s.json: groups[0].union[1]: group 'loop' includes this group through its own union (a "
        "cycle: both_ends -> loop -> both_ends)");
}

TEST_CASE("an unknown top-level key close to generators suggests it") {
  for (const char* typo : {"generator", "generater", "Generators"}) {
    CAPTURE(typo);
    Json j = yarnScene(7, 0, 0);
    j[typo] = j["generators"];
    j.erase("generators");
    CHECK(errorOf([&] { load(j); }) ==
          std::string("s.json: ") + typo + ": unknown field (did you mean 'generators'?)");
  }
}

TEST_CASE("yarn generator: a different seed gives a different yarn") {
  const SceneDef a = load(yarnScene(7, 0.003, 1)), b = load(yarnScene(7, 0.003, 2));
  for (size_t f = 0; f < a.fibres.size(); ++f) {
    CAPTURE(f);
    CHECK(a.fibres[f].geometry.points != b.fibres[f].geometry.points);
  }
}

TEST_CASE("yarn generator: hexagonal rings of 1, 7, 19, 37 fibres at spacing 2R + gap") {
  const double d = 2 * kR + kGap;
  for (int n : {1, 7, 19, 37, 61, 10, 25}) {
    CAPTURE(n);
    const auto sites = hexagonalLayout(n, d);
    REQUIRE(int(sites.size()) == n);
    CHECK(sites[0] == std::array<double, 2>{0.0, 0.0});
    double nearest = 1e9;
    int centreNeighbours = 0;
    for (size_t i = 0; i < sites.size(); ++i) {
      const double r0 = std::hypot(sites[i][0], sites[i][1]);
      if (i > 0 && std::abs(r0 - d) < 1e-12) ++centreNeighbours;
      for (size_t j = 0; j < i; ++j)
        nearest = std::min(nearest, std::hypot(sites[i][0] - sites[j][0], sites[i][1] - sites[j][1]));
    }
    if (n > 1) CHECK(std::abs(nearest - d) < 1e-12);
    CHECK(centreNeighbours == std::min(n - 1, 6));
  }
  // A full ring k lies within k d of the centre; 19 fibres: the outermost at 2 d.
  double outer = 0;
  for (const auto& s : hexagonalLayout(19, d)) outer = std::max(outer, std::hypot(s[0], s[1]));
  CHECK(std::abs(outer - 2 * d) < 1e-12);
}

TEST_CASE("yarn generator: straight untwisted fibres are parallel at spacing 2R + gap, no overlap") {
  const auto lines = centrelines(load(yarnScene(19, 0, 0)));
  REQUIRE(lines.size() == 19);
  double nearest = 1e9;
  for (size_t i = 0; i < lines.size(); ++i) {
    REQUIRE(lines[i].size() == size_t(kYarnPointsPerElement * 8 + 1));
    CHECK(lines[i].front().z() == 0);
    CHECK(std::abs(lines[i].back().z() - kLength) < 1e-15);
    for (size_t j = 0; j < i; ++j)
      for (size_t p = 0; p < lines[i].size(); ++p)
        nearest = std::min(nearest, (lines[i][p] - lines[j][p]).norm());
  }
  CHECK(std::abs(nearest - (2 * kR + kGap)) < 1e-12);
  CHECK(nearest > 2 * kR);
}

TEST_CASE("yarn generator: the perturbation stays within its amplitude and vanishes at the ends") {
  const double amplitude = 0.004;
  const auto straight = centrelines(load(yarnScene(19, 0, 0)));
  const auto perturbed = centrelines(load(yarnScene(19, amplitude, 7)));
  double largest = 0;
  for (size_t f = 0; f < straight.size(); ++f)
    for (size_t p = 0; p < straight[f].size(); ++p) {
      const Vec3 u = perturbed[f][p] - straight[f][p];
      CHECK(std::abs(u.z()) < 1e-15);
      CHECK(std::abs(u.x()) <= amplitude * (1 + 1e-12));
      CHECK(std::abs(u.y()) <= amplitude * (1 + 1e-12));
      largest = std::max({largest, std::abs(u.x()), std::abs(u.y())});
      if (p == 0 || p + 1 == straight[f].size()) CHECK(u.norm() < 1e-15);
    }
  CHECK(largest > 0.3 * amplitude);  // the modes do displace the fibres
}

TEST_CASE("yarn generator: with twist the outer fibre is a helix of angle atan(2 pi r turns / L)") {
  const double turns = 0.75;
  const auto lines = centrelines(load(yarnScene(19, 0, 0, turns)));
  // Fibre 0 is on the axis and stays straight.
  for (const Vec3& p : lines[0]) CHECK(std::hypot(p.x(), p.y()) < 1e-15);
  const std::vector<Vec3>& outer = lines[7];  // the first site of ring 2, radius 2 d
  const double r = 2 * (2 * kR + kGap);
  const double expected = std::atan(2 * std::numbers::pi * r * turns / kLength);
  for (size_t p = 0; p + 1 < outer.size(); ++p) {
    CHECK(std::abs(std::hypot(outer[p].x(), outer[p].y()) - r) < 1e-12);
    const Vec3 t = outer[p + 1] - outer[p];
    CHECK(std::abs(std::atan2(std::hypot(t.x(), t.y()), t.z()) - expected) < 1e-3 * expected);  // chords of 1/64 of the length
  }
  // Over the length the outer fibre turns by 0.75 turn about the axis.
  const double swept = std::atan2(outer.back().y(), outer.back().x()) -
                       std::atan2(outer.front().y(), outer.front().x());
  CHECK(std::abs(std::remainder(swept - 2 * std::numbers::pi * turns, 2 * std::numbers::pi)) <
        1e-12);
}

TEST_CASE("yarn generator: groups of every fibre's ends and of the yarn's ends as unions") {
  const SceneDef s = load(yarnScene(7, 0, 0));
  REQUIRE(s.groups.size() == 3);
  CHECK(s.groups[0].name == "yarn.start");
  CHECK(s.groups[1].name == "yarn.end");
  CHECK(s.groups[2].name == "yarn.all");
  CHECK(s.groups[0].members.size() == 7);
  CHECK(s.groups[0].members[3] == "yarn.f3.start");
  World w(s);
  CHECK(w.constraints().dof.size() == size_t(7 * 9));  // every fibre's start clamped
}

TEST_CASE("fibra expand: the expanded scene loads to the same fibres and groups and solves bitwise the same") {
  TempDir dir("yarn_expand");
  const auto [a, b] = expandRoundTrip(dir, yarnScene(7, 0.002, 3, 0.25));
  CHECK(sameFibresAndGroups(a, b));
  World wa(a), wb(b);
  REQUIRE(wa.step().status == StepStatus::Converged);
  REQUIRE(wb.step().status == StepStatus::Converged);
  CHECK(sameBits(wa.fibres().q, wb.fibres().q));
  // To stdout without --out; a bad scene: exit 2 and the field named.
  const std::string scene = dir / "generated.json";
  const RunResult out = runFibra({"expand", scene}, dir);
  CHECK(out.status == 0);
  CHECK(out.output == readFile(dir / "plain.json"));
  writeFile(scene, yarnScene(0, 0, 0).dump());
  const RunResult bad = runFibra({"expand", scene}, dir);
  CHECK(bad.status == 2);
  CHECK(bad.output.find("generators[0].fibres: must be in [1, 100000], got 0") != std::string::npos);
}

TEST_CASE("yarn generator: errors in its fields name generators[i].field") {
  CHECK(errorAfter([](Json&) {}) == "(no error)");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["type"] = "yarm"; }) ==
        "s.json: generators[0].type: unknown value \"yarm\" (expected one of: yarn, woven_fabric)");
  CHECK(errorAfter([](Json& j) { j["generators"][0].erase("type"); }) ==
        "s.json: generators[0].type: required field missing");
  CHECK(errorAfter([](Json& j) { j["generators"] = Json::object(); }) ==
        "s.json: generators: expected an array, got an object");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["fibre_radius"] = -1; }) ==
        "s.json: generators[0].fibre_radius: must be > 0, got -1");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["fibre_raduis"] = 1; }) ==
        "s.json: generators[0].fibre_raduis: unknown field for a yarn generator (did you mean "
        "'fibre_radius'?)");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["fibres"] = 2.5; }) ==
        "s.json: generators[0].fibres: expected an integer, got the number 2.5");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["gap"] = -0.1; }) ==
        "s.json: generators[0].gap: must be >= 0, got -0.1");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["order"] = 3; }) ==
        "s.json: generators[0].order: must be 1 or 2, got 3");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["axis"] = {0, 0, 0}; }) ==
        "s.json: generators[0].axis: must be a finite, non-zero vector");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["name"] = "a b"; }) ==
        "s.json: generators[0].name: 'a b' contains ' '; names use letters, digits, '_', '-' and '.'");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["perturbation"].erase("seed"); }) ==
        "s.json: generators[0].perturbation.seed: required field missing");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["perturbation"]["modes"] = 0; }) ==
        "s.json: generators[0].perturbation.modes: must be in [1, 100], got 0");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["perturbation"]["min_wavelength"] = 0.1; }) ==
        "s.json: generators[0].perturbation.min_wavelength: must be at least two element "
        "lengths (0.25 mm: a shorter wave is not represented), got 0.1");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["perturbation"]["amplitude"] = -1; }) ==
        "s.json: generators[0].perturbation.amplitude: must be >= 0, got -1");
  // The expanded entries go through the usual checks, under their own paths.
  CHECK(errorAfter([](Json& j) { j["generators"][0]["material"] = "glas"; }) ==
        "s.json: fibres[0].material: unknown material 'glas' (did you mean 'glass'?)");
  CHECK(errorAfter([](Json& j) { j["groups"] = {{{"name", "yarn.start"}, {"union", {"yarn.f0.end"}}}}; }) ==
        "s.json: groups[1].name: duplicate name 'yarn.start' (also groups[0])");
  CHECK(errorAfter([](Json& j) { j["fibres"] = 3; }) == "s.json: fibres: expected an array, got the number 3");
}

namespace {

// Three parallel beams along x, 0.5 mm apart, 4 elements each.
Json threeBeams() {
  Json s = Json::parse(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000}],
    "fibres": [],
    "groups": [{"name": "starts", "union": ["a.start", "b.start", "c.start"]},
               {"name": "ends", "union": ["a.end", "b.end", "c.end"]}],
    "boundary_conditions": [{"type": "clamp", "group": "starts"}],
    "loads": [{"type": "force", "group": "ends", "vector": [0.1, 0, 0]}],
    "steps": [{"increments": 1}]
  })");
  for (int k = 0; k < 3; ++k)
    s["fibres"].push_back({{"name", std::string(1, char('a' + k))},
                           {"material", "m"},
                           {"radius", 0.1},
                           {"elements", 4},
                           {"geometry", {{"type", "line"}, {"points", {{0, 0.5 * k, 0}, {10, 0.5 * k, 0}}}}}});
  return s;
}

std::string unionError(const std::function<void(Json&)>& change) {
  Json j = threeBeams();
  change(j);
  return errorOf([&] { World w(load(j)); });
}

}  // namespace

TEST_CASE("union groups: one group holds every fibre's start, another pulls every end") {
  World w(load(threeBeams()));
  CHECK(w.constraints().dof.size() == size_t(3 * 9));
  REQUIRE(w.step().status == StepStatus::Converged);
  const FibreStore& fibres = w.fibres();
  const auto tipOf = [&](Index f) { return fibres.firstNode[f] + fibres.nodeCount[f] - 1; };
  const double stretch = x0Of(fibres.q, tipOf(0)).x() - 10;
  CHECK(stretch > 0);
  for (Index f = 0; f < 3; ++f) {
    CHECK(x0Of(fibres.q, fibres.firstNode[f]) == x0Of(fibres.qRef, fibres.firstNode[f]));  // held
    const double tip = x0Of(fibres.q, tipOf(f)).x() - 10;
    CHECK(std::abs(tip / stretch - 1) < 1e-9);  // loaded alike
  }
  // The reaction of the one boundary condition balances the three loads.
  CHECK(std::abs(w.reaction(0).force.x() / -0.3 - 1) < 1e-9);
}

TEST_CASE("union groups: a node in several members counts once, unions of unions") {
  Json j = threeBeams();
  j["groups"].push_back({{"name", "both"}, {"union", {"starts", "a.all"}}});
  j["loads"].push_back({{"type", "line_force"}, {"group", "both"}, {"vector", {0, 0, 1e-4}}});
  const SceneDef s = load(j);
  World w(s);
  const GroupStore& g = w.groups();
  for (Index i = 0; i < g.size(); ++i)
    if (g.name[i] == "both") CHECK(g.count[i] == 9 + 2);  // a's 9 nodes, b and c's starts
}

TEST_CASE("union groups: bad members are named by their field") {
  CHECK(unionError([](Json&) {}) == "(no error)");
  CHECK(unionError([](Json& j) { j["groups"][0]["union"][1] = "b.strat"; }) ==
        "s.json: groups[0].union[1]: unknown group 'b.strat' (did you mean 'b.start'?)");
  CHECK(unionError([](Json& j) { j["groups"][0]["union"][2] = "a.start"; }) ==
        "s.json: groups[0].union[2]: group 'a.start' listed twice");
  CHECK(unionError([](Json& j) { j["groups"][0]["union"][0] = "starts"; }) ==
        "s.json: groups[0].union[0]: a group cannot be a union of itself");
  CHECK(unionError([](Json& j) {
          j["groups"][0]["union"][0] = "ends";
          j["groups"][1]["union"][0] = "starts";
        }) == "s.json: groups[0].union[0]: group 'ends' includes this group through its own union "
              "(a cycle: starts -> ends -> starts)");
  CHECK(unionError([](Json& j) { j["groups"][0]["union"] = Json::array(); }) ==
        "s.json: groups[0].union: must list at least one group");
  CHECK(unionError([](Json& j) { j["groups"][0]["union"][0] = 3; }) ==
        "s.json: groups[0].union[0]: expected a string, got the number 3");
  CHECK(unionError([](Json& j) { j["groups"][0]["fibre"] = "a"; }) ==
        "s.json: groups[0].fibre: unknown field for a union group (known fields: name, union)");
  // Neither form: before, "groups[0].fibre: required field missing", as if only one were allowed.
  CHECK(unionError([](Json& j) { j["groups"][0].erase("union"); }) ==
        "s.json: groups[0]: give either 'fibre' and 'nodes' (nodes of one fibre) or 'union' "
        "(names of other groups)");
  CHECK(unionError([](Json& j) { j["groups"][0] = {{"name", "starts"}, {"nodes", {0}}}; }) ==
        "s.json: groups[0].fibre: required field missing");
  CHECK(unionError([](Json& j) {
          j["boundary_conditions"].push_back({{"type", "pin"}, {"group", "b.start"}});
        }) == "s.json: boundary_conditions[1]: holds DOF x of node 0 of fibre 'b', already held "
              "by boundary_conditions[0] (group 'starts')");
}

TEST_CASE("union groups: a SceneDef built in code may not mix the two forms") {
  SceneDef s = load(threeBeams());
  s.groups[0].fibre = s.fibres[0].name;
  s.groups[0].nodes = {0};
  CHECK(errorOf([&] { validateScene(s); }) ==
        "groups[0]: give either 'union' or 'fibre' and 'nodes', not both");
}
