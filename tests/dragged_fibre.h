// A fibre B (L = 3 mm) on a parallel, fully held fibre A under a line load q(t) = 0.05 min(t / 0.2,
// 1) N/mm, its ends dragged 0.3 t mm along the axis with friction mu, in 20 increments (tests of
// parallel sliding friction and of the energy balance).
#pragma once

#include "io/scene_loader.h"

#include <string>

namespace fibra::test {

inline constexpr double kQ = 0.05, kL = 3;  // line load, N/mm; B's length, mm

inline SceneDef draggedFibre(double mu) {
  std::string text = R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [
      {"name": "A", "material": "m", "radius": 0.1, "elements": 20,
       "geometry": {"type": "line", "points": [[-3, 0, 0], [3, 0, 0]], "director": [0, 0, 1]}},
      {"name": "B", "material": "m", "radius": 0.1, "elements": 10,
       "geometry": {"type": "line", "points": [[-1.5, 0, 0.2], [1.5, 0, 0.2]], "director": [0, 0, 1]}}],
    "boundary_conditions": [
      {"type": "clamp", "group": "A.all"},
      {"type": "fix", "group": "B.start", "dofs": ["x", "y", "g1y"], "displacement": [0.3, 0, 0]},
      {"type": "fix", "group": "B.end", "dofs": ["y"]}],
    "loads": [{"type": "line_force", "group": "B.all", "vector": [0, 0, -0.05],
               "table": [[0, 0], [0.2, 1], [1, 1]]}],
    "contact": {"max_reversible_slip": 0.0005, "max_penetration": 0.0005, "friction": )";
  text += std::to_string(mu);
  text += R"(},
    "stabilisation": {"stiffness": 1e-6, "fibres": ["B"]},
    "steps": [{"end_time": 1, "increments": 20}]})";
  return loadSceneFromString(text, "dragged.json");
}

}  // namespace fibra::test
