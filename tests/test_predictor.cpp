// The secant predictor (engine/step_driver.cpp, startAttempt): an attempt after the step's first
// converged one starts from q_n + dt v_n, v_n the rate of the last converged attempt, unless that
// start's residual is more than 10x the plain start's. Checked on samples/helix.json (a coil
// pulled by its clamped end, then let back: prescribed motion, elastic, so the equilibrium at
// each time does not depend on the path): the same equilibria as without the predictor, in
// fewer Newton iterations, no prediction in a step's first increment; on the roll-up (a beam
// curled by an end moment: load control) the extrapolated start is far out, so the predictor is
// dropped at every attempt and the run is bitwise the one without it.
#include "engine/world.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"
#include "store_bits.h"

#include <doctest/doctest.h>

using namespace fibra;
using namespace fibra::test;

namespace {

struct Run {
  std::vector<Eigen::VectorXd> q;  // the state at the end of every increment
  std::vector<StepReport> reports;
  int iterations = 0;              // Newton iterations of all attempts
};

Run solve(SceneDef s, bool predictor) {
  for (StepDef& st : s.steps) st.predictor = predictor;
  WorldDef def;
  def.threads = 1;
  World w(s, def);
  Run run;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    run.q.push_back(w.fibres().q);
    run.reports.push_back(r);
    run.iterations += r.totalIterations;
  }
  return run;
}

}  // namespace

TEST_CASE("secant predictor: the helix reaches the same equilibria in fewer Newton iterations") {
  const SceneDef s = loadScene(sourcePath("samples/helix.json"));
  const Run plain = solve(s, false), predicted = solve(s, true);
  REQUIRE(plain.q.size() == 10);
  REQUIRE(predicted.q.size() == 10);
  for (size_t k = 0; k < plain.q.size(); ++k) {
    CAPTURE(k);
    // Both ends converged to the force tolerance 1e-8: the states agree far below the coil's
    // 1 mm travel.
    CHECK((plain.q[k] - predicted.q[k]).lpNorm<Eigen::Infinity>() < 1e-7);
    const StepReport& r = predicted.reports[k];
    CHECK(plain.reports[k].predicted == 0);
    // No rate yet at a step's first increment (the pull, then the release); then every
    // increment starts from the predictor and converges from it.
    CHECK(r.predicted == (r.increment == 1 ? 0 : 1));
    CHECK(r.predictorRetries == 0);
  }
  MESSAGE("Newton iterations: " << plain.iterations << " plain, " << predicted.iterations
                                << " with the predictor");
  CHECK(predicted.iterations < plain.iterations * 3 / 4);
}

TEST_CASE("secant predictor: dropped where it raises the start residual, as on the load-controlled roll-up") {
  SceneDef s = loadScene(sourcePath("samples/rollup.json"));
  REQUIRE(s.steps.size() == 1);
  s.steps[0].increments = 8;
  const Run plain = solve(s, false), predicted = solve(s, true);
  REQUIRE(plain.q.size() == 8);
  for (size_t k = 0; k < plain.q.size(); ++k) {
    CAPTURE(k);
    CHECK(predicted.reports[k].predicted == 0);
    CHECK(sameBits(plain.q[k], predicted.q[k]));
  }
  CHECK(predicted.iterations == plain.iterations);
}
