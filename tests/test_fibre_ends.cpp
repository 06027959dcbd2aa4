// Fibre ends as finite bodies: a fibre is a cylinder cut flat at its end sections, and its end
// face (centre and rim) touches the tools (systems/tool_detection.h). A vertical fibre (R = 0.1,
// L = 2, E = 4000), clamped at the top, is brought end-first onto a rigid plane and pressed
// 0.002 mm past touch: its end face rests on the plane within p_max, and the plane carries
// EA x the fibre's shortening (a straight bar: F = E pi R^2 (0.002 + z_tip) / L).
#include "engine/world.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace fibra;

TEST_CASE("a fibre's flat end face rests on a plane and carries EA x its shortening") {
  const SceneDef scene = loadSceneFromString(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [{"name": "f", "material": "m", "radius": 0.1, "elements": 6,
                "geometry": {"type": "line", "points": [[0, 0, 0.05], [0, 0, 2.05]],
                             "director": [1, 0, 0]}}],
    "tools": [{"name": "wall", "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}],
    "boundary_conditions": [{"type": "clamp", "group": "f.end", "displacement": [0, 0, -0.052],
                             "table": [[0, 0], [0.5, 0.8653846153846154], [1, 1]]}],
    "steps": [{"end_time": 1, "increments": 10}]})",
                                             "end_on_plane.json");
  World w(scene);
  const double pMax = 5e-4, EA = 4000 * std::numbers::pi * 0.01;
  // The top's displacement -0.052 f(t), f piecewise linear through (0, 0), (0.5, a), (1, 1):
  // the end touches when 0.052 f = 0.05.
  const double a = 0.8653846153846154;
  const auto f = [a](double t) { return t <= 0.5 ? 2 * a * t : a + (1 - a) * (t - 0.5) / 0.5; };
  int pressed = 0;
  while (!w.finished()) {
    REQUIRE(w.step().status == StepStatus::Converged);
    const double tip = x0Of(w.fibres().q, 0).z();
    const double force = -w.toolReaction(0).z();  // the fibre pushes the wall down
    const double reach = 0.052 * f(w.time());       // how far the top has come down, mm
    CAPTURE(w.time());
    if (reach < 0.05 - 2 * pMax) {  // still above the wall: no force
      CHECK(tip > 0);
      CHECK(force == 0);
      continue;
    }
    if (reach < 0.05 + 0.001) continue;  // touching: the penalty is being adapted
    ++pressed;
    CHECK(tip >= -1.5 * pMax);
    CHECK(tip <= pMax);
    const double shortening = tip - 0.05 + reach;  // L - current length, mm
    CHECK(force == doctest::Approx(EA * shortening / 2).epsilon(0.03));
  }
  CHECK(pressed >= 1);
}
