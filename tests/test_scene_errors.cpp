// Scene loader on bad input: every class of error is answered with the file, the field path and
// what is wrong — the whole message is compared, so a wrong path or a vaguer text fails.
#include "engine/world.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

using namespace fibra;
using namespace fibra::test;
using Json = nlohmann::json;

namespace {

// A small valid scene to break one field at a time.
Json baseScene() {
  return Json::parse(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000}],
    "fibres": [{"name": "b", "material": "m", "radius": 0.1, "elements": 4,
                "geometry": {"type": "line", "points": [[0, 0, 0], [10, 0, 0]]}}],
    "groups": [{"name": "mid", "fibre": "b", "nodes": [4]}],
    "tables": {"ramp": [[0, 0], [1, 1]]},
    "boundary_conditions": [{"type": "clamp", "group": "b.start"}],
    "loads": [{"type": "force", "group": "b.end", "vector": [0, -1e-3, 0], "table": "ramp"}],
    "steps": [{"end_time": 1, "increments": 2}],
    "output": {"probes": [{"name": "tip", "fibre": "b", "node": 8}]}
  })");
}

std::string errorAfter(const std::function<void(Json&)>& change) {
  Json j = baseScene();
  change(j);
  return errorOf([&] { loadSceneFromString(j.dump(), "s.json"); });
}

}  // namespace

TEST_CASE("scene errors: the base scene of these tests is valid") {
  CHECK(errorAfter([](Json&) {}) == "(no error)");
}

TEST_CASE("scene errors: each sample in samples/bad is rejected with file, field and reason") {
  const std::pair<const char*, const char*> cases[] = {
      {"malformed",
       "line 5, column 10: malformed JSON: syntax error while parsing object - unexpected string "
       "literal; expected '}'"},
      {"duplicate_key", "fibres[0].radius: duplicate field"},
      {"missing_field", "fibres[0].radius: required field missing"},
      {"wrong_type", "fibres[0].elements: expected an integer, got a string \"four\""},
      {"unknown_field", "fibres[0].raduis: unknown field (did you mean 'radius'?)"},
      {"negative_radius", "fibres[0].radius: must be > 0, got -1"},
      {"negative_modulus", "materials[0].young_modulus: must be > 0, got -4000"},
      {"poisson_ratio", "materials[0].poisson_ratio: must be in (-1, 0.5), got 0.5"},
      {"units", "units: must be \"mm-N-MPa\", got \"m-N-Pa\""},
      {"unknown_group",
       "loads[0].group: unknown group 'beam.tip' (known: beam.all, beam.end, beam.start)"},
      {"unknown_fibre", "groups[0].fibre: unknown fibre 'bean' (did you mean 'beam'?)"},
      {"unknown_material", "fibres[0].material: unknown material 'steel' (known: polymer)"},
      {"unknown_table", "loads[0].table: unknown table 'rampe' (did you mean 'ramp'?)"},
      {"non_monotone_table",
       "tables.ramp[2]: time 0.5 does not follow 1 (times must increase strictly)"},
      {"duplicate_name", "fibres[1].name: duplicate name 'beam' (also fibres[0])"},
      {"conflicting_bcs",
       "boundary_conditions[1]: holds DOF g1x of node 0 of fibre 'beam', already "
       "held by boundary_conditions[0] (group 'beam.start')"},
  };
  for (const auto& [name, expected] : cases) {
    CAPTURE(name);
    const std::string path = sourcePath(std::string("samples/bad/") + name + ".json");
    CHECK(errorOf([&] { loadScene(path); }) == path + ": " + expected);
  }
}

namespace {

// The scene loaded and its World built, as `fibra check` does: errors name the file.
void checkScene(const std::string& path) {
  const SceneDef scene = loadScene(path);
  try {
    World world(scene);
  } catch (const SceneError& e) {
    throw SceneError(path + ": " + e.what());
  }
}

}  // namespace

