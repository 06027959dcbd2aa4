// The twisted rod of the continuation tests, as scene text: L = 10 mm, R = 0.1 mm,
// E = 4000 MPa, 20 quadratic elements, both ends clamped, one end turned 10 turns about the rod
// axis while moved 5 mm towards the other, no contact; a 1 um kink at mid-length breaks the
// symmetry. Load control fails at its snap; `step` is the JSON of its one step's extra keys.
#pragma once

#include <string>

namespace fibra::test {

inline std::string twistedRodScene(int increments, const std::string& step) {
  return R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [{"name": "rod", "material": "m", "radius": 0.1, "elements": 20,
                "geometry": {"type": "polyline", "points": [[0, 0, 0], [5, 0.001, 0], [10, 0, 0]],
                             "director": [0, 0, 1]}}],
    "boundary_conditions": [
      {"type": "clamp", "group": "rod.start"},
      {"type": "clamp", "group": "rod.end", "displacement": [-5, 0, 0],
       "rotation": {"axis": [1, 0, 0], "angle": [[0, 0], [1, 62.83185307179586]]}}],
    "steps": [{"end_time": 1, "increments": )" +
         std::to_string(increments) + (step.empty() ? "" : ", " + step) + "}]}";
}

}  // namespace fibra::test
