// A SceneDef filled in code (no scene file, no validateScene) still gets errors that name the
// fields as the scene file does (docs/SCENE.md), not by their C++ names.
#include "engine/world.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

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
}
