// The fibre-fibre contact normal linearised in Newton (contact `normal_update` "newton",
// systems/normal_linearisation.h): the assembled tangent against central finite differences of
// the residual (the normal recomputed at every perturbed state) on crossing, intermediate-angle
// and parallel pairs, in both penalty branches, without friction and with friction in stick and
// slip; and a reduced heavy line contact, whose straight equilibrium is laterally unstable,
// solved to the uniform line force.
#include "contact_scenes.h"
#include "engine/world_state.h"
#include "fd_tangent.h"
#include "io/scene_loader.h"
#include "systems/contact_geometry.h"
#include "systems/contact_normals.h"
#include "systems/particle.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace fibra;
using namespace fibra::test;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Two straight beams (L = 4 mm, R = 0.1 mm, E = 4000 MPa, `elements` elements: 7 puts the
// midspans inside elements, 8 on nodes): A along x, B turned by `angle` (rad) about z, touching A
// from above at the midspans; ends pinned.
SceneDef pairAt(double angle, double mu, NormalUpdate update, int elements = 7) {
  const double L = 4, R = 0.1;
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  const Vec3 t(std::cos(angle), std::sin(angle), 0), up(0, 0, 2 * R);
  const Vec3 a(L / 2, 0, 0);
  s.fibres.push_back(straightFibre("A", -a, a, R, elements, Vec3::UnitZ()));
  s.fibres.push_back(straightFibre("B", up - L / 2 * t, up + L / 2 * t, R, elements, Vec3::UnitZ()));
  for (const char* f : {"A", "B"}) {
    hold(s, std::string(f) + ".start", {X, Y, Z});
    hold(s, std::string(f) + ".end", {X, Y, Z});
  }
  s.contact.enabled = true;
  s.contact.maxPenetration = 1e-3;  // p_reg = 5e-4 mm
  s.contact.friction = mu;
  s.contact.maxReversibleSlip = 5e-4;
  s.contact.normalUpdate = update;
  s.steps.push_back(StepDef{});
  return s;
}

// The pair with its elements detected, then B pushed down until its closest element penetrates
// by `depth` (mm), slid by `slide` and bent a little (lateral and vertical waves of 5e-5 mm), so
// that normals, tangents and gaps differ from element to element.
void pressedPair(WorldState& w, double angle, double mu, double depth, const Vec3& slide,
                 NormalUpdate update = NormalUpdate::Newton, int elements = 7) {
  w.scene = pairAt(angle, mu, update, elements);
  buildWorld(w);
  runStage(w, w.pipeline.detect, 0);
  double closest = 1;  // mm
  for (double g : w.trial.elements.gap) closest = std::min(closest, g);
  const Index first = w.fibres.firstNode[1];
  for (Index n = first; n < first + w.fibres.nodeCount[1]; ++n) {
    const double i = double(n - first);
    x0Of(w.fibres.q, n) +=
        slide + Vec3(0, 5e-5 * std::sin(1.3 * i), -closest - depth + 5e-5 * std::cos(0.7 * i));
  }
}

// The assembled tangent, both triangles.
Eigen::MatrixXd tangentOf(WorldState& w) {
  runStage(w, w.pipeline.assemble, 0, true);
  return test::fullTangent(w.system);
}

// |K - K_fd| / |K| at the pressed state.
double tangentError(WorldState& w) {
  const Eigen::MatrixXd K = tangentOf(w);
  const Eigen::MatrixXd Kfd = finiteDifferenceTangent(w, 0);
  return (K - Kfd).norm() / K.norm();
}

int activeElements(const WorldState& w) {
  int n = 0;
  for (double r : w.trial.forces.normalForce) n += r > 0;
  return n;
}

}  // namespace

TEST_CASE("linearised normal tangent matches finite differences: crossing, intermediate, parallel") {
  // 90 deg: crossing normal; 12 deg: between theta_parallel (5) and theta_cross (20), the blend;
  // 0 deg: the parallel normal. Depth 3e-4 mm: regularised branch (< p_reg); 2e-3 mm: linear.
  for (double angle : {90.0, 12.0, 0.0})
    for (double depth : {3e-4, 2e-3}) {
      CAPTURE(angle);
      CAPTURE(depth);
      WorldState w;
      pressedPair(w, angle * kDeg, 0, depth, Vec3::Zero());
      REQUIRE_FALSE(w.system.symmetric);
      runStage(w, w.pipeline.assemble, 0, true);
      REQUIRE(activeElements(w) > 0);
      REQUIRE(w.trial.forces.normalJacobian.size() == size_t(w.trial.forces.size()));
      CHECK(tangentError(w) <= 1e-6);
    }
}