TEST_CASE("scene errors: samples/bad of contact classes, forced normals, groups and generators") {
  const std::pair<const char*, const char*> cases[] = {
      {"forced_normals_no_class",
       "steps[0].forced_normals: act between fibres of different classes, but every fibre is in "
       "the default class (no fibre has a \"class\")"},
      {"forced_normals_equal_levels",
       "steps[0].forced_normals: every fibre has level 0, so no crossing is oriented (give the "
       "fibres on top higher \"levels\")"},
      {"empty_levels",
       "fibres[0].levels: must list at least one piece [from, level] (or give one level for the "
       "whole fibre)"},
      {"pair_penalty_min",
       "contact.pairs[0].penalty_min: must be <= penalty_max (10000, the contact section's; or "
       "give the rule its own penalty_max), got 100000"},
      {"pair_one_class",
       "contact.pairs[0].classes: must be two class names [a, b] (for the pairs within one "
       "class: [a, a]), got 1 name"},
      {"pair_unknown_class",
       "contact.pairs[0].classes[1]: unknown class 'wetf' (no fibre has it; the fibres' classes: "
       "warp, weft)"},
      {"group_without_form",
       "groups[0]: give either 'fibre' and 'nodes' (nodes of one fibre) or 'union' (names of "
       "other groups)"},
      {"union_cycle",
       "groups[0].union[1]: group 'b' includes this group through its own union (a cycle: a -> b "
       "-> a)"},
      {"generator_typo", "generator: unknown field (did you mean 'generators'?)"},
      {"yarn_seed",
       "generators[0].perturbation.seed: must be a whole number from 0 to 9007199254740992 "
       "(2^53), got -1"},
  };
  for (const auto& [name, expected] : cases) {
    CAPTURE(name);
    const std::string path = sourcePath(std::string("samples/bad/") + name + ".json");
    CHECK(errorOf([&] { checkScene(path); }) == path + ": " + expected);
    // The first line of each sample names the faulty field.
    const std::string field = std::string(expected).substr(0, std::string(expected).find(':'));
    CHECK(readFile(path).starts_with("// " + field + ": "));
  }
}

TEST_CASE("scene errors: files that cannot be read") {
  const std::string missing = sourcePath("samples/bad/no_such_scene.json");
  CHECK(errorOf([&] { loadScene(missing); }) == missing + ": cannot open the scene file");
  const std::string dir = sourcePath("samples/bad");
  CHECK(errorOf([&] { loadScene(dir); }) == dir + ": is a directory, not a scene file");
  CHECK(
      errorOf([] { loadSceneFromString("", "empty.json"); }) ==
      "empty.json: line 1, column 1: malformed JSON: syntax error while parsing value - unexpected "
      "end of input; expected '[', '{', or a literal");
  CHECK(errorOf([] { loadSceneFromString("[1, 2]", "array.json"); }) ==
        "array.json: expected an object, got an array");
}

TEST_CASE("scene errors: structure — unknown, repeated, missing and mistyped fields") {
  CHECK(errorAfter([](Json& j) { j["boundary_condition"] = j["boundary_conditions"]; }) ==
        "s.json: boundary_condition: unknown field (did you mean 'boundary_conditions'?)");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["colour"] = "red"; }) ==
        "s.json: fibres[0].colour: unknown field (known fields: name, material, radius, elements, "
        "order, geometry, integration, class, levels)");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["geometry"]["pitch"] = 1; }) ==
        "s.json: fibres[0].geometry.pitch: unknown field for a line geometry (known fields: type, "
        "points, director)");
  CHECK(errorAfter([](Json& j) {
          j["fibres"][0]["integration"] = {{"section", "moments"}, {"rings", 2}};
        }) ==
        "s.json: fibres[0].integration.rings: unknown field for section \"moments\" (known fields: "
        "axial, section)");
  CHECK(errorAfter([](Json& j) { j.erase("steps"); }) == "s.json: steps: required field missing");
  CHECK(errorAfter([](Json& j) { j["fibres"] = Json::array(); }) ==
        "s.json: fibres: must list at least one entry");
  CHECK(errorAfter([](Json& j) { j["fibres"][0].erase("geometry"); }) ==
        "s.json: fibres[0].geometry: required field missing");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["radius"] = "0.1"; }) ==
        "s.json: fibres[0].radius: expected a number, got a string \"0.1\"");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["radius"] = true; }) ==
        "s.json: fibres[0].radius: expected a number, got a boolean true");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["elements"] = 2.5; }) ==
        "s.json: fibres[0].elements: expected an integer, got the number 2.5");
  CHECK(errorAfter([](Json& j) {
          j["fibres"][0]["geometry"]["points"][1] = {10, 0};
        }) == "s.json: fibres[0].geometry.points[1]: expected a vector [x, y, z], got 2 values");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["geometry"]["points"][1][2] = nullptr; }) ==
        "s.json: fibres[0].geometry.points[1][2]: expected a number, got null");
  CHECK(errorAfter([](Json& j) {
          j["materials"] = {{"name", "m"}};
        }) == "s.json: materials: expected an array, got an object");
  CHECK(errorAfter([](Json& j) { j["output"]["vtu"] = 1; }) ==
        "s.json: output.vtu: expected true or false, got the number 1");
  CHECK(errorAfter([](Json& j) { j["loads"][0]["type"] = "pressure"; }) ==
        "s.json: loads[0].type: unknown value \"pressure\" (expected one of: force, moment, "
        "line_force)");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["geometry"]["type"] = "spline"; }) ==
        "s.json: fibres[0].geometry.type: unknown value \"spline\" (expected one of: line, "
        "polyline, helix)");
}

