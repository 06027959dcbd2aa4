// Loop B accelerated (contact `normal_acceleration`, systems/normal_acceleration.h): a fibre
// lying on a parallel fibre under a heavy line load is laterally unstable, and loop B's plain
// fixed point on the normals diverges in the lateral mode; the Anderson-mixed normals converge
// to the straight (symmetric) equilibrium with fixed normals in Newton ("loop"). With the
// default "newton_frictionless", an increment whose loop B diverges starts again with the
// frictionless parallel normals linearised in Newton, and the full 10 mm case converges.
#include "contact_scenes.h"
#include "engine/world.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

using namespace fibra;
using fibra::test::heavyLineContact;

namespace {

// Largest |y| of U's centreline nodes, mm.
double lateral(const World& w) {
  const FibreStore& fs = w.fibres();
  double y = 0;
  for (Index n = fs.firstNode[0]; n < fs.firstNode[0] + fs.nodeCount[0]; ++n)
    y = std::max(y, std::abs(x0Of(fs.q, n).y()));
  return y;
}

// The straight equilibrium of the heavy line contact of `length` mm under q = 1 N/mm, checked
// on the finished world against independent measures; `axial`: the largest axial reaction of
// U's start over the run (N).
void checkStraight(const World& w, double length, double axial) {
  const double q = 1.0;  // N/mm
  CHECK(w.time() == doctest::Approx(1));
  CHECK(lateral(w) <= 1e-5);  // the straight equilibrium (1e-4 R), not rolled off
  CHECK(axial <= 1e-3 * q * length);  // frictionless: no axial reaction
  // The load reaches D as q L whatever the elements say: D's support reaction (independent of the
  // contact elements), then the elements' own line force in the middle 2 mm.
  CHECK(w.reaction(2).force.z() == doctest::Approx(q * length).epsilon(1e-6).scale(0));
  const ContactElementStore& el = w.contact().elements;
  const ContactForceStore& f = w.contact().forces;
  double total = 0;
  int inner = 0;
  for (Index e = 0; e < el.size(); ++e) {
    total += f.normalForce[e];
    const double s = el.fibreI[e] == 0 ? el.sI[e] : el.sJ[e];  // on U, from its start, mm
    if (std::abs(s - length / 2) > 1) continue;
    CAPTURE(s);
    CHECK(f.normalForce[e] / el.length[e] == doctest::Approx(q).epsilon(0.02).scale(0));
    ++inner;
  }
  CHECK(inner >= 4);
  CHECK(total == doctest::Approx(w.reaction(2).force.z()).epsilon(1e-3).scale(0));
}

}  // namespace

TEST_CASE("the Anderson-mixed normals hold a heavy parallel line contact straight") {
  World w(loadSceneFromString(heavyLineContact(R"(, "normal_update": "loop")"), "heavy.json"));
  REQUIRE(w.scene().contact.normalAcceleration > 0);  // on by default
  double axial = 0;
  int mixes = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    axial = std::max(axial, std::abs(w.reaction(0).force.x()));
    mixes += r.contact.normalMixes;
  }
  CHECK(mixes > 0);
  checkStraight(w, 6, axial);
}

TEST_CASE("the full heavy line contact converges: a diverging loop B restarts with linearised normals") {
  // line_contact_heavy (10 mm): with "loop" the first detection of an increment already leaves
  // the secant's range and the run fails at t = 0.7. The default restarts such an increment
  // with the frictionless parallel normals in Newton.
  World w(loadSceneFromString(heavyLineContact("", 10), "heavy.json"));
  REQUIRE(w.scene().contact.normalUpdate == NormalUpdate::Auto);  // the default
  CHECK(loadSceneFromString(heavyLineContact(R"(, "normal_update": "newton_frictionless")"), "h.json")
            .contact.normalUpdate == NormalUpdate::NewtonFrictionless);
  double axial = 0;
  int restarts = 0, cutbacks = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    axial = std::max(axial, std::abs(w.reaction(0).force.x()));
    restarts += r.contact.normalRestarts;
    cutbacks += r.cutbacks;
  }
  MESSAGE("restarts " << restarts << ", cutbacks " << cutbacks);
  CHECK(restarts > 0);
  CHECK(cutbacks == 0);
  checkStraight(w, 10, axial);
  // The same scene with loop B alone fails.
  World loop(loadSceneFromString(heavyLineContact(R"(, "normal_update": "loop")", 10), "h.json"));
  bool failed = false;
  while (!loop.finished() && !failed) failed = loop.step().status != StepStatus::Converged;
  CHECK(failed);
}

// The heavy line contact (10 mm) with mu = 0.3, loaded frictionless (friction_factor 0) and then held
// with friction in two increments where nothing prescribed changes.
std::string frictionalHold(bool facing) {
  nlohmann::json j = nlohmann::json::parse(heavyLineContact("", 10));
  j["contact"]["friction"] = 0.3;
  j["contact"]["facing_particles"] = facing;
  j["steps"] = {{{"name", "load"}, {"end_time", 1}, {"increments", 5}, {"friction_factor", 0}},
                {{"name", "hold"}, {"end_time", 2}, {"increments", 2}}};
  return j.dump();
}

TEST_CASE("a frictional hold after the frictionless load of the heavy line contact holds the state") {
  // With the paper's material particles the hold stalled (loop A capped, stagnation at t = 1.5);
  // with facing particles (the default) the load ends where the hold's detection finds the same
  // contact, and the hold's increments start in equilibrium.
  World w(loadSceneFromString(frictionalHold(true), "hold.json"));
  int holdIterations = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    if (r.step == 1) holdIterations = std::max(holdIterations, r.totalIterations);
  }
  CHECK(w.time() == doctest::Approx(2));
  CHECK(holdIterations <= 2);
  CHECK(lateral(w) <= 1e-5);
  CHECK(w.reaction(2).force.z() == doctest::Approx(10.0).epsilon(1e-6));  // q L on D's support
  World paper(loadSceneFromString(frictionalHold(false), "hold.json"));
  bool failed = false;
  while (!paper.finished() && !failed) failed = paper.step().status != StepStatus::Converged;
  CHECK(failed);
}

TEST_CASE("without the acceleration loop B's fixed point loses the heavy line contact") {
  World w(loadSceneFromString(heavyLineContact(R"(, "normal_acceleration": 0, "normal_update": "loop")"), "heavy.json"));
  REQUIRE(w.scene().contact.normalAcceleration == 0);
  bool failed = false;
  while (!w.finished() && !failed) failed = w.step().status != StepStatus::Converged;
  CHECK(failed);
}