TEST_CASE("linearised normal tangent matches finite differences with friction, stick and slip") {
  for (double angle : {90.0, 12.0, 0.0})
    for (double slide : {1e-5, 3e-3}) {
      CAPTURE(angle);
      CAPTURE(slide);
      WorldState w;
      pressedPair(w, angle * kDeg, 0.3, 1e-3, Vec3(0.3 * slide, slide, 0));
      runStage(w, w.pipeline.assemble, 0, true);
      REQUIRE(activeElements(w) > 0);
      int slipping = 0;
      for (std::uint8_t s : w.trial.forces.slip) slipping += s;
      CHECK((slipping > 0) == (slide > 1e-3));
      CHECK(tangentError(w) <= 1e-6);
    }
}

TEST_CASE("linearised normal: a stick/slip status held for the pass takes its branch, tangent exact") {
  // contact friction_hold_after (systems/friction_status.h) applies to the linearised elements as
  // to the fixed-normal ones: a slide of 3e-3 mm would slip (|trial| > g_max) and 1e-5 mm stick;
  // held the other way, every active element takes the held branch (stick: |f_T| = mu R_N
  // |trial| / g_max > mu R_N; slip: = mu R_N), the tracking sees the trial ratio, and the
  // tangent still matches central differences (the branch is fixed for the pass).
  for (double slide : {1e-5, 3e-3}) {
    CAPTURE(slide);
    const bool wouldSlip = slide > 1e-3;
    WorldState w;
    pressedPair(w, 12 * kDeg, 0.3, 1e-3, Vec3(0.3 * slide, slide, 0));
    runStage(w, w.pipeline.assemble, 0, true);
    REQUIRE(activeElements(w) > 0);
    FrictionStatusStore& status = w.trial.frictionStatus;
    REQUIRE(status.size() == w.trial.forces.size());
    for (Index e = 0; e < status.size(); ++e) {
      if (w.trial.forces.normalForce[e] > 0) CHECK(status.trialRatio[e] > 0);
      status.held[e] = wouldSlip ? kStatusStick : kStatusSlip;
    }
    runStage(w, w.pipeline.assemble, 0, true);
    const ContactForceStore& f = w.trial.forces;
    int checked = 0;
    for (Index e = 0; e < f.size(); ++e) {
      if (!(f.normalForce[e] > 0)) continue;
      ++checked;
      CHECK(bool(f.slip[e]) == !wouldSlip);
      const double ratio = f.gRev[e].norm() / 5e-4;  // |g_rev| / g_max
      if (wouldSlip) CHECK(ratio > 1);                // held in stick beyond the circle
      else CHECK(ratio == doctest::Approx(1));       // held in slip inside it
    }
    CHECK(checked > 0);
    CHECK(tangentError(w) <= 1e-6);
  }
}

