// Parallel contact that slides: a fibre B lying on a parallel, fully held fibre A under a uniform
// line load q, dragged along its axis with friction mu. The paired sections of a contact element
// drift apart along the axis by the slip of a pass; the normal must stay orthogonal to the fibres
// (systems/contact_normals.h), else it tilts by atan(offset / 2R) and turns normal force into an
// axial force that cancels part of the friction. In slip the drag force is mu q L (Coulomb) and
// the elements are reported sliding; frictionless, the drag is nil (the stabilisation springs'
// share aside). With the sections' centre-to-centre normal of before the drag was 0.02626 N
// (-12.5%) and no element slid at 0.015 mm per increment; at 0.03 mm per increment the fault
// did not show, so the test keeps the finer increments.
#include "dragged_fibre.h"
#include "engine/world.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace fibra;

using test::draggedFibre;
using test::kQ;
using test::kL;

TEST_CASE("a fibre dragged along a parallel one slides at mu q L with every loaded element sliding") {
  World w(draggedFibre(0.2));
  int checked = 0;
  while (!w.finished()) {
    REQUIRE(w.step().status == StepStatus::Converged);
    if (w.time() < 0.5) continue;  // the load is on and B has slid far beyond g_T,max
    const double drag = w.reaction(1).force.x();
    CAPTURE(w.time());
    CHECK(std::abs(std::abs(drag) - 0.2 * kQ * kL) <= 0.02 * 0.2 * kQ * kL);
    int active = 0, sliding = 0;
    const ContactSnapshot c = w.contactSnapshot();
    for (size_t e = 0; e < c.normalForce.size(); ++e) {
      active += c.normalForce[e] > 0;
      sliding += c.normalForce[e] > 0 && c.slip[e];
    }
    CHECK(active > 10);
    CHECK(sliding == active);
    ++checked;
  }
  CHECK(checked >= 5);
}

TEST_CASE("the true overlap at acceptance is measured from the centrelines and the radii") {
  // B's centreline against A's (the x axis): at every node of B, 2R - |(y, z)|; the reported
  // true overlap (a detection from the accepted state) must match its largest value.
  World w(draggedFibre(0.2));
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    if (w.time() < 0.3) continue;
    const FibreStore& fs = w.fibres();
    double nodes = -1;
    for (Index n = fs.firstNode[1]; n < fs.firstNode[1] + fs.nodeCount[1]; ++n) {
      const Vec3 x = x0Of(fs.q, n);
      nodes = std::max(nodes, 0.2 - std::hypot(x.y(), x.z()));
    }
    CAPTURE(w.time());
    CHECK(nodes > 0);
    CHECK(r.contact.maxOverlap == doctest::Approx(nodes).epsilon(0.05).scale(0));
    CHECK(r.contact.maxOverlap == doctest::Approx(r.contact.maxPenetration).epsilon(0.05).scale(0));
    CHECK(r.contact.redetectZoneChanges == 0);
    CHECK(r.contact.redetectGapChange < 0.1);
  }
}

TEST_CASE("frictionless parallel contact transmits no axial force while the fibre slides") {
  World w(draggedFibre(0));
  while (!w.finished()) {
    REQUIRE(w.step().status == StepStatus::Converged);
    CHECK(std::abs(w.reaction(1).force.x()) <= 1e-4 * kQ * kL);
  }
}
