// Hostile sizes cost neither memory nor time: a generator asked for 1e8 elements and a file
// nested 100 000 brackets deep are refused with a field-named error at once (both took gigabytes
// before: the generator allocated its fibres, the reader a path per nesting level).
#include "engine/world.h"
#include "io/scene_loader.h"
#include "limited_child.h"
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

namespace {

// A one-fibre scene whose fibre has `elements` and `geometry` (JSON text).
std::string oneFibre(const std::string& elements, const std::string& geometry,
                     const std::string& integration = "{}") {
  return R"({"units": "mm-N-MPa", "materials": [{"name": "m", "young_modulus": 1000}],
    "fibres": [{"name": "f", "material": "m", "radius": 0.1, "elements": )" +
         elements + R"(, "geometry": )" + geometry + R"(, "integration": )" + integration +
         R"(}], "steps": [{"end_time": 1}]})";
}

const char* const kLine = R"({"type": "line", "points": [[0, 0, 0], [1, 0, 0]]})";

}  // namespace

// Found by the fuzz test (tests/test_scene_fuzz.cpp): each ended with exit 1 and a message
// naming no field ("cannot create std::vector larger than max_size()", "std::bad_alloc" after
// minutes and 19 GB, "beam reference: degenerate section frame"), or hung past SIGTERM.
TEST_CASE("a fibre's elements, sectors and coordinates are bounded, with the field named") {
  const std::pair<std::string, std::string> cases[] = {
      {oneFibre("2147483647", kLine),
       "fibres[0].elements: brings the scene to 2.14748e+09 beam elements, more than fibra "
       "takes (1e+06)"},
      {oneFibre("4", kLine, R"({"sectors": 10000000})"),
       "fibres[0].integration.sectors: must be in [3, 360], got 10000000"},
      {oneFibre("4", R"({"type": "helix", "radius": 1, "pitch": 1, "turns": 1,
                         "origin": [0, 1e308, 0]})"),
       "fibres[0].geometry.origin: coordinates must be at most 1e+06 mm in size"},
      {oneFibre("4", R"({"type": "line", "points": [[0, 0, 0], [0, 3.5e9, 0]]})"),
       "fibres[0].geometry.points[1]: coordinates must be at most 1e+06 mm in size"},
      {oneFibre("4", R"({"type": "helix", "radius": 1, "pitch": 1, "turns": 1,
                         "axis": [0, 1e308, 0]})"),
       "fibres[0].geometry.axis: is too long: its length overflows a double"},
      {R"({"units": "mm-N-MPa", "materials": [{"name": "m", "young_modulus": 1000}],
          "fibres": [{"name": "f", "material": "m", "radius": 1e308, "elements": 4,
                      "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
          "steps": [{"end_time": 1}]})",
       "fibres[0].radius: must be at most 1e+06 mm in size, got 1e+308"},
      {oneFibre("4", R"({"type": "helix", "radius": 1, "pitch": -1e300, "turns": 1})"),
       "fibres[0].geometry.pitch: must be at most 1e+06 mm in size, got -1e+300"},
  };
  for (const auto& [text, expected] : cases) {
    CAPTURE(text);
    CHECK(errorOf([&] { loadSceneFromString(text, "s.json"); }) == "s.json: " + expected);
  }
}

TEST_CASE("a polyline corner inside an element is refused with the fibre and where, not a crash") {
  // The corner at s = 3 mm falls 7e-5 mm inside element 11 (h = 0.25 mm): its quadratic element
  // bends tighter than R = 0.1 mm and the section frame folds (was: exit 1, "beam reference:
  // degenerate section frame", no field; found by a new user, 2026-12-06). On a node it builds.
  const auto scene = [](const char* corner) {
    return loadSceneFromString(std::string(R"({"units": "mm-N-MPa",
      "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
      "fibres": [{"name": "f", "material": "m", "radius": 0.1, "elements": 18,
        "geometry": {"type": "polyline", "points": [[0, 0, 0], [3, 0, 0], )") + corner +
                                   R"(], "director": [0, 0, 1]}}],
      "steps": [{"end_time": 1}]})", "corner.json");
  };
  const std::string e = errorOf([&] { World w(scene("[3, 1.5001, 0]")); });
  CHECK(e.rfind("fibres[0].geometry: the reference section folds between s = 2.75006 and 3.00007 mm", 0) == 0);
  CHECK(errorOf([&] { World w(scene("[3, 1.5, 0]")); }) == "(no error)");
}

TEST_CASE("a scene that needs more memory than the process may use is refused before building") {
  TempDir scratch("memory_limit");
  fs::create_directories(scratch.path());
  const std::string scene = scratch / "big.json";
  writeFile(scene, oneFibre("900000", kLine));
  ChildLimits limits;  // 2 GiB of address space
  const ChildResult r = runLimited(FIBRA_BINARY, {"check", scene}, scratch / "log", limits);
  CHECK(r.status == 2);
  CHECK(readFile(scratch / "log") ==
        "fibra: error: " + scene +
            ": fibres[0].elements: brings the scene to 900000 beam elements, which need about "
            "21.6 GB, more than the 2.1 GB this process may use\n");
}