TEST_CASE("linearised normal on facing particles: a spun section's normal force passes its axis, tangent exact") {
  // B's sections spun 25 deg about its axis after detection: its material particles roll off
  // the line of centres. With contact.facing_particles (the default) the linearised element
  // measures its gap on, and puts its normal force on, the outlines' points extremal along N
  // (facing 1), so the normal force has no moment about B's axis, and the tangent (with the
  // facing points' motion through the directors and through N) matches central differences,
  // frictionless and with friction in stick and slip.
  for (double mu : {0.0, 0.3})
    for (double slide : {1e-5, 3e-3}) {
      CAPTURE(mu);
      CAPTURE(slide);
      WorldState w;
      const double angle = 12 * kDeg;
      pressedPair(w, angle, mu, 1e-3, Vec3(0.3 * slide, slide, 0));
      const Vec3 axis(std::cos(angle), std::sin(angle), 0);
      const Eigen::Matrix3d spin = Eigen::AngleAxisd(25 * kDeg, axis).toRotationMatrix();
      const Index first = w.fibres.firstNode[1];
      for (Index n = first; n < first + w.fibres.nodeCount[1]; ++n)
        for (int g : {3, 6}) w.fibres.q.segment<3>(kNodeDofs * n + g) =
            spin * w.fibres.q.segment<3>(kNodeDofs * n + g);
      runStage(w, w.pipeline.assemble, 0, true);
      REQUIRE(activeElements(w) > 0);
      const ContactForceStore& f = w.trial.forces;
      for (Index e = 0; e < f.size(); ++e) {
        if (!(f.normalForce[e] > 0)) continue;
        REQUIRE(f.facing[e] == 1);
        // B is side I or J: the normal force's point on B, its moment arm about B's axis
        const bool bIsI = w.trial.elements.fibreI[e] == 1;
        const ParticleWeights& onB = bIsI ? f.facingI[e] : f.facingJ[e];
        const ParticleWeights& materialB = bIsI ? w.trial.elements.sideI[e] : w.trial.elements.sideJ[e];
        ParticleWeights centre = onB;
        for (int a = 0; a < centre.nodes; ++a) centre.c[a][1] = centre.c[a][2] = 0;
        const Vec3 x0 = particlePosition(w.fibres.q, centre);
        const Vec3 arm = particlePosition(w.fibres.q, onB) - x0;
        const Vec3 fN = f.normalForce[e] * f.normal[e];
        CHECK(std::abs(arm.cross(fN).dot(axis)) <= 1e-9 * fN.norm() * 0.1);
        // the material particle has rolled away: its moment would not vanish
        const Vec3 rolled = particlePosition(w.fibres.q, materialB) - x0;
        CHECK(std::abs(rolled.cross(fN).dot(axis)) > 0.1 * 0.1 * fN.norm());
      }
      CHECK(tangentError(w) <= 1e-6);
    }
}

TEST_CASE("linearised normal tangent matches finite differences at sections on interior nodes") {
  // 8 elements: the crossing sections sit on the midspan nodes, where dx0/ds is the mean of two
  // elements' and the contact clique is widened by the neighbouring element.
  for (double mu : {0.0, 0.3}) {
    CAPTURE(mu);
    WorldState w;
    pressedPair(w, 90 * kDeg, mu, 1e-3, Vec3(3e-4, 1e-3, 0), NormalUpdate::Newton, 8);
    runStage(w, w.pipeline.assemble, 0, true);
    REQUIRE(activeElements(w) > 0);
    bool onNode = false;
    for (const NormalJacobian& J : w.trial.forces.normalJacobian) onNode = onNode || J.I.count > 3;
    CHECK(onNode);
    CHECK(tangentError(w) <= 1e-6);
  }
}

TEST_CASE("the fixed-normal tangent misses what the linearised normal adds") {
  // The same parallel pair under normal_update "loop": N fixed in the pass, so the residual's
  // finite differences (with N fixed too) match, but differ from the linearised tangent.
  WorldState loop, newton;
  pressedPair(loop, 0, 0, 2e-3, Vec3::Zero(), NormalUpdate::Loop);
  pressedPair(newton, 0, 0, 2e-3, Vec3::Zero());
  CHECK(loop.system.symmetric);
  CHECK(tangentError(loop) <= 1e-6);
  const Eigen::MatrixXd Kn = tangentOf(newton), Kl = tangentOf(loop);
  CHECK((Kn - Kl).norm() > 1e-4 * Kn.norm());
}

