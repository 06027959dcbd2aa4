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
// And where the default Gauss placement misses an overlap at a node in a loaded scene (a
// twisted 19-fibre bundle), the acceptance gives those zones Lobatto elements
// (engine/contact_loops.h): the run converges, its overlap measured from the nodes alone stays
// within the acceptance's bound, and the refinement survives a checkpoint.
#include "bench/contact_scenes.h"
#include "centreline_measure.h"
#include "engine/world.h"
#include "io/scene_loader.h"
#include "systems/interpolation.h"

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

namespace {

// The deepest true overlap of fibres I and J of the state q, measured from their nodes alone
// (tests/centreline_measure.h): for every s on I in steps of 0.01 mm, the closest point of J
// within 0.2 mm of the same s (a golden-section search on the distance) and there
// w_I + w_J - d, the half-widths along the line of centres; mm.
double deepestOverlap(const FibreStore& fs, const Eigen::VectorXd& q, Index I, Index J) {
  double deepest = -1e300;
  for (double s = 0; s <= fs.length[I]; s += 0.01) {
    const Vec3 x = test::centreline(fs, q, I, s);
    const auto d = [&](double t) { return (test::centreline(fs, q, J, t) - x).norm(); };
    double lo = std::max(0.0, s - 0.2), hi = std::min(fs.length[J], s + 0.2);
    const double r = (std::sqrt(5.0) - 1) / 2;
    for (int k = 0; k < 60; ++k) {
      const double u = hi - r * (hi - lo), v = lo + r * (hi - lo);
      if (d(u) < d(v)) hi = v;
      else lo = u;
    }
    const double t = 0.5 * (lo + hi);
    const Vec3 fromJ = x - test::centreline(fs, q, J, t);
    deepest = std::max(deepest, test::overlapAt(fs, q, I, J, {fromJ.norm(), fromJ, s, t}));
  }
  return deepest;
}

}  // namespace

TEST_CASE("the acceptance refines the zones whose fibres overlap between their Gauss elements") {
  // A 19-fibre bundle of 4 elements per fibre (h = 1 mm), twisted a quarter turn under tension,
  // mu = 0.1, p_max = 1e-4 mm (bench/contact_scenes.h): by t = 1.9 neighbour fibres overlap by
  // 3.5 p_max near a node (s = 0.93 mm, the node at 1.0) where the Gauss elements, 0.21 h from
  // it, report 1.0. A new
  // detection places the same elements, so before the refinement every attempt of that
  // increment failed as an inconsistent set and the run stopped at t = 1.876. The zones that
  // overlap take Lobatto elements (an element at the node) and keep them.
  const double pMax = 1e-4;
  const SceneDef scene = scenes::twistedBundle(2, 4, pMax, 0.1);
  World w(scene);
  StepReport r;
  int refined = 0, zones = 0, iterations = 0;
  std::stringstream checkpoint;  // the first state with refined zones
  while (!w.finished()) {
    r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    // The increment where zones are first refined says so (summed over its converged attempts).
    if (refined == 0 && r.contact.refinedZones > 0) CHECK(r.contact.newlyRefinedZones > 0);
    if (refined == 0 && r.contact.refinedZones > 0 && !w.finished()) w.saveCheckpoint(checkpoint);
    refined = std::max(refined, r.contact.refinedZones);
    zones = r.contact.zones;
    iterations += r.iterations;
  }
  MESSAGE("refined zones " << refined << " of " << zones << ", " << iterations << " Newton iterations");
  CHECK(refined > 0);
  CHECK(refined < zones);  // only where the acceptance found an overlap between elements
  const ZoneStore& z = w.contact().zones;
  CHECK(std::count(z.refined.begin(), z.refined.end(), 1) == r.contact.refinedZones);
  const ContactSnapshot c = w.contactSnapshot();  // as the contact VTU shows them: per element
  int refinedElements = 0;
  for (Index e = 0; e < w.contact().elements.size(); ++e) {
    CHECK(c.zone[e] == w.contact().elements.zone[e]);
    CHECK(c.refined[e] == z.refined[c.zone[e]]);
    refinedElements += c.refined[e];
  }
  CHECK(refinedElements >= r.contact.refinedZones);
  // The refinement is carried in the checkpoint: resumed from it, the run ends bitwise the same.
  REQUIRE(checkpoint.rdbuf()->in_avail() > 0);
  World resumed(scene);
  resumed.restoreCheckpoint(checkpoint);
  while (!resumed.finished()) REQUIRE(resumed.step().status == StepStatus::Converged);
  CHECK(resumed.fibres().q == w.fibres().q);
  // The final state's overlap, from the nodes alone, over every pair of neighbours (centres 2R
  // apart at the start): within the acceptance's bound, and what the acceptance measured.
  const FibreStore& fs = w.fibres();
  double deepest = 0;
  for (Index I = 0; I < fs.fibres(); ++I)
    for (Index J = I + 1; J < fs.fibres(); ++J)
      if ((x0Of(fs.qRef, fs.firstNode[I]) - x0Of(fs.qRef, fs.firstNode[J])).norm() <
          2.1 * fs.radius[I])
        deepest = std::max(deepest, deepestOverlap(fs, fs.q, I, J));
  MESSAGE("deepest overlap " << deepest / pMax << " p_max; acceptance " << r.contact.maxOverlapRatio
                             << ", elements " << r.contact.maxPenetrationRatio);
  CHECK(deepest <= 1.5 * std::max(1.0, r.contact.maxPenetrationRatio) * pMax);
  CHECK(deepest >= 0.95 * r.contact.maxOverlap);
}
