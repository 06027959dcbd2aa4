// contact normal_update "auto" (engine/step_driver.cpp retryNormals): an attempt that fails
// with loop B's normals is tried again at the same size with every fibre normal linearised in
// Newton, and a step whose retry converged keeps them. A 7-fibre bundle (bench/contact_scenes.h)
// twisted a quarter turn in 6 increments under tension, mu = 0.3: with "loop" the twist needs
// cutbacks; with "auto" the failed attempt is retried, the rest of the twist keeps the
// linearised normals, nothing is cut back, about half the Newton iterations are spent, and the
// bundle's torque and axial force at the end are those of the loop's run (the friction path
// differs, so not bitwise: to 1e-3). A run resumed from any of its increments' checkpoints ends
// bitwise where the uninterrupted run ends (the step's choice is carried).
#include "bench/contact_scenes.h"
#include "engine/world.h"

#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

using namespace fibra;

namespace {

SceneDef twistIn6(NormalUpdate mode) {
  SceneDef s = scenes::twistedBundle(1, 10, 5e-4, 0.3);
  s.steps.back().increments = 6;
  s.contact.normalUpdate = mode;
  return s;
}

struct Outcome {
  int iterations = 0, cutbacks = 0, retries = 0, linearised = 0;
  double torque = 0, axial = 0;  // N mm about x and N along x, the twisted ends' reactions
  std::vector<std::string> checkpoints;  // after each increment
};

Outcome solve(World& w) {
  Outcome o;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    o.iterations += r.totalIterations;
    o.cutbacks += r.cutbacks;
    o.retries += r.normalRetries;
    o.linearised += r.normalsLinearised;
    std::ostringstream out;
    w.saveCheckpoint(out);
    o.checkpoints.push_back(out.str());
  }
  for (Index b = 1; b < Index(w.scene().bcs.size()); b += 2) {  // the ends (start, end pairs)
    o.torque += w.reaction(b).moment.x();
    o.axial += w.reaction(b).force.x();
  }
  return o;
}

}  // namespace

TEST_CASE("normal_update auto retries a failed attempt with linearised normals: a twisted bundle without cutbacks") {
  CHECK(ContactDef{}.normalUpdate == NormalUpdate::Auto);  // the default
  World loopWorld(twistIn6(NormalUpdate::Loop));
  const Outcome loop = solve(loopWorld);
  World autoWorld(twistIn6(NormalUpdate::Auto));
  const Outcome automatic = solve(autoWorld);
  MESSAGE("loop: " << loop.iterations << " iterations, " << loop.cutbacks << " cutbacks; auto: "
                   << automatic.iterations << ", " << automatic.cutbacks << " cutbacks, "
                   << automatic.retries << " retries, " << automatic.linearised
                   << " increments linearised");
  CHECK(loop.cutbacks > 0);
  CHECK(loop.retries == 0);
  CHECK(automatic.cutbacks == 0);
  CHECK(automatic.retries >= 1);
  CHECK(automatic.linearised >= 2);  // the retried increment and the rest of the twist
  CHECK(4 * automatic.iterations < 3 * loop.iterations);  // measured: 163 against 315
  CHECK(std::abs(loop.torque) > 0.1);
  CHECK(automatic.torque == doctest::Approx(loop.torque).epsilon(1e-3).scale(0));
  CHECK(automatic.axial == doctest::Approx(loop.axial).epsilon(1e-3).scale(0));

  // Resumed from a checkpoint before the retried increment and from two after it.
  const SceneDef scene = twistIn6(NormalUpdate::Auto);
  REQUIRE(automatic.checkpoints.size() == 8);
  for (size_t k : {size_t(3), size_t(4), size_t(5)}) {
    CAPTURE(k);
    World resumed(scene);
    std::istringstream in(automatic.checkpoints[k]);
    resumed.restoreCheckpoint(in);
    const Outcome rest = solve(resumed);
    CHECK(rest.checkpoints.back() == automatic.checkpoints.back());
  }
}

TEST_CASE("normal_update auto: a failed retry leaves the step as newton_frictionless leaves it") {
  // The same twist in 4 increments: the retry with every normal linearised fails as well, and
  // the step goes on from the attempt before it (its predictor, the size of its cutback), as
  // with "newton_frictionless": the same sub-increments and cutbacks, increment by increment.
  SceneDef base = scenes::twistedBundle(1, 10, 5e-4, 0.3);
  base.steps.back().increments = 4;
  SceneDef frictionless = base, automatic = base;
  frictionless.contact.normalUpdate = NormalUpdate::NewtonFrictionless;
  automatic.contact.normalUpdate = NormalUpdate::Auto;
  World a(frictionless), b(automatic);
  int retries = 0, cutbacks = 0;
  while (!a.finished()) {
    const StepReport ra = a.step(), rb = b.step();
    REQUIRE(ra.status == StepStatus::Converged);
    REQUIRE(rb.status == StepStatus::Converged);
    CAPTURE(ra.time);
    CHECK(rb.cutbacks == ra.cutbacks);
    CHECK(rb.subIncrements == ra.subIncrements);
    CHECK(rb.smallestIncrement == doctest::Approx(ra.smallestIncrement).epsilon(1e-12));
    retries += rb.normalRetries;
    cutbacks += ra.cutbacks;
    MESSAGE("t = " << ra.time << ": " << ra.totalIterations << " / " << rb.totalIterations
                   << " iterations, cutbacks " << ra.cutbacks << " / " << rb.cutbacks
                   << ", retries " << rb.normalRetries);
  }
  CHECK(b.finished());
  CHECK(retries >= 1);
  CHECK(cutbacks >= 1);
}
