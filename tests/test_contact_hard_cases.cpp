// Hard cases with contact: contacts appearing and vanishing within a step, an increment too
// large for Newton (cutbacks rescue it), penalties adapted until the deepest penetration sits at
// p_max; never a NaN, never a silent non-convergence.
#include "beam_fixtures.h"
#include "contact_scenes.h"

#include <doctest/doctest.h>

#include <numbers>

using namespace fibra;
using namespace fibra::test;

namespace {

// A straight fibre along x (4 mm, R = 0.1 mm), clamped at both ends, resting on the top of a
// roller (radius 1 mm, axis y, under its middle) that rises by `rise` mm at mid-step and comes
// back down: contact grows and vanishes.
SceneDef risingRoller(double rise, int increments) {
  BeamSpec b;
  b.length = 4;
  b.radius = 0.1;
  b.elements = 8;
  SceneDef s = straightBeam(b, increments);
  for (auto& f : s.fibres) f.geometry.points = {Vec3(0, 0, 0.6), Vec3(4, 0, 0.6)};
  for (const char* end : {"b.start", "b.end"}) {
    BcDef c;
    c.group = end;
    s.bcs.push_back(c);
  }
  ToolDef roller;
  roller.name = "roller";
  roller.kind = ToolKind::Cylinder;
  roller.point = Vec3(2, 0, -0.5 - 1e-3);
  roller.direction = Vec3::UnitY();
  roller.radius = 1;
  roller.displacement = Vec3(0, 0, rise);
  roller.displacementTable = {{0, 0.5, 1}, {0, 1, 0}};
  s.tools.push_back(roller);
  return s;
}

}  // namespace

TEST_CASE("contact appears, carries load and vanishes within one step") {
  World w(risingRoller(0.3, 12));
  int withContact = 0;
  double push = 0;  // largest downward force on the roller, N
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    REQUIRE(std::isfinite(r.residual));
    if (r.contact.active > 0) ++withContact;
    push = std::max(push, -w.toolReaction(0).z());
  }
  CHECK(withContact >= 8);   // it touched for most of the step,
  CHECK(push > 0.1);         // lifted the fibre,
  CHECK(w.toolReaction(0).norm() == 0);  // and let go at the end
  CHECK((w.fibres().q - w.fibres().qRef).norm() < 1e-6);
}

TEST_CASE("an increment too large for Newton with contact is rescued by cutbacks") {
  SceneDef s = risingRoller(0.3, 1);
  s.tools[0].displacementTable = {{0, 1}, {0, 1}};  // the whole rise in one increment
  // 6: the whole rise needs 18 iterations (the roller's crest sampled by 25 points per element,
  // systems/tool_detection.h); with 5 even 1/256 of it takes 6 (the frozen normals converge
  // linearly on the crest), and the cutbacks cannot rescue it.
  s.steps[0].maxIterations = 6;
  World w(s);
  const StepReport r = w.step();
  CHECK(r.status == StepStatus::Converged);
  CHECK(r.cutbacks >= 1);
  CHECK(r.message.find("cutback") != std::string::npos);
  CHECK(r.contact.maxPenetrationRatio < 2);
}

TEST_CASE("a step that cannot converge fails with a report and the last converged state") {
  SceneDef s = risingRoller(0.3, 1);
  s.tools[0].displacementTable = {{0, 1}, {0, 1}};
  s.steps[0].maxIterations = 3;
  s.steps[0].maxCutbacks = 1;
  World w(s);
  const StepReport r = w.step();
  CHECK(r.status == StepStatus::Failed);
  INFO(r.message);
  CHECK(r.message.find("failed after 1 cutback") != std::string::npos);
  CHECK(r.message.find("failed after 1 cutbacks") == std::string::npos);
  CHECK(w.fibres().q == w.fibres().qRef);
  CHECK(w.fibres().q.allFinite());
}

TEST_CASE("penalty adaptation brings the deepest penetration just under p_max") {
  SceneDef s = risingRoller(0.3, 6);
  s.tools[0].displacementTable = {{0, 1}, {0, 1}};  // rise and stay
  s.contact.maxPenetration = 1e-3;
  World w(s);
  StepReport r;
  while (!w.finished()) {
    r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
  }
  CHECK(r.contact.active > 0);
  CHECK(r.contact.maxPenetrationRatio <= 1);    // aimed at 0.9 p_max,
  CHECK(r.contact.maxPenetrationRatio >= 0.8);  // and reached
}

TEST_CASE("beams pressed together at angles around theta_parallel and theta_cross converge") {
  // Two simply supported beams, B above A and turned by theta about z, B's midspan pushed down
  // by P. Near theta_parallel (5 deg) the normals switch from the centre-to-centre direction to
  // the blend; near theta_cross (20 deg) from the blend to t^A x t^B. Every angle must converge
  // with finite forces, the contact carrying part of P within the allowed penetration.
  const double P = 0.02, pMax = 1e-4;
  for (double degrees : {2.0, 4.5, 5.0, 5.5, 12.0, 19.5, 20.5}) {
    CAPTURE(degrees);
    SceneDef s = crossingBeams(P, pMax);
    const double th = degrees * std::numbers::pi / 180;
    const Vec3 along(std::cos(th), std::sin(th), 0);  // B's axis, at theta from A's (x)
    s.fibres[1].geometry.points = {Vec3(0, 0, 0.2) - 2 * along, Vec3(0, 0, 0.2) + 2 * along};
    for (BcDef& b : s.bcs)  // B's spin about its own axis turns g1 = z mostly along y now
      if (b.group == "B.start" && b.dofs[G1X]) b.dofs[G1X] = false, b.dofs[G1Y] = true;
    World w(s);
    StepReport r;
    while (!w.finished()) {
      r = w.step();
      INFO(r.message);
      REQUIRE(r.status == StepStatus::Converged);
      REQUIRE(std::isfinite(r.residual));
    }
    double carried = 0;  // z force the contact puts on A, N
    const ContactSnapshot c = w.contactSnapshot();
    for (Index e = 0; e < c.size(); ++e) {
      REQUIRE(std::isfinite(c.normalForce[e]));
      carried += (c.fibreI[e] == 0 ? 1 : -1) * c.normalForce[e] * c.normal[e].z();
    }
    CHECK(carried < 0);  // A is pushed down
    CHECK(-carried > 0.3 * P);
    CHECK(-carried < P);
    CHECK(r.contact.maxPenetration <= 1.5 * pMax);
  }
}
