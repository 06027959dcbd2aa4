// Fibre-fibre contact mechanics against closed-form results: two crossing beams pressed
// together share the load by their stiffnesses; two parallel beams under a line load transmit it
// uniformly; regenerating the contact elements without motion leaves the forces unchanged.
#include "contact_scenes.h"
#include "engine/world_state.h"
#include "fd_tangent.h"
#include "systems/friction_history.h"

#include "systems/contact_geometry.h"
#include "systems/contact_queries.h"
#include "systems/particle.h"

#include <Eigen/Geometry>
#include <numbers>

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
void pressedCrossing(WorldState& w, double slide, double mu, bool facing = false) {
  w.scene = crossingBeams(0.01, 1e-3);
  w.scene.contact.friction = mu;
  w.scene.contact.facingParticles = facing;
  w.scene.contact.maxReversibleSlip = 5e-4;
  buildWorld(w);
  runStage(w, w.pipeline.detect, 0);
  for (Index n = w.fibres.firstNode[1]; n < w.fibres.firstNode[1] + w.fibres.nodeCount[1]; ++n)
    x0Of(w.fibres.q, n) += Vec3(0.3 * slide, slide, -6e-4);
}

void assembleAt(WorldState& w, bool tangent) { runStage(w, w.pipeline.assemble, 0, tangent); }

// B's sections spun by `a` rad about its axis (y) after the detection (sheared: and made
// elliptical): its material particles roll off the line of centres.
void spinB(WorldState& w, double a, bool sheared = false) {
  const Eigen::Matrix3d spin = Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix();
  for (Index n = w.fibres.firstNode[1]; n < w.fibres.firstNode[1] + w.fibres.nodeCount[1]; ++n) {
    const Vec3 g1 = spin * Vec3(w.fibres.q.segment<3>(kNodeDofs * n + 3));
    const Vec3 g2 = spin * Vec3(w.fibres.q.segment<3>(kNodeDofs * n + 6));
    w.fibres.q.segment<3>(kNodeDofs * n + 3) = sheared ? Vec3(1.05 * g1) : g1;
    w.fibres.q.segment<3>(kNodeDofs * n + 6) = sheared ? Vec3(0.97 * g2 + 0.1 * g1) : g2;
  }
}

// Element 0's sections and the surfaces' gap along the normal its force used:
// (x0I - x0J) . N - R |G_I^T N| - R |G_J^T N| (systems/contact_queries.h halfWidth), mm.
struct ElementSections {
  Section I, J;
  double surfaceGap;
};
ElementSections elementSections(const WorldState& w) {
  const ContactElementStore& el = w.trial.elements;
  const Vec3 N = w.trial.forces.normal[0];
  const Section I = contactSection(w.fibres, w.fibres.q, el.fibreI[0], el.sI[0]);
  const Section J = contactSection(w.fibres, w.fibres.q, el.fibreJ[0], el.sJ[0]);
  const double RI = w.fibres.radius[el.fibreI[0]], RJ = w.fibres.radius[el.fibreJ[0]];
  return {I, J, (I.x0 - J.x0).dot(N) - halfWidth(I, RI, N) - halfWidth(J, RJ, N)};
}

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

