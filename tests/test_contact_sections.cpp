// Nearest sections in the eq. 8 plane (systems/contact_sections.h): on a fibre wound round a
// straight core, cut by the plane of a pair that the zone's linear map puts apart along the
// core, the eq. 8 cuts lie apart along the fibres and their centre distance exceeds the helix
// radius; the nearest pair keeps its midpoint in the plane and reaches the minimum of the
// distance along that constraint, found here independently by dense sampling and bisection.
// On straight parallel fibres the eq. 8 pair is that minimum already.
#include "contact_fixtures.h"
#include "systems/contact_geometry.h"
#include "systems/contact_sections.h"

#include <doctest/doctest.h>

#include <numbers>

using namespace fibra;

namespace {

// Two fibres of `elements` quadratic elements; their nodes placed on x(s) for each.
template <class PathI, class PathJ>
FibreStore twoFibres(int elements, double lengthI, double lengthJ, PathI xI, PathJ xJ,
                     Eigen::VectorXd& q, CentrelineStore& cl) {
  FibreStore fs;
  fixtures::add(fs, fixtures::polylineFibre("i", 0.1, elements, 2, {Vec3(0, 0, 0), Vec3(lengthI, 0, 0)}));
  fixtures::add(fs, fixtures::polylineFibre("j", 0.1, elements, 2, {Vec3(0, 1, 0), Vec3(lengthJ, 1, 0)}));
  q = fs.q;
  for (Index f = 0; f < 2; ++f)
    for (Index k = 0; k < fs.nodeCount[f]; ++k) {
      const double s = fs.length[f] * double(k) / double(fs.nodeCount[f] - 1);
      x0Of(q, fs.firstNode[f] + k) = f == 0 ? xI(s) : xJ(s);
    }
  cl.poly.clear();
  for (Index e = 0; e < Index(fs.elementFirstNode.size()); ++e) cl.poly.push_back(centrelinePolynomial(fs, q, e));
  return fs;
}

// The root of F on [a, b] by bisection (F(a), F(b) of opposite signs).
template <class F>
double bisect(F f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double m = 0.5 * (a + b), fm = f(m);
    if ((fm > 0) == (fa > 0)) a = m, fa = fm;
    else b = m;
  }
  return 0.5 * (a + b);
}

}  // namespace

TEST_CASE("nearest sections: a skewed pair on a fibre wound round a core reaches the constrained minimum") {
  // I the core along z; J a helix of radius 0.19 mm (R = 0.1: overlap 0.01 mm) and pitch 1 mm
  // round it, 3 turns; c = ds_J / dz.
  const double r = 0.19, pitch = 1, L = 3, k = 2 * std::numbers::pi / pitch;
  const double c = std::sqrt(1 + (k * r) * (k * r));
  Eigen::VectorXd q;
  CentrelineStore cl;
  const FibreStore fs = twoFibres(
      32, L, c * L, [](double s) { return Vec3(0, 0, s); },
      [&](double s) { const double z = s / c; return Vec3(r * std::cos(k * z), r * std::sin(k * z), z); }, q, cl);
  // The plane of a pair the zone's linear map puts 0.2 mm apart along z: through their
  // midpoint, normal to t_int = (t_I dI + t_J dJ) / 2 with dJ / dI = c.
  const double sI0 = 1.0, sJ0 = 1.2 * c;
  const CentrelinePoint pI = centrelineAt(fs, cl, 0, sI0), pJ = centrelineAt(fs, cl, 1, sJ0);
  const Vec3 xInt = 0.5 * (pI.x + pJ.x), t = (pI.dxds + c * pJ.dxds).normalized();
  auto side = [&](Index f, double s) { return (centrelineAt(fs, cl, f, s).x - xInt).dot(t); };
  // Eq. 8: each fibre cut by the plane.
  const double cutI = bisect([&](double s) { return side(0, s); }, sI0 - 0.3, sI0 + 0.3);
  const double cutJ = bisect([&](double s) { return side(1, s); }, sJ0 - 0.3, sJ0 + 0.3);
  auto distance = [&](double a, double b) {
    return (centrelineAt(fs, cl, 0, a).x - centrelineAt(fs, cl, 1, b).x).norm();
  };
  const double eq8 = distance(cutI, cutJ);
  CHECK(eq8 > 0.19 + 3e-3);  // the cuts are not facing: 0.0044 mm of the overlap missed
  double sI = cutI, sJ = cutJ;
  const SectionWindows w{0, fs.length[0], 0, fs.length[1]};
  REQUIRE(nearestSectionsInPlane(fs, cl, 0, 1, xInt, t, w, 0, sI, sJ));
  // The midpoint stays in the plane.
  CHECK(std::abs((0.5 * (centrelineAt(fs, cl, 0, sI).x + centrelineAt(fs, cl, 1, sJ).x) - xInt).dot(t)) < 1e-12);
  // Independently: for each a on I, b on J with the midpoint in the plane (bisection); the
  // distance along that constraint is smallest at sI among its neighbours, and within the
  // interpolation's ripple (1e-5 mm) of the smallest over +-0.4 mm by dense sampling.
  auto partner = [&](double a) {
    const Vec3 xa = centrelineAt(fs, cl, 0, a).x;
    return bisect([&](double b) { return (0.5 * (xa + centrelineAt(fs, cl, 1, b).x) - xInt).dot(t); },
                  cutJ - 0.5, cutJ + 0.5);
  };
  CHECK(std::abs(partner(sI) - sJ) < 1e-9);
  for (const double da : {-1e-3, -1e-4, 1e-4, 1e-3}) CHECK(distance(sI + da, partner(sI + da)) >= distance(sI, sJ));
  double best = 1e300;
  for (int n = 0; n <= 4000; ++n) {
    const double a = cutI - 0.4 + 0.8 * n / 4000;
    best = std::min(best, distance(a, partner(a)));
  }
  CHECK(distance(sI, sJ) <= best + 1e-5);
  CHECK(distance(sI, sJ) < eq8 - 3e-3);
  CHECK(distance(sI, sJ) == doctest::Approx(0.19).epsilon(1e-3).scale(0));  // the helix radius
  // With a window in the way (J's held within 1e-3 mm of its cut), nothing moves.
  double a = cutI, b = cutJ;
  CHECK(std::abs(sJ - cutJ) > 1e-2);
  const bool kept = nearestSectionsInPlane(fs, cl, 0, 1, xInt, t, {0, fs.length[0], cutJ - 1e-3, cutJ + 1e-3}, 0, a, b);
  CHECK_FALSE(kept);
  CHECK(a == cutI);
  CHECK(b == cutJ);
}

TEST_CASE("nearest sections: straight parallel fibres keep their eq. 8 pair") {
  Eigen::VectorXd q;
  CentrelineStore cl;
  const FibreStore fs = twoFibres(
      8, 4, 4, [](double s) { return Vec3(s, 0, 0); }, [](double s) { return Vec3(s, 0.19, 0.01); }, q, cl);
  for (const double s : {0.3, 1.7, 2.0, 3.9}) {
    const Vec3 xInt(s, 0.095, 0.005), t(1, 0, 0);
    double sI = s, sJ = s;
    const bool moved = nearestSectionsInPlane(fs, cl, 0, 1, xInt, t, {0, 4, 0, 4}, 0, sI, sJ);
    CHECK(moved);
    CHECK(std::abs(sI - s) < 1e-12);
    CHECK(std::abs(sJ - s) < 1e-12);
  }
}
