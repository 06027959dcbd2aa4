// Viscous continuation (a step's `damping`, systems/stabilisation.h): a rod clamped at both
// ends, one end turned 10 turns about the rod axis while moved 5 mm towards the other (no
// contact), passes limit points of the twist where load control stops; the viscous force the
// report gives is the static residual of the final state, measured independently by assembling
// it with the continuation off; the force vanishes where the state stops moving.
#include "engine/world_state.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <cmath>

using namespace fibra;

namespace {

SceneDef twistedRod(double damping, int increments) {
  return loadSceneFromString(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [{"name": "rod", "material": "m", "radius": 0.1, "elements": 20,
                "geometry": {"type": "polyline", "points": [[0, 0, 0], [5, 0.001, 0], [10, 0, 0]],
                             "director": [0, 0, 1]}}],
    "boundary_conditions": [
      {"type": "clamp", "group": "rod.start"},
      {"type": "clamp", "group": "rod.end", "displacement": [-5, 0, 0],
       "rotation": {"axis": [1, 0, 0], "angle": [[0, 0], [1, 62.83185307179586]]}}],
    "steps": [{"end_time": 1, "increments": )" + std::to_string(increments) +
                                 R"(, "damping": )" + std::to_string(damping) + "}]}",
                             "rod.json");
}

// |r on the free DOFs| / F_ref, F_ref = max(|f_ext|, |reactions|, floor), directors / R.
double relativeFreeResidual(const WorldState& w) {
  const LinearSystem& ls = w.system;
  double free2 = 0, held2 = 0;
  for (Index d = 0; d < ls.r.size(); ++d) {
    const double w2 = d % kNodeDofs < 3 ? 1.0 : 1 / (w.lengthScale * w.lengthScale);
    (ls.equation[d] >= 0 ? free2 : held2) += w2 * ls.r(d) * ls.r(d);
  }
  return std::sqrt(free2) / std::max({ls.fext.norm(), std::sqrt(held2), w.forceFloor});
}

// Advances to the end or to the first failure; returns the reports.
std::vector<StepReport> run(WorldState& w) {
  std::vector<StepReport> reports;
  while (w.step < int(w.scene.steps.size())) {
    reports.push_back(advance(w));
    if (reports.back().status != StepStatus::Converged) break;
  }
  return reports;
}

}  // namespace

TEST_CASE("viscous continuation carries a twisted rod past the limit point where load control stops") {
  WorldState plain;
  plain.scene = twistedRod(0, 50);
  buildWorld(plain);
  const std::vector<StepReport> p = run(plain);
  CHECK(p.back().status == StepStatus::Failed);
  CHECK(plain.time < 0.7);

  WorldState w;
  w.scene = twistedRod(1e-3, 50);
  buildWorld(w);
  const std::vector<StepReport> r = run(w);
  REQUIRE(r.back().status == StepStatus::Converged);
  CHECK(w.time == 1);
  const double reported = r.back().viscousForce;
  CHECK(reported > 0);

  // The same state with the continuation off: its free residual is the viscous force.
  w.stabilisation.viscous = 0;
  assembleResidual(w, w.time);
  CHECK(relativeFreeResidual(w) == doctest::Approx(reported).epsilon(1e-6).scale(0));
}

TEST_CASE("the viscous force decays where the state stops moving") {
  // Twist to 10 turns with damping, then hold the ends and let the flow go on: the viscous
  // force falls as the rod settles.
  WorldState w;
  w.scene = twistedRod(1e-3, 50);
  StepDef hold = w.scene.steps[0];
  hold.endTime = 2;
  hold.increments = 10;
  w.scene.steps.push_back(hold);
  buildWorld(w);
  const std::vector<StepReport> r = run(w);
  REQUIRE(r.back().status == StepStatus::Converged);
  REQUIRE(r.size() == 60);
  CHECK(r.back().viscousForce < 0.2 * r[49].viscousForce);
}
