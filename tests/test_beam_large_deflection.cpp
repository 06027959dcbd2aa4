// Large deflections: cantilever under a dead tip load against the inextensible elastica
// (reference by a shooting method, bench/elastica.h), and the roll-up of a beam into a circle by an
// end moment M = 2 pi EI / L.
#include "beam_fixtures.h"
#include "bench/elastica.h"

#include <doctest/doctest.h>

using namespace fibra;
using namespace fibra::test;

TEST_CASE("elastica reference reproduces the known cantilever tip for PL^2/EI = 10") {
  // Tabulated (e.g. Mattiasson 1981): u/L = 0.55494, v/L = 0.81061.
  const Eigen::Vector2d tip = elasticaTip(10);
  CHECK(1 - tip.x() == doctest::Approx(0.55494).epsilon(1e-4));
  CHECK(-tip.y() == doctest::Approx(0.81061).epsilon(1e-4));
}

TEST_CASE("cantilever under a dead tip load follows the elastica within 0.5%") {
  for (double lambda : {1.0, 3.0, 10.0}) {
    CAPTURE(lambda);
    BeamSpec b;  // L/R = 100, 10 quadratic elements
    const double P = lambda * bendingStiffness(b) / (b.length * b.length);
    SceneDef s = straightBeam(b, 10);
    clampStart(s);
    tipLoad(s, LoadKind::Force, Vec3(0, -P, 0));
    World w(s);
    REQUIRE(solveAll(w));
    const Eigen::Vector2d ref = elasticaTip(lambda) * b.length;
    const Vec3 tip = tipPosition(w);
    // Displacements (u along the beam, v across) within 0.5% of the elastica's.
    CHECK(std::abs((b.length - tip.x()) / (b.length - ref.x()) - 1) < 0.005);
    CHECK(std::abs(tip.y() / ref.y() - 1) < 0.005);
  }
}

TEST_CASE("roll-up: an end moment 2 pi EI / L bends the beam into a circle") {
  BeamSpec b;
  b.radius = b.length / 1000;
  b.elements = 20;
  SceneDef s = straightBeam(b, 10);
  clampStart(s);
  tipLoad(s, LoadKind::Moment, Vec3(0, 0, 2 * std::numbers::pi * bendingStiffness(b) / b.length));
  World w(s);
  REQUIRE(solveAll(w));
  CHECK(tipPosition(w).norm() < 0.005 * b.length);
  // Every node lies on the circle of radius L / 2 pi through the origin, centred on the y axis.
  const double radius = b.length / (2 * std::numbers::pi);
  for (Index n = 0; n < w.fibres().nodes(); ++n)
    CHECK(std::abs((x0Of(w.fibres().q, n) - Vec3(0, radius, 0)).norm() - radius) < 0.005 * radius);
}

TEST_CASE("the energy line search costs the roll-up at most 1.5x the iterations of plain Newton") {
  // ../shared/cases/rollup_line_search.json: a 100 mm beam (R 0.1 mm, E 1000 MPa, 20 elements)
  // rolled into a circle in 20 increments. The line search once cut every increment to 1/80 to
  // 1/160 of the load: 6270 iterations against ~220.
  BeamSpec b;
  b.length = 100;
  b.elements = 20;
  b.young = 1000;
  const auto iterations = [&](bool lineSearch) {
    SceneDef s = straightBeam(b, 20);
    clampStart(s);
    tipLoad(s, LoadKind::Moment, Vec3(0, 0, 2 * std::numbers::pi * bendingStiffness(b) / b.length));
    s.steps[0].lineSearch = lineSearch;
    World w(s);
    int total = 0;
    while (!w.finished()) {
      const StepReport r = w.step();
      REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
      total += r.totalIterations;
    }
    CHECK(tipPosition(w).norm() < 0.005 * b.length);  // the circle closes
    return total;
  };
  const int searched = iterations(true), plain = iterations(false);
  MESSAGE("roll-up in 20 increments: " << searched << " iterations with the line search, " << plain
                                        << " without");
  CHECK(double(searched) <= 1.5 * double(plain));
}
