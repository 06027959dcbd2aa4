// Resuming from a checkpoint (World::saveCheckpoint / restoreCheckpoint): a world built from the
// same scene and restored from the checkpoint of any converged increment ends bitwise where the
// uninterrupted world ends, with the same iterations on the way; a checkpoint that is truncated,
// corrupt or of another scene is refused with the reason and leaves the world unchanged.
#include "contact_scenes.h"
#include "io/scene_loader.h"
#include "observed_state.h"

#include <doctest/doctest.h>

#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace fibra;
using namespace fibra::test;

namespace {

// The sliding crossing (tests/contact_scenes.h), pressed in 3 increments, slid in 6 with an
// iteration limit that forces cutbacks, so that the attempt size carried between increments
// matters.
SceneDef slidingCrossing() {
  StepDef slide;
  slide.increments = 6;
  slide.maxIterations = 6;
  slide.maxCutbacks = 8;
  return fibra::test::slidingCrossing(3, slide);
}

// The checkpoint after w's next `increments` increments (each must converge).
std::string checkpointAfter(World& w, int increments) {
  for (int i = 0; i < increments; ++i) REQUIRE(w.step().status == StepStatus::Converged);
  std::ostringstream out;
  w.saveCheckpoint(out);
  return out.str();
}

struct Run {
  std::vector<std::string> checkpoints;  // after each converged increment
  std::vector<int> iterations;           // total Newton iterations of each increment
  int cutbacks = 0;
  EnergyBalance energy;
};

// Solves to the end (every increment must converge), saving a checkpoint after each.
Run solve(World& w) {
  Run run;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    run.iterations.push_back(r.totalIterations);
    run.cutbacks += r.cutbacks;
    run.energy = r.energy;
    run.checkpoints.push_back(checkpointAfter(w, 0));
  }
  return run;
}

void restore(World& w, const std::string& checkpoint) {
  std::istringstream in(checkpoint);
  w.restoreCheckpoint(in);
}

