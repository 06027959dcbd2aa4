// Large deflections: cantilever under a dead tip load against the inextensible elastica
// (reference by a shooting method computed here), and the roll-up of a beam into a circle by an
// end moment M = 2 pi EI / L.
#include "beam_fixtures.h"

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>

using namespace fibra;
using namespace fibra::test;

namespace {

// Elastica of a cantilever under a dead load P normal to it, lambda = P L^2 / EI, arc length
// u in [0, 1]: theta'' = lambda cos(theta), theta(0) = 0, theta'(1) = 0 (load along -y).
// Returns the tip (x, y) / L. RK4 on (theta, theta', x, y); bisection on theta'(0).
Eigen::Vector2d elasticaTip(double lambda) {
  auto integrate = [lambda](double k, Eigen::Vector2d& tip) {
    const int n = 4000;
    const double h = 1.0 / n;
    Eigen::Vector4d y(0, k, 0, 0);
    auto rhs = [lambda](const Eigen::Vector4d& s) {
      return Eigen::Vector4d(s(1), lambda * std::cos(s(0)), std::cos(s(0)), std::sin(s(0)));
    };
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector4d k1 = rhs(y), k2 = rhs(y + 0.5 * h * k1), k3 = rhs(y + 0.5 * h * k2),
                            k4 = rhs(y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    tip = y.tail<2>();
    return y(1);  // theta'(1)
  };
  double lo = -lambda, hi = 0;
  Eigen::Vector2d tip;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (integrate(mid, tip) > 0 ? hi : lo) = mid;
  }
  integrate(0.5 * (lo + hi), tip);
  return tip;
}

}  // namespace

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
