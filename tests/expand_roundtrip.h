// `fibra expand` on a generator scene, as the generator tests use it (tests only): the scene is
// written with a comment line first, expanded by the program, and both files loaded.
#pragma once

#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <utility>

namespace fibra::test {

// Checks that `fibra expand` exits 0 and writes exactly expandScene's text, without generators;
// returns the scene loaded from the original (DIR/generated.json) and from the expanded file
// (DIR/plain.json).
inline std::pair<SceneDef, SceneDef> expandRoundTrip(const TempDir& dir, const nlohmann::json& j) {
  fs::create_directories(dir.path());
  const std::string scene = dir / "generated.json", expanded = dir / "plain.json";
  writeFile(scene, "// a comment\n" + j.dump(2));
  const RunResult r = runFibra({"expand", scene, "--out", expanded}, dir);
  REQUIRE_MESSAGE(r.status == 0, r.output);
  const std::string text = readFile(expanded);
  CHECK(text == expandScene(scene));
  CHECK(nlohmann::json::parse(text).contains("generators") == false);
  return {loadScene(scene), loadScene(expanded)};
}

}  // namespace fibra::test
