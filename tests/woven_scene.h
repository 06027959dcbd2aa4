// A scene with one woven_fabric generator named "fab" for the generator's tests
// (test_fabric_generator.cpp, test_fabric_crimped.cpp): the material, the pattern, the yarn
// counts and the keys every yarn of both directions shares (spacing, fibres_per_yarn, ...); the
// fabric's low-x and low-y edges clamped, one step.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace fibra::test {

inline nlohmann::json wovenScene(const nlohmann::json& material, const nlohmann::json& pattern,
                                 int warps, int wefts, const nlohmann::json& yarn) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "units": "mm-N-MPa",
    "generators": [{"type": "woven_fabric", "name": "fab"}],
    "boundary_conditions": [{"type": "clamp", "group": "fab.edge.xmin"},
                            {"type": "clamp", "group": "fab.edge.ymin"}],
    "steps": [{"increments": 1}]
  })");
  s["materials"] = nlohmann::json::array({material});
  nlohmann::json& g = s["generators"][0];
  g["pattern"] = pattern;
  for (const char* dir : {"warp", "weft"}) {
    g[dir] = yarn;
    g[dir]["yarns"] = std::string(dir) == "warp" ? warps : wefts;
    g[dir]["material"] = material["name"];
  }
  return s;
}

}  // namespace fibra::test