TEST_CASE("scene errors: out-of-range numbers") {
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["elements"] = 0; }) ==
        "s.json: fibres[0].elements: must be >= 1, got 0");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["order"] = 3; }) ==
        "s.json: fibres[0].order: must be 1 or 2, got 3");
  CHECK(errorAfter([](Json& j) { j["materials"][0]["poisson_ratio"] = -1; }) ==
        "s.json: materials[0].poisson_ratio: must be in (-1, 0.5), got -1");
  CHECK(errorAfter([](Json& j) { j["materials"][0]["bending_factor"] = -0.1; }) ==
        "s.json: materials[0].bending_factor: must be >= 0, got -0.1");
  CHECK(errorAfter([](Json& j) { j["materials"][0]["law"] = "hooke"; }) ==
        "s.json: materials[0].law: unknown value \"hooke\" (expected one of: "
        "saint_venant_kirchhoff, neo_hookean)");
  CHECK(errorAfter([](Json& j) {
          j["materials"][0]["law"] = "neo_hookean";
          j["fibres"][0]["integration"] = {{"section", "moments"}};
        }) == "s.json: fibres[0].integration.section: must be \"quadrature\" (the default): "
              "material 'm' has law \"neo_hookean\", whose energy is integrated point by point "
              "over the section");
  CHECK(errorAfter([](Json& j) {
          j["fibres"][0]["integration"] = {{"section", "quadrature"}, {"rings", 5}};
        }) == "s.json: fibres[0].integration.rings: must be 1 to 4, got 5");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["damping_from"] = "failure"; }) ==
        "s.json: steps[0].damping_from: \"failure\" needs a `damping` > 0 on the step (the "
        "continuation it turns on), got damping 0");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["damping_from"] = "later"; }) ==
        "s.json: steps[0].damping_from: unknown value \"later\" (expected one of: start, failure)");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["increments"] = 0; }) ==
        "s.json: steps[0].increments: must be in [1, 1000000], got 0");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["increments"] = 2000000000; }) ==
        "s.json: steps[0].increments: must be in [1, 1000000], got 2000000000");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["force_tolerance"] = 0; }) ==
        "s.json: steps[0].force_tolerance: must be > 0, got 0");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["max_cutbacks"] = -1; }) ==
        "s.json: steps[0].max_cutbacks: must be in [0, 50], got -1");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["max_cutbacks"] = 2000; }) ==
        "s.json: steps[0].max_cutbacks: must be in [0, 50], got 2000");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["max_iterations"] = 1000000000; }) ==
        "s.json: steps[0].max_iterations: must be in [1, 10000], got 1000000000");
  CHECK(errorAfter([](Json& j) { j["steps"][0]["end_time"] = 0; }) ==
        "s.json: steps[0].end_time: must be after the start, 0, got 0");
  CHECK(errorAfter([](Json& j) {
          j["steps"].push_back({{"end_time", 1}});
        }) == "s.json: steps[1].end_time: must be after the previous step's end, 1, got 1");
  CHECK(errorAfter([](Json& j) {
          j["contact"] = {{"theta_cross_deg", 20}, {"theta_parallel_deg", 30}};
        }) == "s.json: contact.theta_parallel_deg: must not exceed theta_cross_deg (20)");
  CHECK(errorAfter([](Json& j) {
          j["contact"] = {{"friction", -0.1}};
        }) == "s.json: contact.friction: must be >= 0, got -0.1");
  CHECK(errorAfter([](Json& j) {
          j["contact"] = {{"penalty_change", 0.5}};
        }) == "s.json: contact.penalty_change: must be >= 1, got 0.5");
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"step_penetration", 2000}}; }) ==
        "s.json: contact.step_penetration: must be in [1, 1000], got 2000");
  // Lengths against the radii (R = 0.1): contact would be lost, or detection would not end.
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"proximity_distance", 0.19}}; }) ==
        "s.json: contact.proximity_distance: must exceed the sum of two touching fibres' radii "
        "(2 x 0.1 mm), got 0.19: closer fibres would not be sought for contact");
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"skin", 1e39}}; }) ==
        "s.json: contact.skin: must be at most 1e+06 mm, got 1e+39");
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"test_point_spacing", 1e-9}}; }) ==
        "s.json: contact.test_point_spacing: must be at least 1e-3 x the smallest radius (0.0001 "
        "mm), got 1e-09");
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"penalty_min", 0}}; }) ==
        "s.json: contact.penalty_min: must be > 0, got 0");
  CHECK(errorAfter([](Json& j) {
          j["fibres"][0]["geometry"]["points"][1] = {0, 0, 0};
        }) == "s.json: fibres[0].geometry.points[1]: repeats the previous point");
  CHECK(errorAfter([](Json& j) {
          j["fibres"][0]["geometry"]["director"] = {2, 0, 0};
        }) == "s.json: fibres[0].geometry.director: is parallel to the fibre's first segment");
  CHECK(
      errorAfter([](Json& j) {
        j["fibres"][0]["geometry"] = {{"type", "helix"}, {"radius", 1}, {"pitch", 1}, {"turns", 0}};
      }) == "s.json: fibres[0].geometry.turns: must not be 0");
}