TEST_CASE("frictionless contact acts on facing particles: the true gap, no torque about the axis, an exact tangent") {
  for (const bool sheared : {false, true}) {
    CAPTURE(sheared);
    WorldState w;
    pressedCrossing(w, 1e-5, 0, true);
    spinB(w, 20 * std::numbers::pi / 180, sheared);
    assembleAt(w, true);
    const ContactElementStore& el = w.trial.elements;
    const ContactForceStore& f = w.trial.forces;
    REQUIRE(f.size() == 1);
    REQUIRE(f.normalForce[0] > 0);
    REQUIRE(f.facing[0] == 1);
    // The gap is the surfaces' along N, from the sections, not from the particles.
    const Vec3 N = f.normal[0];
    const auto [I, J, surfaceGap] = elementSections(w);
    const double R = w.fibres.radius[0];
    CHECK(f.gap[0] == doctest::Approx(surfaceGap).epsilon(1e-12).scale(1e-3));
    // Circular sections: the force passes both axes, no moment about either fibre's tangent,
    // where the spun section's material particle had one (an elliptical section's extremal
    // point may carry one: its outline's normal there is N, its radius is not).
    for (int side = 0; side < 2 && !sheared; ++side) {
      CAPTURE(side);
      const Section& S = side == 0 ? I : J;
      const Vec3 F = (side == 0 ? 1.0 : -1.0) * f.force[0];
      const auto moment = [&](const ParticleWeights& p) {
        return (particlePosition(w.fibres.q, p) - S.x0).cross(F).dot(S.dx0ds.normalized());
      };
      CHECK(std::abs(moment(side == 0 ? f.facingI[0] : f.facingJ[0])) <= 1e-12 * F.norm() * R);
      if (side == 1) CHECK(std::abs(moment(el.sideJ[0])) > 0.3 * F.norm() * R);  // sin 20 deg
    }
    // Against central differences, with the outlines' rolling stiffness (without it: 6e-6 of
    // |K| off, sheared, against 4e-9 with it).
    REQUIRE(w.system.symmetric);  // frictionless, loop B converged: the upper triangle is stored
    const Eigen::MatrixXd K = Eigen::MatrixXd(w.system.K).selfadjointView<Eigen::Upper>();
    const Eigen::MatrixXd Kfd = test::finiteDifferenceTangent(w, 0);
    CHECK((K - Kfd).norm() <= 1e-7 * K.norm());
    // Newton's step limit measures the gap's change on the facing particles (dg/dq), not on
    // the spun material ones: a step closing by 10x what it allows is cut to 0.1.
    Eigen::VectorXd dq = Eigen::VectorXd::LinSpaced(w.fibres.q.size(), -1, 1).array().sin();
    const auto closing = [&](const ParticleWeights& a, const ParticleWeights& b) {
      return N.dot(particlePosition(dq, a) - particlePosition(dq, b));
    };
    if (closing(f.facingI[0], f.facingJ[0]) > 0) dq = -dq;
    const double allowed = w.contact.stepPenetration * w.trial.zones.pMax[el.zone[0]];
    dq *= 10 * std::max(f.gap[0] + allowed, allowed) / -closing(f.facingI[0], f.facingJ[0]);
    CHECK(std::abs(closing(el.sideI[0], el.sideJ[0]) / closing(f.facingI[0], f.facingJ[0]) - 1) > 1e-3);
    CHECK(stepLimit(w.contact, w.trial, dq) == doctest::Approx(0.1).epsilon(1e-12));
  }
  // Off (the default): the material particles, as before.
  WorldState w;
  pressedCrossing(w, 1e-5, 0);
  assembleAt(w, false);
  REQUIRE(w.trial.forces.size() == 1);
  CHECK(w.trial.forces.facing.empty());  // nor any facing column stored
}

