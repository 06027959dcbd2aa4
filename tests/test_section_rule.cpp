// Section rule on twisted references: a helical wire of a seven-wire strand (lay angle 11.8 deg,
// R = 1.865 mm on a helix of radius 3.835 mm), clamped at both ends and stretched by 1e-3.
// A pretwisted wire couples stretch and twist through the metric's variation across the section
// (A3 = V0 + xi1 V3 + xi2 V4, with V3, V4 carrying the reference twist); the default rule must
// capture it: its end torque equals a fine quadrature's (4 x 48, itself converged to 1e-6 against
// 4 x 24) within 0.5%. The `moments` rule, which freezes the metric at the centroid, does not
// (it is kept for straight references, where both rules agree exactly).
#include "engine/world.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace fibra;

namespace {

constexpr double kPitch = 115.34112130484495;  // mm, one lay length: tan(11.8 deg) = 2 pi r / p

// The wire's end torque about its axis (N mm) after the stretch, for the given integration
// section ("" keeps the default).
double endTorque(const std::string& integration, int elements) {
  const std::string integ = integration.empty() ? "" : R"(, "integration": )" + integration;
  const SceneDef scene = loadSceneFromString(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "steel", "young_modulus": 188000, "poisson_ratio": 0.3}],
    "fibres": [{"name": "w", "material": "steel", "radius": 1.865, "elements": )" +
                                                 std::to_string(elements) + R"(,
                "geometry": {"type": "helix", "radius": 3.835, "pitch": 115.34112130484495,
                             "turns": 1, "origin": [0, 0, 0], "axis": [0, 0, 1]})" +
                                                 integ + R"(}],
    "boundary_conditions": [{"type": "clamp", "group": "w.start"},
                            {"type": "clamp", "group": "w.end",
                             "displacement": [0, 0, 0.11534112130484495]}],
    "steps": [{"end_time": 1, "increments": 1}],
    "output": {"vtu": false, "moment_point": [0, 0, 115.34112130484495]}})",
                                             "helix_wire.json");
  World w(scene);
  while (!w.finished()) REQUIRE(w.step().status == StepStatus::Converged);
  return w.reaction(1).moment.z();
}

}  // namespace

TEST_CASE("the default section rule is converged on a twisted helical wire") {
  const int elements = 20;
  const double fine = endTorque(R"({"section": "quadrature", "rings": 4, "sectors": 48})", elements);
  const double finer = endTorque(R"({"section": "quadrature", "rings": 4, "sectors": 24})", elements);
  CHECK(std::abs(finer - fine) <= 1e-6 * std::abs(fine));
  const double byDefault = endTorque("", elements);
  CHECK(std::abs(byDefault - fine) <= 5e-3 * std::abs(fine));
  // The centroid-metric rule misses the stretch-twist coupling: off by far more than 0.5%.
  const double moments = endTorque(R"({"section": "moments"})", elements);
  CHECK(std::abs(moments - fine) > 0.2 * std::abs(fine));
  MESSAGE("end torque: default " << byDefault << ", moments " << moments << ", 4x48 " << fine
                                 << " N mm");
}