TEST_CASE("scene errors: names — unknown, repeated, malformed") {
  CHECK(errorAfter([](Json& j) { j["groups"][0]["name"] = "b.end"; }) ==
        "s.json: groups[0].name: 'b.end' is an automatic group of fibre 'b'");
  CHECK(errorAfter([](Json& j) { j["groups"].push_back(j["groups"][0]); }) ==
        "s.json: groups[1].name: duplicate name 'mid' (also groups[0])");
  CHECK(errorAfter([](Json& j) { j["materials"].push_back(j["materials"][0]); }) ==
        "s.json: materials[1].name: duplicate name 'm' (also materials[0])");
  CHECK(errorAfter([](Json& j) { j["output"]["probes"].push_back(j["output"]["probes"][0]); }) ==
        "s.json: output.probes[1].name: duplicate name 'tip' (also output.probes[0])");
  CHECK(errorAfter([](Json& j) { j["fibres"][0]["name"] = "my beam"; }) ==
        "s.json: fibres[0].name: 'my beam' contains ' '; names use letters, digits, '_', '-' and "
        "'.'");
  CHECK(errorAfter([](Json& j) { j["materials"][0]["name"] = ""; }) ==
        "s.json: materials[0].name: must not be empty");
  CHECK(errorAfter([](Json& j) { j["boundary_conditions"][0]["group"] = "b.begin"; }) ==
        "s.json: boundary_conditions[0].group: unknown group 'b.begin' (known: b.all, b.end, "
        "b.start, mid)");
  CHECK(errorAfter([](Json& j) { j["output"]["probes"][0]["fibre"] = "c"; }) ==
        "s.json: output.probes[0].fibre: unknown fibre 'c' (did you mean 'b'?)");
  CHECK(errorAfter([](Json& j) {
          j["stabilisation"] = {{"stiffness", 1}, {"fibres", {"q"}}};
        }) == "s.json: stabilisation.fibres[0]: unknown fibre 'q' (did you mean 'b'?)");
  CHECK(errorAfter([](Json& j) {
          j["tools"] = {{{"name", "t"}, {"type", "plane"}, {"normal", {0, 0, 1}}},
                        {{"name", "t"}, {"type", "plane"}, {"normal", {0, 0, 1}}}};
        }) == "s.json: tools[1].name: duplicate name 't' (also tools[0])");
}