TEST_CASE("frictional contact on facing particles: the normal force on the outlines, friction's slip between the material particles, an exact tangent") {
  // The crossing with mu = 0.3, B's sections spun by 20 deg after the detection (its material
  // particle moves R sin 20 deg = 0.034 mm: in stick with g_T,max = 0.1 mm, in slip with 5e-4
  // and B slid 3e-3 mm): the gap is the surfaces' (as frictionless), the slip the material
  // particles' trial g_rev,0 + P (d - d_0), and the non-symmetric tangent, with the coupling of
  // the normal force into friction, matches central differences.
  for (double slide : {1e-5, 3e-3}) {
    CAPTURE(slide);
    WorldState w;
    pressedCrossing(w, slide, 0.3, true);
    if (slide < 1e-3) w.contact.gMax = 0.1;
    const double a = 20 * std::numbers::pi / 180;
    spinB(w, a);
    assembleAt(w, true);
    const ContactElementStore& el = w.trial.elements;
    const ContactForceStore& f = w.trial.forces;
    REQUIRE(f.size() == 1);
    REQUIRE(f.normalForce[0] > 0);
    REQUIRE(f.facing[0] == 1);
    CHECK(bool(f.slip[0]) == (slide > 1e-3));
    const Vec3 N = f.normal[0];
    const double R = w.fibres.radius[0];
    CHECK(f.gap[0] == doctest::Approx(elementSections(w).surfaceGap).epsilon(1e-12).scale(1e-3));
    // the material particles' gap is R (1 - cos 20 deg) wider on B's side
    const Vec3 d = particlePosition(w.fibres.q, el.sideI[0]) - particlePosition(w.fibres.q, el.sideJ[0]);
    CHECK(d.dot(N) - f.gap[0] == doctest::Approx(R * (1 - std::cos(a))).epsilon(0.05).scale(0));
    // the slip from the material particles
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - N * N.transpose();
    const Vec3 trial = el.gRev0[0] + P * (d - el.d0[0]);
    const Vec3 gRev = slide > 1e-3 ? Vec3(w.contact.gMax * trial.normalized()) : trial;
    CHECK((f.gRev[0] - gRev).norm() <= 1e-12 * gRev.norm());
    CHECK(gRev.norm() > 0.5 * R * std::sin(a) * (slide > 1e-3 ? 0 : 1));
    const Vec3 friction = f.force[0] - f.normalForce[0] * N;
    CHECK((friction + 0.3 * f.normalForce[0] / w.contact.gMax * gRev).norm() <=
          1e-12 * f.normalForce[0]);
    REQUIRE_FALSE(w.system.symmetric);
    const Eigen::MatrixXd K = test::fullTangent(w.system);
    const Eigen::MatrixXd Kfd = test::finiteDifferenceTangent(w, 0);
    MESSAGE("|K - K_fd| / |K| = " << (K - Kfd).norm() / K.norm());
    CHECK((K - Kfd).norm() <= 1e-6 * K.norm());
  }
}

TEST_CASE("a weighted line contact's tangent matches finite differences: facing particles, and in slip") {
  // Two parallel beams, A of 8 elements, B of 7 (the elements between both fibres' element ends
  // then differ in length), A pressed 8e-5 mm into its floor tool and B 8e-5 mm into A along their
  // length (p_max 1e-4: past the regularised penalty's 5e-5; at 0 or 5e-5 central differences
  // straddle a kink of the penalty and miss by O(h)): the weighted
  // Gauss-point elements of a line contact, on facing particles (the default). mu = 0.3: B
  // then slid 3e-3 mm along x (past g_T,max), friction on the material particles.
  for (double mu : {0.0, 0.3}) {
    CAPTURE(mu);
    WorldState w;
    w.scene = parallelBeams(0.01, 1e-4, 8);
    w.scene.contact.friction = mu;
    w.scene.contact.maxReversibleSlip = 5e-4;
    w.scene.fibres[1].elements = 7;
    buildWorld(w);
    const auto move = [&](Index f, const Vec3& by) {
      for (Index n = w.fibres.firstNode[f]; n < w.fibres.firstNode[f] + w.fibres.nodeCount[f]; ++n)
        x0Of(w.fibres.q, n) += by;
    };
    move(0, Vec3(0, 0, -8e-5));   // A into the floor tool, likewise off its penalty's kinks
    move(1, Vec3(0, 0, -16e-5));  // B into A
    runStage(w, w.pipeline.detect, 0);
    move(1, Vec3(mu > 0 ? 3e-3 : 0, 0, 0));
    assembleAt(w, true);
    const ContactElementStore& el = w.trial.elements;
    const ContactForceStore& f = w.trial.forces;
    REQUIRE(el.size() > 4);
    double lightest = 1e300, heaviest = 0;
    int pressed = 0, sliding = 0, facing = 0;
    for (Index e = 0; e < el.size(); ++e) {
      lightest = std::min(lightest, el.weight[e]), heaviest = std::max(heaviest, el.weight[e]);
      pressed += f.normalForce[e] > 0;
      sliding += f.slip[e] != 0;
      facing += e < Index(f.facing.size()) && f.facing[e];
    }
    CHECK(heaviest > 1.1 * lightest);  // unequal weights: the Gauss points' shares
    CHECK(pressed > 4);
    CHECK((sliding > 0) == (mu > 0));
    CHECK(facing == el.size());
    const Eigen::MatrixXd K = test::fullTangent(w.system);  // both triangles
    const Eigen::MatrixXd Kfd = test::finiteDifferenceTangent(w, 0);
    MESSAGE("|K - K_fd| / |K| = " << (K - Kfd).norm() / K.norm());
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
