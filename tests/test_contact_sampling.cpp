// Where a line contact samples the gap (contact.element_placement, docs/CONTACT.md 1.4): a
// fibre U held over a parallel held fibre D (R = 0.1 mm each, 6 mm long), its centreline bent
// so that it comes closest to D's axis at one point, where the two overlap by delta. The true
// overlap is known in closed form; the deepest penetration the contact elements report must
// match it:
// - U kinked at one of its nodes (a polyline through that node): the Gauss points lie 0.21 h
//   from the node and see the fibres apart; the Lobatto placement puts an element at the node.
// - U a parabola z = zmin + kappa/2 (x - x0)^2 (quadratic elements interpolate it exactly),
//   its lowest point x0 anywhere along an element: the Lobatto placement cuts its pieces until
//   the gap cannot dip more than p_max / 4 between samples; the Gauss points leave up to
//   kappa (0.29 h)^2 / 8 unseen.
#include "engine/world.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

using namespace fibra;

namespace {

constexpr double kR = 0.1, kDelta = 2e-4, kPMax = 1e-4;  // radius, overlap, p_max, mm

// U through the points of `shape` (x -> z) at `vertices` + 1 equally spaced x in [-3, 3], D
// straight at z = 0; both clamped, one increment: the contact elements of that state.
SceneDef heldPair(const std::function<double(double)>& shape, int vertices, int elementsU,
                  int elementsD, const char* placement) {
  std::ostringstream points;
  points.precision(17);
  for (int k = 0; k <= vertices; ++k) {
    const double x = -3 + 6.0 * k / vertices;
    points << (k ? ", " : "") << "[" << x << ", 0, " << shape(x) << "]";
  }
  const std::string text = R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [
      {"name": "U", "material": "m", "radius": 0.1, "elements": )" +
                           std::to_string(elementsU) + R"(,
       "geometry": {"type": "polyline", "points": [)" + points.str() +
                           R"(], "director": [0, 1, 0]}},
      {"name": "D", "material": "m", "radius": 0.1, "elements": )" +
                           std::to_string(elementsD) + R"(,
       "geometry": {"type": "line", "points": [[-3, 0, 0], [3, 0, 0]], "director": [0, 1, 0]}}],
    "boundary_conditions": [{"type": "clamp", "group": "U.all"},
                            {"type": "clamp", "group": "D.all"}],
    "contact": {"max_penetration": 1e-4, "element_placement": ")" +
                           placement + R"("},
    "steps": [{"end_time": 1, "increments": 1}]})";
  return loadSceneFromString(text, "held_pair.json");
}

// The deepest penetration -g_N among the fibre-fibre elements (0 when none penetrates), mm.
double deepestPenetration(const SceneDef& s) {
  World w(s);
  REQUIRE(w.step().status == StepStatus::Converged);
  const ContactSnapshot c = w.contactSnapshot();
  double deepest = 0;
  for (Index e = 0; e < c.size(); ++e)
    if (!c.tool[e]) deepest = std::max(deepest, -c.gap[e]);
  return deepest;
}

}  // namespace

TEST_CASE("an element sits at a kink of the centreline at a node (Lobatto placement)") {
  // U: two straight halves meeting at x = 0, node 12 of its 12 quadratic elements, at
  // z = 2R - delta; slope 0.01. D's 7 elements put none of its nodes there.
  auto vee = [](double x) { return 2 * kR - kDelta + 0.01 * std::abs(x); };
  const double lobatto = deepestPenetration(heldPair(vee, 2, 12, 7, "lobatto"));
  const double gauss = deepestPenetration(heldPair(vee, 2, 12, 7, "weighted"));
  MESSAGE("kink: true overlap " << kDelta << ", Lobatto " << lobatto << ", Gauss " << gauss);
  CHECK(lobatto == doctest::Approx(kDelta).epsilon(1e-3).scale(0));
  // The nearest Gauss point, 0.106 mm from the node, is 1.06e-3 mm higher: no penetration seen.
  CHECK(gauss == 0);
}

TEST_CASE("a smooth dip between nodes is sampled within p_max / 4 (Lobatto placement)") {
  // kappa = 0.05 / mm: the Gauss points 0.29 h = 0.14 mm apart in the middle of an element
  // miss up to 0.05 * 0.14^2 / 8 = 1.3e-4 mm = 1.3 p_max.
  constexpr double kappa = 0.05;
  double worstLobatto = 0, worstGauss = 0;
  for (const double x0 : {0.0, 0.06, 0.125, 0.19, 0.25, 0.31, 0.4}) {
    CAPTURE(x0);
    auto parabola = [&](double x) { return 2 * kR - kDelta + 0.5 * kappa * (x - x0) * (x - x0); };
    const double lobatto = deepestPenetration(heldPair(parabola, 2000, 12, 7, "lobatto"));
    const double gauss = deepestPenetration(heldPair(parabola, 2000, 12, 7, "weighted"));
    CHECK(lobatto <= kDelta * (1 + 1e-3));
    CHECK(lobatto >= kDelta - 0.25 * kPMax);
    worstLobatto = std::max(worstLobatto, kDelta - lobatto);
    worstGauss = std::max(worstGauss, kDelta - gauss);
  }
  MESSAGE("parabola: most missed, Lobatto " << worstLobatto << " mm, Gauss " << worstGauss
                                            << " mm");
  CHECK(worstGauss > 0.5 * kPMax);  // what the Lobatto placement's sub-pieces are for
}