TEST_CASE("scene errors: groups, boundary conditions, loads and tables") {
  CHECK(errorAfter([](Json& j) { j["groups"][0]["nodes"] = {9}; }) ==
        "s.json: groups[0].nodes[0]: node 9 outside 0..8 (fibre 'b')");
  CHECK(errorAfter([](Json& j) {
          j["groups"][0]["nodes"] = {1, 2, 1};
        }) == "s.json: groups[0].nodes[2]: node 1 listed twice");
  CHECK(errorAfter([](Json& j) { j["groups"][0]["nodes"] = Json::array(); }) ==
        "s.json: groups[0].nodes: must list at least one node");
  CHECK(errorAfter([](Json& j) { j["output"]["probes"][0]["node"] = -1; }) ==
        "s.json: output.probes[0].node: node -1 outside 0..8 (fibre 'b')");
  // "end": the fibre's last node whatever its mesh; any other word is an error.
  CHECK(errorAfter([](Json& j) { j["output"]["probes"][0]["node"] = "end"; }) == "(no error)");
  CHECK(errorAfter([](Json& j) { j["output"]["probes"][0]["node"] = "tip"; }) ==
        "s.json: output.probes[0].node: expected a node index or \"end\", got \"tip\"");
  CHECK(errorAfter([](Json& j) {
          j["output"]["probes"][0]["node"] = "end";
          j["output"]["probes"][0]["fibre"] = "c";
        }) == "s.json: output.probes[0].fibre: unknown fibre 'c' (did you mean 'b'?)");
  CHECK(errorAfter([](Json& j) { j["boundary_conditions"][0]["type"] = "fix"; }) ==
        "s.json: boundary_conditions[0].dofs: required field missing for type \"fix\"");
  CHECK(errorAfter([](Json& j) { j["boundary_conditions"][0]["dofs"] = {"x"}; }) ==
        "s.json: boundary_conditions[0].dofs: only for type \"fix\" (clamp holds all nine DOFs, "
        "pin the three of x0)");
  CHECK(
      errorAfter([](Json& j) {
        j["boundary_conditions"][0] = {{"type", "fix"}, {"group", "b.start"}, {"dofs", {"x", "w"}}};
      }) ==
      "s.json: boundary_conditions[0].dofs[1]: unknown DOF \"w\" (expected x, y, z, g1x, g1y, g1z, "
      "g2x, g2y, g2z, x0, g1 or g2)");
  CHECK(errorAfter([](Json& j) {
          j["boundary_conditions"][0] = {
              {"type", "fix"}, {"group", "b.start"}, {"dofs", Json::array()}};
        }) == "s.json: boundary_conditions[0].dofs: a fix must hold at least one DOF");
  CHECK(errorAfter([](Json& j) {
          j["boundary_conditions"].push_back({{"type", "pin"}, {"group", "b.all"}});
        }) ==
        "s.json: boundary_conditions[1]: holds DOF x of node 0 of fibre 'b', already held by "
        "boundary_conditions[0] (group 'b.start')");
  CHECK(errorAfter([](Json& j) { j["boundary_conditions"][0]["table"] = "ramp"; }) ==
        "s.json: boundary_conditions[0].table: scales \"displacement\", which is missing");
  CHECK(errorAfter([](Json& j) {
          j["boundary_conditions"][0]["rotation"] = {{"axis", {0, 0, 1}}};
        }) == "s.json: boundary_conditions[0].rotation.angle: required field missing");
  CHECK(errorAfter([](Json& j) {
          j["boundary_conditions"][0]["rotation"] = {{"axis", {0, 0, 0}}, {"angle", "ramp"}};
        }) == "s.json: boundary_conditions[0].rotation.axis: must be a finite, non-zero vector");
  CHECK(errorAfter([](Json& j) {
          j["loads"][0]["table"] = {{0, 0}, {1, 1}, {1, 2}};
        }) == "s.json: loads[0].table[2]: time 1 does not follow 1 (times must increase strictly)");
  CHECK(errorAfter([](Json& j) {
          j["loads"][0]["table"] = {{0, 0, 1}};
        }) == "s.json: loads[0].table[0]: expected a point [t, v], got an array");
  CHECK(errorAfter([](Json& j) { j["loads"][0]["table"] = Json::array(); }) ==
        "s.json: loads[0].table: must have at least one point [t, v]");
  CHECK(errorAfter([](Json& j) { j["loads"][0]["table"] = 3; }) ==
        "s.json: loads[0].table: expected a table [[t, v], ...] or a table name, got the number 3");
  CHECK(errorAfter([](Json& j) {
          j["tables"] = {{"ramp", {{0, 0}, {1, "one"}}}};
        }) == "s.json: tables.ramp[1][1]: expected a number, got a string \"one\"");
  CHECK(errorAfter([](Json& j) { j["loads"][0]["type"] = "line_force"; }) ==
        "s.json: loads[0].group: group 'b.end' holds no whole element for a line force");
  CHECK(errorAfter([](Json& j) { j["loads"][0].erase("vector"); }) ==
        "s.json: loads[0].vector: required field missing");
}

