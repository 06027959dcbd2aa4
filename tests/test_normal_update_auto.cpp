// contact normal_update "auto" (engine/step_driver.cpp retryNormals, slowNormalLoop): an
// attempt that fails with loop B's normals is tried again at the same size with every fibre
// normal linearised in Newton, and a step whose retry converged keeps them; an attempt that
// converges with loop B's normals slowly (more than max_iterations Newton iterations, more
// passes than detections) switches the step's next attempts to them without a failure. A
// 7-fibre bundle (bench/contact_scenes.h) twisted a quarter turn under tension, mu = 0.3: in 6
// increments (p_max 5e-4) the loop's run needs a cutback and "auto" switches after the first
// twist increment, nothing is cut back and under a third of the Newton iterations (98 against
// 315) are spent; in 4 increments the first twist increment fails with the loop's normals and
// the retry converges; in 3 (p_max 1e-4) the retry fails too and a slow loop B switches later.
// The bundle's torque and axial force at the end are those of the loop's run (the friction path
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

SceneDef twistIn(int increments, double pMax, NormalUpdate mode) {
  SceneDef s = scenes::twistedBundle(1, 10, pMax, 0.3);
  s.steps.back().increments = increments;
  s.contact.normalUpdate = mode;
  return s;
}

struct Outcome {
  int iterations = 0, cutbacks = 0, retries = 0, linearised = 0, switched = 0;
  std::vector<NormalChange> changes;  // every increment's, in order
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
    o.switched += r.normalsSwitched;
    o.changes.insert(o.changes.end(), r.normalChanges.begin(), r.normalChanges.end());
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

// Loop's and auto's runs of a scene; auto's resumed from the checkpoints `resumeAfter`.
std::pair<Outcome, Outcome> loopAndAuto(int increments, double pMax,
                                        std::vector<size_t> resumeAfter) {
  World loopWorld(twistIn(increments, pMax, NormalUpdate::Loop));
  const Outcome loop = solve(loopWorld);
  const SceneDef scene = twistIn(increments, pMax, NormalUpdate::Auto);
  World autoWorld(scene);
  const Outcome automatic = solve(autoWorld);
  MESSAGE("loop: " << loop.iterations << " iterations, " << loop.cutbacks << " cutbacks; auto: "
                   << automatic.iterations << ", " << automatic.cutbacks << " cutbacks, "
                   << automatic.retries << " retries, " << automatic.switched << " switches, "
                   << automatic.linearised << " increments linearised");
  CHECK(loop.retries == 0);
  CHECK(loop.switched == 0);
  CHECK(loop.changes.empty());
  CHECK(std::abs(loop.torque) > 0.1);
  CHECK(automatic.torque == doctest::Approx(loop.torque).epsilon(1e-3).scale(0));
  CHECK(automatic.axial == doctest::Approx(loop.axial).epsilon(1e-3).scale(0));
  REQUIRE(automatic.checkpoints.size() == size_t(2 + increments));
  for (size_t k : resumeAfter) {
    CAPTURE(k);
    World resumed(scene);
    std::istringstream in(automatic.checkpoints[k]);
    resumed.restoreCheckpoint(in);
    const Outcome rest = solve(resumed);
    CHECK(rest.checkpoints.back() == automatic.checkpoints.back());
  }
  return {loop, automatic};
}

}  // namespace

TEST_CASE("normal_update auto switches a slow loop B to linearised normals: a twisted bundle without cutbacks") {
  CHECK(ContactDef{}.normalUpdate == NormalUpdate::Auto);  // the default
  // resumed before the switching increment (the pull's last), after it, and one later
  const auto [loop, automatic] = loopAndAuto(6, 5e-4, {1, 2, 4});
  CHECK(loop.cutbacks > 0);
  CHECK(automatic.cutbacks == 0);
  CHECK(automatic.retries == 0);
  CHECK(automatic.switched == 1);
  CHECK(automatic.changes == std::vector<NormalChange>{NormalChange::Switched});
  CHECK(automatic.linearised == 5);  // every twist increment after the first
  CHECK(2 * automatic.iterations < loop.iterations);  // measured: 98 against 315
}

TEST_CASE("normal_update auto retries a failed attempt with linearised normals and keeps them") {
  // resumed before the retried increment, and after it
  const auto [loop, automatic] = loopAndAuto(4, 5e-4, {1, 2, 3});
  CHECK(loop.cutbacks > 0);
  CHECK(automatic.cutbacks == 0);
  CHECK(automatic.retries == 1);
  CHECK(automatic.switched == 0);
  CHECK(automatic.changes == std::vector<NormalChange>{NormalChange::RetryConverged});
  CHECK(automatic.linearised == 4);  // the retried increment and the rest of the twist
  CHECK(2 * automatic.iterations < loop.iterations);  // measured: 89 against 263
}

