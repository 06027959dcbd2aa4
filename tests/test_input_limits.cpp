// Hostile sizes cost neither memory nor time: a generator asked for 1e8 elements and a file
// nested 100 000 brackets deep are refused with a field-named error at once (both took gigabytes
// before: the generator allocated its fibres, the reader a path per nesting level).
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

#include <string>

using namespace fibra;
using namespace fibra::test;

TEST_CASE("a generator refuses more than a million elements before making any") {
  const std::string text = R"({"units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 1000}],
    "generators": [{"type": "yarn", "name": "y", "material": "m", "fibres": 100000,
                    "fibre_radius": 0.01, "length": 1, "elements": 1000}],
    "steps": [{"end_time": 1}]})";
  const std::string e = errorOf([&] { loadSceneFromString(text, "big.json"); });
  CHECK(e.find("big.json: generators[0].elements: 100000 fibres x 1000 elements") == 0);
  CHECK(e.find("more than a generator makes") != std::string::npos);
}

TEST_CASE("a scene nested deeper than 64 levels is refused where it goes too deep") {
  const std::string text = R"({"generators": )" + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
  const std::string e = errorOf([&] { loadSceneFromString(text, "deep.json"); });
  CHECK(e.find("deep.json: generators[0][0]") == 0);
  CHECK(e.find("nested deeper than 64 levels") != std::string::npos);
}