TEST_CASE("a heavy parallel line contact converges with the linearised normal to a uniform line force") {
  // line_contact_heavy reduced: a 6 mm frictionless fibre U (R = 0.1 mm) on a held parallel
  // fibre D under 1 N/mm, p_max = 5e-4 mm. Lying on D is laterally unstable (negative lateral
  // stiffness q / 2R = 5 N/mm^2 against U's bending ~3e-3 N/mm^2): loop B's fixed point on the
  // normal amplifies round-off in y (with normal_update "loop" and no normal_acceleration this
  // scene fails at t = 0.65 after 8 cutbacks); Newton with dN/dq converges to the straight
  // equilibrium (24 iterations).
  const std::string text = heavyLineContact(R"(, "normal_update": "newton")");
  const double q = 1.0;  // N/mm
  World w(loadSceneFromString(text, "heavy.json"));
  double axial = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    axial = std::max(axial, std::abs(w.reaction(0).force.x()));
  }
  CHECK(axial <= 1e-3 * q * 6);  // frictionless: no axial reaction
  const ContactElementStore& el = w.contact().elements;
  const ContactForceStore& f = w.contact().forces;
  int inner = 0;
  for (Index e = 0; e < el.size(); ++e) {
    const double s = el.fibreI[e] == 0 ? el.sI[e] : el.sJ[e];  // on U, from its start, mm
    if (s < 2 || s > 4) continue;  // beyond 2 mm from either end: the middle 2 mm
    CAPTURE(s);
    CHECK(f.normalForce[e] / el.length[e] == doctest::Approx(q).epsilon(0.02).scale(0));
    ++inner;
  }
  CHECK(inner >= 4);
}


TEST_CASE("linearised normal tangent matches finite differences where the crossing lies past an end") {
  // A along x; B at 30 degrees to it in plan, 2R above, ending 0.01 mm before the crossing (40
  // elements each), pressed 1e-3 mm into A: the tangent lines of B's sections near its end meet A's past that
  // end, and their crossing normal is the line between the closest points of the segments the
  // fibres cover (systems/contact_normals.h), which turns with the state.
  for (double mu : {0.0, 0.3}) {
    CAPTURE(mu);
    const double R = 0.1;
    SceneDef s;
    s.materials.push_back({"m", 4000, 0.3, 1, 1});
    s.fibres.push_back(straightFibre("A", Vec3(-2, 0, 0), Vec3(2, 0, 0), R, 40, Vec3::UnitZ()));
    const Vec3 b(std::cos(30 * kDeg), std::sin(30 * kDeg), 0);
    s.fibres.push_back(straightFibre("B", Vec3(0, 0, 2 * R) - 2 * b, Vec3(0, 0, 2 * R) - 0.01 * b, R, 40, Vec3::UnitZ()));
    for (const char* f : {"A", "B"}) {
      hold(s, std::string(f) + ".start", {X, Y, Z});
      hold(s, std::string(f) + ".end", {X, Y, Z});
    }
    s.contact.enabled = true;
    s.contact.maxPenetration = 1e-3;
    s.contact.friction = mu;
    s.contact.maxReversibleSlip = 5e-4;
    s.contact.normalUpdate = NormalUpdate::Newton;
    s.steps.push_back(StepDef{});
    WorldState w;
    w.scene = s;
    buildWorld(w);
    const Index first = w.fibres.firstNode[1];
    for (Index n = first; n < first + w.fibres.nodeCount[1]; ++n) {
      const double i = double(n - first);
      x0Of(w.fibres.q, n) += Vec3(2e-4, 5e-5 * std::sin(1.3 * i), -1e-3 + 5e-5 * std::cos(0.7 * i));
    }
    runStage(w, w.pipeline.detect, 0);
    runStage(w, w.pipeline.assemble, 0, true);
    const ContactElementStore& el = w.trial.elements;
    int tilted = 0;  // active side elements whose normal the fibre ends turned
    for (Index e = 0; e < el.size(); ++e) {
      if (!(w.trial.forces.normalForce[e] > 0) || (el.fallback[e] & (kEndFaceI | kEndFaceJ))) continue;
      const Section I = contactSection(w.fibres, w.fibres.q, el.fibreI[e], el.sI[e]);
      const Section J = contactSection(w.fibres, w.fibres.q, el.fibreJ[e], el.sJ[e]);
      const double xiI[2] = {el.xiI1[e], el.xiI2[e]}, xiJ[2] = {el.xiJ1[e], el.xiJ2[e]};
      const NormalGap lines = normalAndGap(I, J, xiI, xiJ, R, R, w.contact.thetaParallel,
                                           w.contact.thetaCross, el.fallback[e]);
      tilted += (lines.normal - el.normal[e]).norm() > 1e-6;
    }
    MESSAGE(tilted << " active side elements with a tilted crossing normal of " << el.size());
    CHECK(tilted > 0);
    CHECK(tangentError(w) <= 1e-6);
  }
}