TEST_CASE("scene errors: a repeated key is found wherever it is") {
  const std::string text =
      R"({"units": "mm-N-MPa", "materials": [{"name": "m", "young_modulus": 1}],
          "fibres": [{"name": "f", "material": "m", "radius": 1, "elements": 1,
                      "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
          "steps": [{"end_time": 1}, {"end_time": 2, "increments": 2, "increments": 4}]})";
  CHECK(errorOf([&] { loadSceneFromString(text, "r.json"); }) ==
        "r.json: steps[1].increments: duplicate field");
}

TEST_CASE("scene errors: a self-contact separation not below the shortest fibre's length") {
  // Self-contact pairs points of one fibre at least the separation apart along it: 100 mm on
  // fibres of 10 and 8.25 mm left the loop no self-contact at all, silently.
  const auto withSeparation = [](double separation) {
    return errorAfter([&](Json& j) {
      j["fibres"].push_back(j["fibres"][0]);
      j["fibres"][1]["name"] = "loop";
      j["fibres"][1]["geometry"]["points"] = {{0, 1, 0}, {8.25, 1, 0}};
      j["contact"] = {{"self_contact", true}, {"self_contact_separation", separation}};
    });
  };
  const std::string tail =
      ": with self-contact on, no two points of that fibre are that far apart along it, so it "
      "would pass through itself unseen; give a separation below 8.25 mm, or leave it out for the "
      "derived default";
  CHECK(withSeparation(100) ==
        "s.json: contact.self_contact_separation: must be less than the shortest fibre's length, "
        "8.25 mm (fibre 'loop'), got 100" + tail);
  CHECK(withSeparation(8.25) ==
        "s.json: contact.self_contact_separation: must be less than the shortest fibre's length, "
        "8.25 mm (fibre 'loop'), got 8.25" + tail);
  CHECK(withSeparation(8.2) == "(no error)");
  // A helix's length is its arc length: 2 turns of radius 0.5 and pitch 0 are 6.28 mm.
  CHECK(errorAfter([](Json& j) {
          j["fibres"][0]["geometry"] = {{"type", "helix"}, {"radius", 0.5}, {"pitch", 0}, {"turns", 2}};
          j["contact"] = {{"self_contact", true}, {"self_contact_separation", 7}};
        }).starts_with("s.json: contact.self_contact_separation: must be less than the shortest "
                       "fibre's length, 6.28319 mm (fibre 'b'), got 7: "));
}

TEST_CASE("scene errors: a self-contact separation given with self-contact off") {
  const std::string expected =
      "s.json: contact.self_contact_separation: given (0.5 mm) while self_contact is off (false, "
      "or absent: its default), where it has no effect; set \"self_contact\": true, or remove the "
      "separation";
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"self_contact_separation", 0.5}}; }) == expected);
  CHECK(errorAfter([](Json& j) {
          j["contact"] = {{"self_contact", false}, {"self_contact_separation", 0.5}};
        }) == expected);
  CHECK(errorAfter([](Json& j) {
          j["contact"] = {{"self_contact", true}, {"self_contact_separation", 0.5}};
        }) == "(no error)");
  CHECK(errorAfter([](Json& j) { j["contact"] = {{"self_contact", false}}; }) == "(no error)");
}
