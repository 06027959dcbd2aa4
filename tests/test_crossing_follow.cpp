// Crossing follow (systems/crossing_follow.h): after the fibres of a frictionless crossing slide,
// its point element's sections are moved to the new closest points of the centrelines, with the
// particles of eq. 9 there; frictional crossings and a switched-off option leave them alone.
// From the converged crossing beams (tests/contact_scenes.h): A along x, B along y above it,
// crossing at A's s = 2 mm and B's s = 2 mm, in the middle of their fifth element.
#include "contact_scenes.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"
#include "engine/world.h"
#include "systems/crossing_follow.h"
#include "systems/interpolation.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace fibra;
using namespace fibra::test;

namespace {

// The crossing beams pressed in one increment, frictionless: the contact state and the fibres.
struct Pressed {
  FibreStore fibres;
  ContactState contact;
};

Pressed pressed() {
  SceneDef s = crossingBeams(0.01, 1e-4, 9);  // 9 elements: the crossing mid-element
  s.steps[0].increments = 1;
  World w(s);
  REQUIRE(w.step().status == StepStatus::Converged);
  return {w.fibres(), w.contact()};
}

// Moves every node of fibre f by v (its centreline; directors unchanged).
void translate(FibreStore& fs, Index f, const Vec3& v) {
  for (Index n = fs.firstNode[f]; n < fs.firstNode[f] + fs.nodeCount[f]; ++n)
    fs.q.segment<3>(kNodeDofs * n) += v;
}

ContactParams followParams() {
  ContactParams p;
  p.followCrossings = true;
  p.thetaParallel = 5 * std::numbers::pi / 180;
  return p;
}

}  // namespace

TEST_CASE("crossing follow: a slid crossing's sections move to the new closest points") {
  Pressed c = pressed();
  const ContactElementStore& detected = c.contact.elements;
  REQUIRE(detected.size() == 1);
  REQUIRE(detected.crossing[0] == 1);  // one point element at the closest points
  const Index A = detected.fibreI[0] == 0 ? 0 : 1;
  CHECK(detected.sI[0] == doctest::Approx(2).epsilon(1e-6));
  CHECK(detected.sJ[0] == doctest::Approx(2).epsilon(1e-6));
  // B slides 0.05 mm along A (+x), A 0.03 mm along B (+y): the crossing moves by about as much
  // on each (the beams are bent by the load: not exactly).
  translate(c.fibres, 1 - A, Vec3(0.05, 0, 0));
  translate(c.fibres, A, Vec3(0, 0.03, 0));
  ContactElementStore el = detected;
  ContactLoopStats stats;
  followCrossings(c.fibres, c.fibres.q, followParams(), c.contact.zones, el, stats);
  const double sA = A == el.fibreI[0] ? el.sI[0] : el.sJ[0];
  const double sB = A == el.fibreI[0] ? el.sJ[0] : el.sI[0];
  CHECK(sA == doctest::Approx(2.05).epsilon(1e-3).scale(0));
  CHECK(sB == doctest::Approx(2.03).epsilon(1e-3).scale(0));
  CHECK(stats.crossingShift == doctest::Approx(0.05).epsilon(1e-2).scale(0));
  // They are the closest points: the line of centres is normal to both centrelines.
  const Section I = sectionAt(c.fibres, c.fibres.q, locate(c.fibres, el.fibreI[0], el.sI[0]));
  const Section J = sectionAt(c.fibres, c.fibres.q, locate(c.fibres, el.fibreJ[0], el.sJ[0]));
  const Vec3 centres = I.x0 - J.x0;
  CHECK(std::abs(centres.dot(I.dx0ds.normalized())) < 1e-12);
  CHECK(std::abs(centres.dot(J.dx0ds.normalized())) < 1e-12);
  // The particles on the outlines (|xi| = R), on the sides that face each other.
  const Vec3 xI = I.x0 + el.xiI1[0] * I.g1 + el.xiI2[0] * I.g2;
  const Vec3 xJ = J.x0 + el.xiJ1[0] * J.g1 + el.xiJ2[0] * J.g2;
  CHECK(std::hypot(el.xiI1[0], el.xiI2[0]) == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(std::hypot(el.xiJ1[0], el.xiJ2[0]) == doctest::Approx(0.1).epsilon(1e-12));
  CHECK((xI - I.x0).dot(centres) < 0);
  CHECK((xJ - J.x0).dot(centres) > 0);
  // The particle weights were bound at the new sections: the particle from the DOFs is xI.
  Vec3 fromWeights = Vec3::Zero();
  const ParticleWeights& w = el.sideI[0];
  for (int a = 0; a < w.nodes; ++a)
    for (int k = 0; k < 3; ++k)
      fromWeights += w.c[a][k] * c.fibres.q.segment<3>(kNodeDofs * (w.firstNode + a) + 3 * k);
  CHECK((fromWeights - xI).norm() < 1e-12);
  // Nothing left to move: a second call shifts nothing.
  followCrossings(c.fibres, c.fibres.q, followParams(), c.contact.zones, el, stats);
  CHECK(stats.crossingShift < 1e-12);
}

TEST_CASE("crossing follow: frictional crossings and the option off keep their material points") {
  Pressed c = pressed();
  translate(c.fibres, 1, Vec3(0.05, 0.05, 0));
  ContactLoopStats stats;
  ContactElementStore el = c.contact.elements;
  ZoneStore frictional = c.contact.zones;
  for (double& mu : frictional.friction) mu = 0.2;
  followCrossings(c.fibres, c.fibres.q, followParams(), frictional, el, stats);
  CHECK(stats.crossingShift == 0);
  CHECK(el.sI == c.contact.elements.sI);
  CHECK(el.sJ == c.contact.elements.sJ);
  // ... unless the step switches friction off (friction_factor 0).
  ContactParams off = followParams();
  off.frictionFactor = 0;
  followCrossings(c.fibres, c.fibres.q, off, frictional, el, stats);
  CHECK(stats.crossingShift > 0.04);
  ContactParams disabled = followParams();
  disabled.followCrossings = false;
  el = c.contact.elements;
  followCrossings(c.fibres, c.fibres.q, disabled, c.contact.zones, el, stats);
  CHECK(stats.crossingShift == 0);
  CHECK(el.sI == c.contact.elements.sI);
}

TEST_CASE("crossing follow: contact.follow_crossings is read, false by default, and must be a boolean") {
  const auto scene = [](const std::string& follow) {
    return R"({"units": "mm-N-MPa", "materials": [{"name": "m", "young_modulus": 1000}],
      "fibres": [{"name": "a", "material": "m", "radius": 0.1, "elements": 2,
                  "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
      "boundary_conditions": [{"type": "clamp", "group": "a.start"}],
      "contact": {"max_penetration": 1e-3)" + follow + "}, \"steps\": [{}]}";
  };
  CHECK(!loadSceneFromString(scene(""), "s.json").contact.followCrossings);
  CHECK(loadSceneFromString(scene(R"(, "follow_crossings": true)"), "s.json").contact.followCrossings);
  const std::string error =
      errorOf([&] { loadSceneFromString(scene(R"(, "follow_crossings": "yes")"), "s.json"); });
  CHECK(error.find("s.json") != std::string::npos);
  CHECK(error.find("contact.follow_crossings") != std::string::npos);
}
