// Dense frictional bundles converge in every increment (bench/contact_scenes.h; the full sweep is
// build/bench_bundles). A 7-fibre hexagonal bundle, every fibre clamped at both ends, pulled to
// 0.1% strain and then twisted a quarter turn about its axis under that tension, mu = 0.1:
// every increment converges, friction is exercised (sliding elements), and the reactions are
// in global equilibrium (no load, no tool: the contact forces are internal up to the couples of
// the friction forces across the gaps), which checks the reported reactions and contact forces
// against each other. A 19-fibre bundle squeezed between two plates with mu = 0.3: every
// increment converges, the plate force rises, and the two plates' forces balance.
#include "bench/contact_scenes.h"
#include "engine/world.h"

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
    // net moment sum (x_I - x_J) x f_I is what the reactions balance.
    const ContactSnapshot c = w.contactSnapshot();
    Vec3 couple = Vec3::Zero();
    for (Index e = 0; e < c.size(); ++e)
      couple += Vec3(c.particleI[e] - c.particleJ[e]).cross(Vec3(c.normalForce[e] * c.normal[e] + c.friction[e]));
    CHECK(couple.norm() > 0);
    CHECK((moment + couple).norm() <= 1e-5 * couple.norm());
  }
}

TEST_CASE("a 19-fibre bundle squeezed between two plates with mu = 0.3 converges in every increment") {
  // 19 fibres x 10 elements (3.5k DOFs), squeezed 0.01 mm in 10 increments; about 35 s on two
  // threads. (With mu = 0.1 it does not converge yet past t = 0.55: docs/RESULTS.md.)
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
