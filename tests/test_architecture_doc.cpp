// docs/ARCHITECTURE.md shows the stages of a contact scene as the code builds them: its generated
// section must be exactly what World::describe() gives for samples/bundle_squeeze.json
// (regenerate it with `fibra describe samples/bundle_squeeze.json`).
#include "engine/world.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

using namespace fibra;
using namespace fibra::test;

TEST_CASE("docs/ARCHITECTURE.md shows the stages the code builds for the bundle sample") {
  const std::string doc = readFile(sourcePath("docs/ARCHITECTURE.md"));
  const std::string begin = "<!-- generated: fibra describe samples/bundle_squeeze.json -->\n";
  const std::string end = "<!-- end generated -->";
  const size_t a = doc.find(begin), b = doc.find(end);
  REQUIRE(a != std::string::npos);
  REQUIRE(b != std::string::npos);
  const std::string shown = doc.substr(a + begin.size(), b - a - begin.size());
  const World world(loadScene(sourcePath("samples/bundle_squeeze.json")));
  CHECK(shown == world.describe());
  CHECK(shown.find("| fibre contact law |") != std::string::npos);
}