TEST_CASE("normal_update auto: a failed retry leaves the attempt as newton_frictionless leaves it, and a slow loop B still switches") {
  // The same twist in 3 increments, p_max 1e-4: the first twist attempt fails with loop B's
  // normals, the retry with every normal linearised fails as well, and the increment goes on from
  // the attempt before it (the size of its cutback), as with "newton_frictionless": the same
  // cutback and first sub-increment. Its sub-increments then converge slowly with loop B's
  // normals, and the step switches to linearised ones (a failed retry does not stop the switch):
  // the rest of the twist costs fewer Newton iterations and ends at the same torque and axial
  // force to 1e-3.
  SceneDef base = scenes::twistedBundle(1, 10, 1e-4, 0.3);
  base.steps.back().increments = 3;
  SceneDef frictionless = base, automatic = base;
  frictionless.contact.normalUpdate = NormalUpdate::NewtonFrictionless;
  automatic.contact.normalUpdate = NormalUpdate::Auto;
  World a(frictionless), b(automatic);
  std::vector<StepReport> ra, rb;
  while (!a.finished()) {
    ra.push_back(a.step()), rb.push_back(b.step());
    REQUIRE(ra.back().status == StepStatus::Converged);
    REQUIRE(rb.back().status == StepStatus::Converged);
    MESSAGE("t = " << ra.back().time << ": " << ra.back().totalIterations << " / "
                   << rb.back().totalIterations << " iterations, cutbacks " << ra.back().cutbacks
                   << " / " << rb.back().cutbacks << ", retries " << rb.back().normalRetries
                   << std::string(rb.back().normalsSwitched ? ", switched" : ""));
  }
  CHECK(b.finished());
  REQUIRE(ra.size() == 5);
  for (size_t k = 0; k < 2; ++k) CHECK(rb[k].totalIterations == ra[k].totalIterations);  // the pull
  // the first twist increment: the retry fails, the cutback is the attempt before it's
  CHECK(rb[2].normalRetries == 1);
  CHECK(ra[2].cutbacks >= 1);
  CHECK(rb[2].cutbacks == ra[2].cutbacks);
  CHECK(rb[2].normalsSwitched);
  CHECK(rb[2].normalChanges ==
        std::vector<NormalChange>{NormalChange::RetryFailed, NormalChange::Switched});
  CHECK(rb[2].message.find("every fibre normal linearised at t = 1.33333: ") == 0);
  CHECK(ra[2].message.find("cutback at t = 1.33333: ") == 0);
  int restA = 0, restB = 0;
  for (size_t k = 3; k < 5; ++k) {
    CHECK(rb[k].normalsLinearised);
    CHECK(rb[k].normalRetries == 0);
    restA += ra[k].totalIterations, restB += rb[k].totalIterations;
  }
  CHECK(2 * restB < restA);  // measured: 25 against 161
  for (Index c = 1; c < Index(base.bcs.size()); c += 2) {
    CHECK(b.reaction(c).moment.x() == doctest::Approx(a.reaction(c).moment.x()).epsilon(1e-3).scale(1e-3));
    CHECK(b.reaction(c).force.x() == doctest::Approx(a.reaction(c).force.x()).epsilon(1e-3).scale(1e-3));
  }
}

TEST_CASE("normal_update auto: no retry where no fibre normal can be linearised, and a failure lists its attempts") {
  // One fibre dragged over a cylinder (a tool): contact on, no fibre-fibre element, so a retry
  // "with every fibre normal linearised" would repeat the failed attempt exactly. With
  // max_iterations 2 the increment fails: "auto" must fail as "loop" does, iteration for
  // iteration, and the failure's message names the attempts before the last.
  const auto run = [](NormalUpdate mode, int cutbacks = 2) {
    SceneDef s;
    MaterialDef m;
    m.name = "m";
    m.youngModulus = 4000;
    s.materials.push_back(m);
    FibreDef f;
    f.name = "f";
    f.material = "m";
    f.radius = 0.1;
    f.elements = 8;
    f.geometry.points = {Vec3(-2, 0, 1.1), Vec3(2, 0, 1.1)};
    s.fibres.push_back(f);
    for (const char* end : {"f.start", "f.end"}) {
      BcDef b;
      b.kind = BcKind::Clamp;
      b.group = end;
      b.displacement = Vec3(0, 0, -0.2);
      s.bcs.push_back(b);
    }
    ToolDef t;
    t.name = "roller";
    t.kind = ToolKind::Cylinder;
    t.point = Vec3::Zero();
    t.direction = Vec3::UnitY();
    t.radius = 1;
    t.friction = 0.2;
    s.tools.push_back(t);
    s.contact.enabled = true;
    s.contact.normalUpdate = mode;
    StepDef st;
    st.increments = 1;
    st.maxIterations = 2;
    st.maxCutbacks = cutbacks;
    s.steps.push_back(st);
    World w(s);
    return w.step();
  };
  const StepReport loop = run(NormalUpdate::Loop), automatic = run(NormalUpdate::Auto);
  MESSAGE(automatic.message);
  REQUIRE(loop.status == StepStatus::Failed);
  CHECK(automatic.status == StepStatus::Failed);
  CHECK(automatic.normalRetries == 0);
  CHECK(automatic.normalChanges.empty());
  CHECK(automatic.totalIterations == loop.totalIterations);
  CHECK(automatic.message == loop.message);
  CHECK(loop.message.find("failed after 2 cutbacks") != std::string::npos);
  CHECK(loop.message.find(". Before it, 2 failed attempts of the increment (what followed at t: "
                          "why): cutback at t = 1: ") != std::string::npos);
  // a longer list: the first two and the last three in full, the count of the others
  const StepReport many = run(NormalUpdate::Auto, 7);
  REQUIRE(many.status == StepStatus::Failed);
  CHECK(many.message.find("Before it, 7 failed attempts of the increment") != std::string::npos);
  CHECK(many.message.find("... 2 more ...; ") != std::string::npos);
}
