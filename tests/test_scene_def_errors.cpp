// Scene errors that name the field as the scene file does (docs/SCENE.md): a SceneDef filled in
// code (no scene file, no validateScene), and numbers a double cannot hold.
#include "engine/world.h"
#include "io/scene_loader.h"
#include "io/scene_validate.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace fibra;
using namespace fibra::test;

TEST_CASE("contact parameters set in code are reported by their scene names") {
  const SceneDef base = loadScene(sourcePath("samples/bundle_squeeze.json"));
  const auto errorWith = [&](auto change) {
    SceneDef s = base;
    change(s.contact);
    return errorOf([&] { World world(s); });
  };
  CHECK(errorWith([](ContactDef& c) {
          c.thetaCross = 0.2;
          c.thetaParallel = 0.3;
        }) == "contact.theta_parallel_deg: must not exceed theta_cross_deg");
  CHECK(errorWith([](ContactDef& c) { c.thetaCross = 2; }) ==
        "contact.theta_cross_deg: must not exceed 90 degrees");
  CHECK(errorWith([](ContactDef& c) { c.proximityDistance = -1; }) ==
        "contact.proximity_distance: must be a finite value >= 0");
  CHECK(errorWith([](ContactDef& c) { c.skin = -1; }) ==
        "contact.skin: must be a finite value >= 0");
  CHECK(errorWith([](ContactDef& c) { c.testPointSpacing = 0; }) ==
        "contact.test_point_spacing: must be > 0");
  CHECK(errorWith([](ContactDef& c) { c.frictionHoldAfter = 256; }) ==
        "contact.friction_hold_after: must be in [0, 255], got 256");
  CHECK(errorWith([](ContactDef& c) { c.frictionHoldTolerance = 0; }) ==
        "contact.friction_hold_tolerance: must be in (0, 1], got 0");
  CHECK(errorWith([](ContactDef& c) { c.normalAcceleration = -1; }) ==
        "contact.normal_acceleration: must be in [0, 10], got -1");
  CHECK(errorWith([](ContactDef& c) { c.normalAcceleration = 11; }) ==
        "contact.normal_acceleration: must be in [0, 10], got 11");
  CHECK(errorWith([](ContactDef& c) { c.stepPenetration = 0.5; }) ==
        "contact.step_penetration: must be in [1, 1000], got 0.5");
  CHECK(errorWith([](ContactDef& c) { c.stepPenetration = std::nan(""); }) ==
        "contact.step_penetration: must be in [1, 1000], got nan");
}

TEST_CASE("a number beyond a double's range is a scene error naming its field") {
  const std::string text = R"({"units": "mm-N-MPa",
    "materials": [{"name": "a", "young_modulus": 1e999}]})";
  CHECK(errorOf([&] { loadSceneFromString(text, "big.json"); }) ==
        "big.json: materials[0].young_modulus: the number 1e999 is out of range (a double's "
        "magnitude is at most 1.8e308)");
}

TEST_CASE("long bad values are cut to 40 characters in messages") {
  const std::string longName(5000, 'x');
  const std::string cut = std::string(37, 'x') + "...";
  SceneDef s = loadScene(sourcePath("samples/cantilever.json"));
  s.fibres[0].material = longName;  // an unknown material
  const std::string unknown = errorOf([&] { validateScene(s); });
  CHECK(unknown.find("'" + cut + "'") != std::string::npos);
  CHECK(unknown.size() < 200);
  s = loadScene(sourcePath("samples/cantilever.json"));
  s.fibres[0].name = longName + " ";  // a bad character
  const std::string badName = errorOf([&] { validateScene(s); });
  CHECK(badName.starts_with("fibres[0].name: '" + cut + "' contains ' '"));
  auto json = nlohmann::json::parse(readFile(sourcePath("samples/cantilever.json")), nullptr,
                                    true, true);
  json["steps"][0]["increments"] = longName;  // a string for a number
  const std::string type = errorOf([&] { loadSceneFromString(json.dump(), "s.json"); });
  CHECK(type == "s.json: steps[0].increments: expected an integer, got a string \"" +
                    std::string(36, 'x') + "...");
}
