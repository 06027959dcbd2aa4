// Viscous continuation (a step's `damping`, systems/stabilisation.h): a rod clamped at both
// ends, one end turned 10 turns about the rod axis while moved 5 mm towards the other (no
// contact), passes limit points of the twist where load control stops; the viscous force the
// report gives is the static residual of the final state, measured independently by assembling
// it with the continuation off; the force vanishes where the state stops moving. With
// damping_from "failure" the step is load-controlled until an increment fails, then damped to its
// end (c = 1e-3 then fails in the snap, at t = 0.446, and 1e-2, 3e-3 and 3e-2 do not: the
// continuation's path after load control is not the damped-from-the-start one).
#include "engine/world_state.h"
#include "io/scene_loader.h"
#include "twisted_rod.h"

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

using namespace fibra;

namespace {

SceneDef twistedRod(double damping, int increments) {
  return loadSceneFromString(
      test::twistedRodScene(increments, "\"damping\": " + std::to_string(damping)), "rod.json");
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

TEST_CASE("damping_from failure: load control until it fails, then the continuation to the step's end") {
  // Load control of the twisted rod fails at its snap (the first case above). With
  // damping_from "failure" the same step runs undamped to that failure, bitwise as load control,
  // then takes the failed increment again with the continuation on and reaches the end; a run
  // resumed after that point ends where the uninterrupted one does.
  WorldState plain;
  plain.scene = twistedRod(0, 50);
  buildWorld(plain);
  std::vector<Eigen::VectorXd> plainStates;
  StepReport last;
  while ((last = advance(plain)).status == StepStatus::Converged) plainStates.push_back(plain.fibres.q);
  REQUIRE(last.status == StepStatus::Failed);
  REQUIRE(plainStates.size() < 49);

  SceneDef scene = twistedRod(1e-2, 50);
  scene.steps[0].dampingFrom = DampingFrom::Failure;
  WorldState w;
  w.scene = scene;
  buildWorld(w);
  std::vector<StepReport> reports;
  std::string checkpoint;
  while (w.step < 1) {
    reports.push_back(advance(w));
    INFO(reports.back().message);
    INFO(w.time);
    REQUIRE(reports.back().status == StepStatus::Converged);
    const size_t n = reports.size();
    if (n <= plainStates.size()) {
      CHECK(w.fibres.q == plainStates[n - 1]);  // bitwise: nothing damped yet
      CHECK(reports.back().viscousForce == 0);
      CHECK(reports.back().dampedFrom == -1);
    } else if (n == plainStates.size() + 1) {
      CHECK(reports.back().dampedFrom == plain.time);  // on where load control stopped
      CHECK(reports.back().viscousForce > 0);
    } else {
      CHECK(reports.back().dampedFrom == -1);
      CHECK(reports.back().viscousForce > 0);
    }
    if (n == plainStates.size() + 3) {
      std::ostringstream out;
      saveCheckpoint(w, out);
      checkpoint = out.str();
    }
  }
  CHECK(w.time == 1);
  CHECK(w.dampedStep == 0);

  WorldState resumed;
  resumed.scene = scene;
  buildWorld(resumed);
  std::istringstream in(checkpoint);
  restoreCheckpoint(resumed, in);
  CHECK(resumed.dampedStep == 0);
  while (resumed.step < 1) REQUIRE(advance(resumed).status == StepStatus::Converged);
  CHECK(resumed.fibres.q == w.fibres.q);
}
