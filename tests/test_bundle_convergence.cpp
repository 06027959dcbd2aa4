// Dense frictional bundles converge in every increment (bench/contact_scenes.h; the full sweep is
// build/bench_bundles). A 7-fibre hexagonal bundle, every fibre clamped at both ends, pulled to
// 0.1% strain and then twisted a quarter turn about its axis under that tension, mu = 0.1:
// every increment converges, friction is exercised (sliding elements), and the reactions are
// in global equilibrium (no load, no tool: the contact forces are internal up to the couples of
// the friction forces across the gaps), which checks the reported reactions and contact forces
// against each other. A 19-fibre bundle squeezed between two plates with mu = 0.3: every
// increment converges, the plate force rises, and the two plates' forces balance. The same
// bundle with mu = 0.1 converges without continuation once its fibres' ends are gripped (their
// spin held): free, the spin of a fibre whose contacts all slip has no stiffness.
#include "bench/contact_scenes.h"
#include "engine/world.h"
#include "systems/facing_particles.h"
#include "systems/particle.h"

#include <Eigen/Geometry>
#include <doctest/doctest.h>

using namespace fibra;

TEST_CASE("a 7-fibre bundle twisted a quarter turn under tension converges in every increment") {
  for (double mu : {0.1, 0.3}) {
    CAPTURE(mu);
    World w(scenes::twistedBundle(1, 10, 5e-4, mu));
    int increments = 0, sliding = 0;
    while (!w.finished()) {
      const StepReport r = w.step();
      REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
      ++increments;
      sliding = std::max(sliding, int(r.contact.sliding));
      CHECK(r.contact.maxPenetrationRatio < 5);
    }
    CHECK(increments == 12);
    CHECK(sliding > 0);

    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    double torque = 0, scale = 0;
    for (Index b = 0; b < Index(w.scene().bcs.size()); ++b) {
      const Reaction r = w.reaction(b);
      force += r.force;
      moment += r.moment;
      scale = std::max(scale, r.force.norm());
      if (b % 2) torque += r.moment.x();  // the twisted ends (about x through the origin)
    }
    CHECK(std::abs(torque) > 1e-3);  // N mm: the bundle resists the twist
    CHECK(force.norm() <= 1e-9 * scale);
    // The contact pairs' forces are equal and opposite but act at particles a gap apart: their
    // net moment sum (x_I - x_J) x f_I is what the reactions balance, the normal force's at the
    // particles it acted on (facing ones), friction's at the material particles.
    const ContactState& c = w.contact();
    const Eigen::VectorXd& q = w.fibres().q;
    const auto arm = [&](const ParticleWeights& I, const ParticleWeights& J) {
      return Vec3(particlePosition(q, I) - particlePosition(q, J));
    };
    Vec3 couple = Vec3::Zero();
    for (Index e = 0; e < c.elements.size(); ++e) {
      const Vec3 normal = c.forces.normalForce[e] * c.forces.normal[e];
      couple += arm(forceParticle(c.elements, c.forces, e, 0), forceParticle(c.elements, c.forces, e, 1))
                    .cross(normal);
      couple += arm(c.elements.sideI[e], c.elements.sideJ[e]).cross(Vec3(c.forces.force[e] - normal));
    }
    CHECK(couple.norm() > 0);
    CHECK((moment + couple).norm() <= 1e-5 * couple.norm());
  }
}

TEST_CASE("a 19-fibre bundle squeezed between two plates with mu = 0.3 converges in every increment") {
  // 19 fibres x 10 elements (3.5k DOFs), squeezed 0.01 mm in 10 increments; about 35 s on two
  // threads. (With mu = 0.1 it needs the continuation: the next test.)
  World w(scenes::bundle(2, 10, 0.01, 5e-4, 0.3));
  double previous = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    const Vec3 top = w.toolReaction(1), bottom = w.toolReaction(0);
    CHECK(top.z() > previous);  // the plate force rises with the squeeze
    previous = top.z();
    // The plates carry the squeeze between them (the ends are held in x and y only; the
    // stabilisation springs take at most their reported share of the reference force).
    CHECK(std::abs(top.z() + bottom.z()) <= 3e-3 * top.z());
  }
  CHECK(previous > 1);  // N
}

TEST_CASE("held stick-slip statuses carry a squeezed 7-fibre bundle with mu = 0.1 past its cycles") {
  // With a light continuation damping (1e-3) and no holding, the increment to t = 0.3 stagnates
  // on a 2-iteration cycle of 8 elements jumping between stick and slip (docs/METHOD.md); with
  // the statuses held after two changes every increment converges, and every held element ends
  // within the tolerance of its branch's side of the slip circle.
  SceneDef s = scenes::bundle(1, 10, 0.01, 5e-4, 0.1);
  s.steps[0].damping = 1e-3;
  World w(s);
  int held = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    held = std::max(held, r.contact.frictionHeld);
    CHECK(r.contact.frictionExcess <= s.contact.frictionHoldTolerance);
  }
  CHECK(held > 0);
}

TEST_CASE("a 19-fibre bundle with gripped ends squeezed with mu = 0.1 converges without continuation") {
  // 19 fibres x 10 elements squeezed 0.01 mm in 10 increments, static (no damping), the spin of
  // every held end held too (scenes::holdEndSpin). With the spin free the same scene stagnates
  // at t = 0.6 (docs/METHOD.md "Free spin"). Measured: 226 Newton iterations, no cutback.
  SceneDef s = scenes::bundle(2, 10, 0.01, 5e-4, 0.1);
  scenes::holdEndSpin(s);
  World w(s);
  double previous = 0;
  int iterations = 0, sliding = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    CHECK(r.cutbacks == 0);
    iterations += r.iterations;
    sliding = std::max(sliding, int(r.contact.sliding));
    const double top = w.toolReaction(1).z();
    CHECK(top > previous);
    previous = top;
    CHECK(r.contact.frictionExcess <= s.contact.frictionHoldTolerance);
    // A static equilibrium: the plates carry the squeeze between them, up to the stabilisation
    // springs' reported share.
    CHECK(std::abs(top + w.toolReaction(0).z()) <= 3e-3 * top);
  }
  CHECK(sliding > 0);  // friction is exercised: elements slide
  CHECK(previous > 1);  // N
  CHECK(iterations <= 300);  // the goal: 30 Newton iterations per increment on average
}

TEST_CASE("a 19-fibre bundle squeezed with mu = 0.1 converges in every increment with continuation") {
  // 19 fibres x 10 elements squeezed 0.01 mm in 10 increments with viscous continuation c = 1e-2
  // (StepDef::damping): undamped, the spin of the fibres (ends held in position only) has no
  // stiffness once their contacts slip, and Newton leaves for residuals 1e2 x the reference
  // (docs/METHOD.md "Free spin"; the previous test holds the spin instead).
  SceneDef s = scenes::bundle(2, 10, 0.01, 5e-4, 0.1);
  s.steps[0].damping = 1e-2;
  World w(s);
  double previous = 0, viscous = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    const double top = w.toolReaction(1).z();
    CHECK(top > previous);
    previous = top;
    viscous = std::max(viscous, r.viscousForce);
    CHECK(r.contact.frictionExcess <= s.contact.frictionHoldTolerance);
  }
  CHECK(previous > 1);  // N
  CHECK(viscous > 0);   // the continuation acted: the states are not static equilibria
  // The plates carry the squeeze between them, up to the viscous and stabilisation forces
  // (measured: 0.019 N of 4.95 N at the end).
  CHECK(std::abs(previous + w.toolReaction(0).z()) <= 0.01 * previous);
}
