// Fibre-fibre contact mechanics against closed-form results: two crossing beams pressed
// together share the load by their stiffnesses; two parallel beams under a line load transmit it
// uniformly; regenerating the contact elements without motion leaves the forces unchanged.
#include "contact_scenes.h"
#include "engine/world_state.h"
#include "fd_tangent.h"
#include "systems/friction_history.h"

#include "systems/contact_queries.h"

#include <doctest/doctest.h>

using namespace fibra;
using namespace fibra::test;

namespace {

bool solveAll(World& w) {
  while (!w.finished())
    if (w.step().status != StepStatus::Converged) return false;
  return true;
}

double totalNormalForce(const World& w) {
  double sum = 0;
  for (double r : w.contact().forces.normalForce) sum += r;
  return sum;
}

}  // namespace

TEST_CASE("two crossing simply supported beams pressed at midspan share the load equally") {
  const double P = 0.01;
  double previousError = 1;
  for (double pMax : {1e-3, 1e-4, 1e-5}) {
    CAPTURE(pMax);
    World w(crossingBeams(P, pMax));
    REQUIRE(solveAll(w));
    const double error = std::abs(totalNormalForce(w) / (P / 2) - 1);
    CHECK(error < previousError);  // converges as p_max -> 0
    previousError = error;
    double deepest = 0;
    for (double g : w.contact().forces.gap) deepest = std::max(deepest, -g);
    CHECK(deepest <= pMax);
    if (pMax <= 1e-4) CHECK(error < 0.01);
  }
}

TEST_CASE("parallel beams under a uniform line load carry a uniform contact line force") {
  const double w = 0.01;  // N/mm
  World world(parallelBeams(w, 1e-4));
  REQUIRE(solveAll(world));
  const ContactElementStore& el = world.contact().elements;
  const ContactForceStore& m = world.contact().forces;
  REQUIRE(m.size() > 10);
  // Line force: each element stands for the length between its neighbours along A.
  std::vector<std::pair<double, double>> sf;  // (s on A, force)
  for (Index e = 0; e < m.size(); ++e) sf.emplace_back(el.fibreI[e] == 0 ? el.sI[e] : el.sJ[e], m.normalForce[e]);
  std::sort(sf.begin(), sf.end());
  const double L = 4;
  int checked = 0;
  for (size_t i = 1; i + 1 < sf.size(); ++i) {
    const double s = sf[i].first;
    if (s < 0.2 * L || s > 0.8 * L) continue;  // away from the ends
    const double spacing = 0.5 * (sf[i + 1].first - sf[i - 1].first);
    CHECK(sf[i].second / spacing == doctest::Approx(w).epsilon(0.02).scale(0));
    ++checked;
  }
  CHECK(checked >= 5);
  CHECK(totalNormalForce(world) == doctest::Approx(w * L).epsilon(0.02).scale(0));
}

namespace {

// A world with crossing beams, contact elements detected, the beams pushed into each other and
// slid by `slide` mm (B along y), and friction mu.
void pressedCrossing(WorldState& w, double slide, double mu) {
  w.scene = crossingBeams(0.01, 1e-3);
  w.scene.contact.friction = mu;
  w.scene.contact.maxReversibleSlip = 5e-4;
  buildWorld(w);
  runStage(w, w.pipeline.detect, 0);
  for (Index n = w.fibres.firstNode[1]; n < w.fibres.firstNode[1] + w.fibres.nodeCount[1]; ++n)
    x0Of(w.fibres.q, n) += Vec3(0.3 * slide, slide, -6e-4);
}

void assembleAt(WorldState& w, bool tangent) { runStage(w, w.pipeline.assemble, 0, tangent); }

}  // namespace

TEST_CASE("fibre contact tangent matches finite differences, in stick and in slip") {
  for (double slide : {1e-5, 3e-3}) {
    CAPTURE(slide);
    WorldState w;
    pressedCrossing(w, slide, 0.3);
    assembleAt(w, true);
    const ContactForceStore& f = w.trial.forces;
    REQUIRE(f.size() > 0);
    REQUIRE(f.normalForce[0] > 0);
    CHECK(bool(f.slip[0]) == (slide > 1e-3));
    const Eigen::MatrixXd K(w.system.K);
    const Eigen::MatrixXd Kfd = test::finiteDifferenceTangent(w, 0);
    CHECK((K - Kfd).norm() <= 1e-6 * K.norm());
  }
}

TEST_CASE("regenerating the contact elements without motion leaves the forces unchanged") {
  SceneDef s = parallelBeams(0.01, 1e-4);
  s.contact.friction = 0.2;
  s.contact.maxReversibleSlip = 5e-4;
  // Slide B along the beams so that the friction history is not trivial.
  hold(s, "B.start", {}, Vec3::Zero());
  s.bcs.erase(s.bcs.begin() + 2);  // B.start held in x, y, G1Y: replaced by a sliding hold
  hold(s, "B.start", {X, Y, G1Y}, Vec3(8e-3, 0, 0));  // 4 g_T,max per increment: slides
  WorldState w;
  w.scene = s;
  buildWorld(w);
  while (w.step < int(w.scene.steps.size())) REQUIRE(advance(w).status == StepStatus::Converged);
  // Regenerate at the converged state, record the history of these elements, regenerate again
  // with no motion: the second set must reproduce the first one's forces through the history.
  int sliding = 0;  // at the Coulomb limit as the report counts it (systems/contact_queries.h)
  const ContactForceStore& f = w.committed.forces;
  for (size_t e = 0; e < f.gRev.size(); ++e)
    sliding += fibra::sliding(f.normalForce[e], f.gRev[e], w.contact.gMax);
  CHECK(sliding > 0);  // the solved state slides: the history holds slips at g_T,max
  ContactState& t = w.trial;
  t = w.committed;
  runStage(w, w.pipeline.detect, w.time);
  assembleAt(w, false);
  recordFrictionHistory(w.fibres, t.elements, t.forces, t.toolElements, t.toolForces, t.history);
  const std::vector<Vec3> before = t.forces.force;
  runStage(w, w.pipeline.detect, w.time);
  assembleAt(w, false);
  REQUIRE(t.forces.force.size() == before.size());
  double diff = 0, size = 0;
  for (size_t e = 0; e < before.size(); ++e) {
    diff = std::max(diff, (t.forces.force[e] - before[e]).norm());
    size = std::max(size, before[e].norm());
  }
  CHECK(size > 0);
  CHECK(diff <= 1e-6 * size);
}