std::string refusal(World& w, const std::string& checkpoint) {
  try {
    restore(w, checkpoint);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a world restored from the checkpoint of any increment ends bitwise where the uninterrupted one ends") {
  const SceneDef scene = slidingCrossing();
  World full(scene);
  const Run reference = solve(full);
  const Observed end = observe(full);
  REQUIRE(reference.checkpoints.size() == 9);
  CHECK(reference.cutbacks > 0);  // the carried attempt size is exercised
  REQUIRE(end.contacts.size() > 0);

  for (size_t k = 0; k + 1 < reference.checkpoints.size(); ++k) {
    CAPTURE(k);
    World resumed(scene);
    restore(resumed, reference.checkpoints[k]);
    CHECK(resumed.time() == doctest::Approx(k < 3 ? (k + 1) / 3.0 : 1 + (k - 2) / 6.0));
    const Run rest = solve(resumed);
    REQUIRE(rest.iterations.size() == reference.iterations.size() - k - 1);
    for (size_t i = 0; i < rest.iterations.size(); ++i)
      CHECK(rest.iterations[i] == reference.iterations[k + 1 + i]);
    checkSame(observe(resumed), end);
    CHECK(rest.checkpoints.back() == reference.checkpoints.back());
    CHECK(rest.energy.friction == reference.energy.friction);
    CHECK(rest.energy.error() == reference.energy.error());
  }
}

TEST_CASE("a resumed world is restored from a checkpoint at its own state: nothing changes") {
  const SceneDef scene = slidingCrossing();
  World w(scene);
  const std::string state = checkpointAfter(w, 4);
  const Observed before = observe(w);
  restore(w, state);
  checkSame(observe(w), before);
  CHECK(w.currentStep() == 1);
}

TEST_CASE("a truncated, corrupt or foreign checkpoint is refused with its reason and the world is unchanged") {
  const SceneDef scene = slidingCrossing();
  World saved(scene);
  const std::string good = checkpointAfter(saved, 4);

  World w(scene);
  REQUIRE(w.step().status == StepStatus::Converged);
  const Observed before = observe(w);

  CHECK(refusal(w, "") == "not a fibra checkpoint");
  CHECK(refusal(w, "{\"materials\": []}") == "not a fibra checkpoint");
  // Every prefix of the file: refused, never a crash or a huge allocation.
  for (size_t n = 18; n < good.size(); n += 1 + n / 7) {
    CAPTURE(n);
    CHECK(refusal(w, good.substr(0, n)).find("truncated") != std::string::npos);
  }
  // One flipped bit anywhere after the header: corrupt (checksum or sizes).
  for (size_t at = 80; at < good.size(); at += 1 + good.size() / 40) {
    CAPTURE(at);
    std::string bad = good;
    bad[at] = char(bad[at] ^ 0x10);
    const std::string why = refusal(w, bad);
    CHECK((why.find("corrupt") != std::string::npos || why.find("truncated") != std::string::npos));
  }
  // Of another scene: other geometry, or other steps.
  SceneDef other = scene;
  other.steps[1].endTime = 3;
  World foreign(other);
  CHECK(refusal(foreign, good).find("another scene") != std::string::npos);
  SceneDef moved = scene;
  moved.fibres[0].geometry.points[0].x() += 1e-3;
  World elsewhere(moved);
  CHECK(refusal(elsewhere, good).find("another scene") != std::string::npos);
  for (const auto& change : std::vector<std::function<void(SceneDef&)>>{
           [](SceneDef& d) { d.fibres[1].radius *= 1.01; },
           [](SceneDef& d) { d.materials[0].youngModulus *= 2; },
           [](SceneDef& d) { d.loads[0].vector.z() *= 2; },
           [](SceneDef& d) { d.steps[1].increments = 5; },
           [](SceneDef& d) { d.contact.friction = 0.3; },
           [](SceneDef& d) { d.tools[0].friction = 0.1; },
           [](SceneDef& d) { d.steps[1].damping = 1e-3; }}) {  // no step had damping
    SceneDef edited = scene;
    change(edited);
    World differs(edited);
    CHECK(refusal(differs, good).find("another scene") != std::string::npos);
  }
  // What a user may change to get a stopped run going: limits, tolerances, output, and the
  // damping of a scene that has some.
  SceneDef limits = scene;
  limits.steps[1].maxIterations = 40;
  limits.steps[1].maxCutbacks = 20;
  limits.steps[1].forceTolerance = 1e-9;
  limits.output.vtu = false;
  World relaxed(limits);
  CHECK(refusal(relaxed, good).empty());
  CHECK(relaxed.time() == saved.time());
  SceneDef damped = scene;
  damped.steps[0].damping = 1e-3;
  World dampedWorld(damped);
  const std::string dampedState = checkpointAfter(dampedWorld, 4);
  damped.steps[0].damping = 2e-3;
  damped.steps[1].damping = 1e-3;
  World moreDamped(damped);
  CHECK(refusal(moreDamped, dampedState).empty());

  checkSame(observe(w), before);
  // And the refused world still solves as if nothing had happened.
  World twin(scene);
  REQUIRE(twin.step().status == StepStatus::Converged);
  REQUIRE(w.step().status == StepStatus::Converged);
  REQUIRE(twin.step().status == StepStatus::Converged);
  checkSame(observe(w), observe(twin));
}

TEST_CASE("resuming across increments restarted with linearised normals ends bitwise where the uninterrupted run ends") {
  // The 10 mm heavy line contact: loop B diverges at t = 0.6 and t = 1, and those increments
  // restart with linearised normals and a non-symmetric tangent (a new pattern), then the next
  // attempt goes back to the symmetric one.
  const SceneDef scene = loadSceneFromString(heavyLineContact("", 10), "heavy.json");
  World full(scene);
  const Run reference = solve(full);
  REQUIRE(reference.checkpoints.size() == 5);
  for (size_t k : {size_t(1), size_t(2)}) {  // before and after the first restarted increment
    CAPTURE(k);
    World resumed(scene);
    restore(resumed, reference.checkpoints[k]);
    const Run rest = solve(resumed);
    REQUIRE(rest.iterations.size() == reference.iterations.size() - k - 1);
    for (size_t i = 0; i < rest.iterations.size(); ++i)
      CHECK(rest.iterations[i] == reference.iterations[k + 1 + i]);
    CHECK(rest.checkpoints.back() == reference.checkpoints.back());
  }
}
