// The paper's alternate sliding test (section 5.1) from samples/two_beams_sliding.json: beam B,
// pressed on beam A by 0.1 N at each end, is moved back and forth by 0.75 mm. Checks: every
// increment converges, each leg sticks then slips, in slip the contact force on B (taken from
// B's equilibrium, not from the law) has a tangential part mu times its normal part within 2%,
// the contact crosses an element boundary of B in every leg, and the second cycle repeats the
// first within 2% of the peak force.
#include "io/scene_loader.h"
#include "engine/world.h"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

using namespace fibra;

namespace {

struct Row {
  double time = 0;
  double horizontal = 0;   // y force of B's end holds on B, N
  double vertical = 0;     // z force of A's holds on A (= normal load carried), N
  double tangential = 0;   // contact force on B, part in the contact plane, N
  double normal = 0;       // contact force on B, part along the contact normal, N
  bool sliding = false;
  int iterations = 0;
  double sB = 0;           // arc length of the contact on B, mm (first element)
};

// The force the contact exerts on B balances B's holds and its two end loads (the stabilisation
// spring's force is below 1e-6 of it and is left out).
Row measure(const World& w, const StepReport& r) {
  Row row;
  row.time = w.time();
  const Vec3 holds = w.reaction(2).force + w.reaction(3).force;
  const Vec3 onB = -(holds + Vec3(0, 0, -0.2));
  row.horizontal = holds.y();
  row.vertical = (w.reaction(0).force + w.reaction(1).force).z();
  const ContactElementStore& el = w.contact().elements;
  const ContactForceStore& f = w.contact().forces;
  Vec3 n = Vec3::Zero();  // force-weighted normal, from A to B
  for (Index e = 0; e < el.size(); ++e) {
    const double side = el.fibreI[e] == 1 ? 1 : -1;
    n += side * f.normalForce[e] * el.normal[e];
  }
  n.normalize();
  row.normal = onB.dot(n);
  row.tangential = (onB - row.normal * n).norm();
  row.sliding = r.contact.sliding > 0;
  if (el.size() > 0) row.sB = el.fibreI[0] == 1 ? el.sI[0] : el.sJ[0];
  row.iterations = r.iterations;
  return row;
}

}  // namespace

TEST_CASE("two beams, alternate sliding (paper 5.1): stick, slip at mu R_N, cycles repeat") {
  const SceneDef scene = loadScene(FIBRA_SOURCE_DIR "/samples/two_beams_sliding.json");
  const double mu = scene.contact.friction;
  World w(scene);
  std::vector<Row> rows;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    CHECK(std::isfinite(r.residual));
    CHECK(r.contact.maxPenetration <= scene.contact.maxPenetration);
    rows.push_back(measure(w, r));
  }
  REQUIRE(rows.size() == 125);

  const int perLeg = 25;
  double peak = 0;
  for (const Row& r : rows) peak = std::max(peak, std::abs(r.horizontal));
  CHECK(peak == doctest::Approx(mu * 0.2).epsilon(0.05).scale(0));
  for (int leg = 0; leg < 5; ++leg) {
    CAPTURE(leg);
    const double direction = leg % 2 == 0 ? 1 : -1;  // sign of B's motion, and of its holds' y force
    // Stick first: after a reversal the first increment moves B by 30 um, far below the slip
    // reversal needs (2 g_max = 1 um would be rigid fibres; the beams' compliance takes more).
    if (leg > 0) {
      const Row& first = rows[leg * perLeg];
      CHECK_FALSE(first.sliding);
      CHECK(std::abs(first.horizontal) < 0.8 * mu * first.vertical);
    }
    // Then slip: the last ten increments of every leg slide at the Coulomb limit.
    for (int i = perLeg - 10; i < perLeg; ++i) {
      const Row& r = rows[leg * perLeg + i];
      CAPTURE(r.time);
      CHECK(r.sliding);
      CHECK(r.tangential == doctest::Approx(mu * r.normal).epsilon(0.02).scale(0));
      CHECK(direction * r.horizontal > 0);
      CHECK(std::abs(r.horizontal) == doctest::Approx(mu * r.vertical).epsilon(0.05).scale(0));
    }
  }
  // The contact crosses B's element boundary at s = 1.6 mm in every leg (elements of 0.4 mm;
  // B's material under A is at s = 2 - d when B has moved by d).
  for (int leg = 0; leg < 5; ++leg) {
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < perLeg; ++i) {
      lo = std::min(lo, rows[leg * perLeg + i].sB);
      hi = std::max(hi, rows[leg * perLeg + i].sB);
    }
    CHECK(lo < 1.6);
    CHECK(hi > 1.6);
  }
  // Cycle 2 (legs 4-5) against cycle 1 (legs 2-3), increment by increment.
  for (int i = perLeg; i < 3 * perLeg; ++i)
    CHECK(std::abs(rows[i].horizontal - rows[i + 2 * perLeg].horizontal) <= 0.02 * peak);
}
