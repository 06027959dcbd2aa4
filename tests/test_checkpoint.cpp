// The increment checkpoint: after a failed or cancelled increment the world is at its last
// converged state — not only the positions, but the residual, the reactions, the tool reactions
// and every contact element (fibre-fibre and fibre-tool) with its forces, bitwise; after a
// cutback, the last converged state may be a sub-increment.
#include "beam_fixtures.h"
#include "contact_scenes.h"
#include "observed_state.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace fibra;
using namespace fibra::test;

namespace {

// The sliding crossing (tests/contact_scenes.h): step 1 presses (2 increments) and converges;
// step 2 slides B's ends in one increment with one Newton iteration and no cutback allowed: it
// cannot converge.
SceneDef slidingCrossing() {
  StepDef slide;
  slide.maxIterations = 1;
  slide.maxCutbacks = 0;
  return fibra::test::slidingCrossing(2, slide);
}

// Solves step 1 and returns what it converged to.
Observed firstStep(World& w) {
  while (w.currentStep() == 0) REQUIRE(w.step().status == StepStatus::Converged);
  const Observed o = observe(w);
  REQUIRE(o.contacts.size() > 0);
  int tool = 0;
  for (auto t : o.contacts.tool) tool += t;
  REQUIRE(tool > 0);
  REQUIRE(o.toolReaction.norm() > 0);
  return o;
}

}  // namespace

TEST_CASE("a failed increment leaves residual, reactions and contact forces at the last converged state") {
  World w(slidingCrossing());
  const Observed converged = firstStep(w);
  const StepReport r = w.step();
  REQUIRE(r.status == StepStatus::Failed);
  checkSame(observe(w), converged);
  // And again: a second failed attempt from the restored state fails the same way.
  CHECK(w.step().status == StepStatus::Failed);
  checkSame(observe(w), converged);
}

TEST_CASE("a cancelled increment leaves residual, reactions and contact forces at the last converged state") {
  SceneDef s = slidingCrossing();
  s.steps[1].maxIterations = 30;
  int iterationsOfStep2 = 0;
  WorldDef def;
  def.progress = [&](const Progress& p) { iterationsOfStep2 += p.step == 1; };
  def.cancel = [&] { return iterationsOfStep2 >= 2; };
  World w(s, def);
  const Observed converged = firstStep(w);
  REQUIRE(w.step().status == StepStatus::Cancelled);
  CHECK(iterationsOfStep2 >= 2);
  checkSame(observe(w), converged);
}

TEST_CASE("a failure after a converged sub-increment leaves the world at that sub-increment") {
  // A cantilever whose end moment is small up to t = 0.5 and then jumps to a full roll-up: the
  // whole increment fails, its first half converges, the second half fails again.
  BeamSpec b;
  b.radius = 0.01;
  SceneDef s = straightBeam(b, 1);
  clampStart(s);
  tipLoad(s, LoadKind::Moment, Vec3(0, 0, 2 * std::numbers::pi * bendingStiffness(b) / b.length));
  s.loads.back().table = {{0, 0.5, 1}, {0, 0.01, 1}};
  s.steps[0].maxIterations = 8;
  s.steps[0].maxCutbacks = 1;
  World w(s);
  const StepReport r = w.step();
  REQUIRE(r.status == StepStatus::Failed);
  CHECK(r.cutbacks == 2);
  CHECK(r.time == 0.5);
  CHECK(w.time() == 0.5);
  CHECK(w.fibres().q != w.fibres().qRef);
  // The world shows a converged state: its residual vanishes on the free DOFs.
  const Eigen::VectorXd residual = w.residual();
  double free2 = 0, held2 = 0;
  for (Index d = 0; d < residual.size(); ++d) (d < kNodeDofs ? held2 : free2) += residual(d) * residual(d);
  CHECK(std::sqrt(free2) <= 1e-6 * std::sqrt(held2));
  // Trying again starts from there and ends there.
  const Eigen::VectorXd q = w.fibres().q;
  CHECK(w.step().status == StepStatus::Failed);
  CHECK(w.time() == 0.5);
  CHECK(w.fibres().q == q);
}
