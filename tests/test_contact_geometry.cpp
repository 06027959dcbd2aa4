// Contact detection geometry: the closest-point kernel, particles on deformed section outlines,
// normals and gaps (unit, from J to I, odd in the swap of I and J), the documented degenerate
// cases, and the parameter defaults.
#include "contact_fixtures.h"
#include "engine/contact_setup.h"
#include "systems/contact_detection.h"
#include "systems/contact_geometry.h"
#include "systems/contact_normals.h"
#include "systems/contact_queries.h"

#include <doctest/doctest.h>

#include <numbers>
#include <random>

using namespace fibra;

namespace {

using fixtures::Detected;
using fixtures::defaults;
using fixtures::detect;

bool finite(const ContactElementStore& el) {
  for (Index e = 0; e < el.size(); ++e)
    if (!el.normal[e].allFinite() || !std::isfinite(el.gap[e]) || !std::isfinite(el.sI[e]) ||
        !std::isfinite(el.sJ[e]) || !std::isfinite(el.xiI1[e] + el.xiI2[e] + el.xiJ1[e] + el.xiJ2[e]) ||
        !std::isfinite(el.theta[e]) || !std::isfinite(el.crossWeight[e]))
      return false;
  return true;
}

FibreStore pair(const FibreDef& a, const FibreDef& b) {
  FibreStore fs;
  fixtures::add(fs, a);
  fixtures::add(fs, b);
  return fs;
}

}  // namespace

TEST_CASE("closest point on a quadratic element is the global minimum over the element") {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  int twoMinima = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double curl = trial % 2 ? 2.0 : 0.2;  // strongly curved elements have two local minima
    const CentrelinePolynomial P{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)),
                                 curl * Vec3(u(rng), u(rng), u(rng))};
    const Vec3 p(u(rng), u(rng), u(rng));
    const double z0 = trial % 3 ? -1 : -0.3 + 0.2 * u(rng), z1 = 1;
    const ClosestPoint c = closestOnPolynomial(P, p, z0, z1);
    auto D = [&](double z) { return (P.a + z * P.b + z * z * P.c - p).squaredNorm(); };
    double best = 1e300, zBest = 0;
    int localMinima = 0;
    const int n = 20000;
    for (int i = 0; i <= n; ++i) {
      const double z = z0 + (z1 - z0) * i / n, d = D(z);
      if (d < best) best = d, zBest = z;
      if (i > 0 && i < n && d < D(z0 + (z1 - z0) * (i - 1) / n) && d < D(z0 + (z1 - z0) * (i + 1) / n))
        ++localMinima;
    }
    twoMinima += localMinima >= 2;
    CAPTURE(trial);
    CHECK(c.z >= z0);
    CHECK(c.z <= z1);
    CHECK(std::abs(c.dist2 - D(c.z)) <= 1e-14 * (1 + c.dist2));
    CHECK(c.dist2 <= best + 1e-12);  // never worse than the sampled minimum
    CHECK(std::abs(c.z - zBest) <= 1e-3 + (std::abs(best - c.dist2) < 1e-9 ? 2.0 : 0.0));
  }
  CHECK(twoMinima >= 50);  // the hard case is exercised
}

TEST_CASE("particles lie on the deformed section outlines, facing the other section") {
  const FibreStore fs = fixtures::crossing(31);
  const Eigen::VectorXd q = fixtures::deformed(fs, 31, 0.01);  // elliptical, sheared sections
  Detected d;
  detect(fs, q, defaults(fs), d);
  REQUIRE(d.el.size() >= 20);
  int checked = 0, endFaces = 0;
  for (Index e = 0; e < d.el.size(); ++e) {
    for (int side = 0; side < 2; ++side) {
      const Index f = side ? d.el.fibreJ[e] : d.el.fibreI[e], o = side ? d.el.fibreI[e] : d.el.fibreJ[e];
      const double s = side ? d.el.sJ[e] : d.el.sI[e], so = side ? d.el.sI[e] : d.el.sJ[e];
      const double xi1 = side ? d.el.xiJ1[e] : d.el.xiI1[e], xi2 = side ? d.el.xiJ2[e] : d.el.xiI2[e];
      const Section c = sectionAt(fs, q, locate(fs, f, s)), other = sectionAt(fs, q, locate(fs, o, so));
      if (d.el.fallback[e] & (kEndFaceI | kEndFaceJ)) {  // on a flat end face: within its rim
        CHECK(std::hypot(xi1, xi2) <= fs.radius[f] * (1 + 1e-12));
        ++endFaces;
        continue;
      }
      CHECK(std::hypot(xi1, xi2) == doctest::Approx(fs.radius[f]).epsilon(1e-12).scale(0));
      // the particle x0 + xi1 g1 + xi2 g2 lies in the section plane along the projection of
      // the direction to the other centre (plane normal n = g1 x g2)
      const Vec3 r = xi1 * c.g1 + xi2 * c.g2, n = c.g1.cross(c.g2).normalized();
      const Vec3 d0 = other.x0 - c.x0, proj = d0 - d0.dot(n) * n;
      if (proj.norm() < 1e-6 * d0.norm()) continue;
      CHECK(r.cross(proj).norm() <= 1e-9 * r.norm() * proj.norm());
      CHECK(r.dot(proj) > 0);
      CHECK(std::abs(r.dot(n)) <= 1e-12 * r.norm());
      ++checked;
    }
  }
  CHECK(checked >= 40);
  MESSAGE(endFaces << " particles on end faces");
}

TEST_CASE("normals are unit and point from J to I, swapping I and J flips N and keeps gN") {
  for (unsigned seed : {41u, 42u}) {
    const FibreStore fs = seed == 41 ? fixtures::crossing(seed) : fixtures::nearlyParallel(seed);
    const Eigen::VectorXd q = fixtures::deformed(fs, seed, 0.005);
    const ContactParams p = defaults(fs);
    Detected d;
    detect(fs, q, p, d);
    REQUIRE(d.el.size() >= 20);
    ContactElementStore again = d.el, swapped = d.el;
    ContactLoopStats stats;
    updateNormalsAndGaps(fs, q, p, again, stats, nullptr);  // loop B at the same state: same values
    CHECK(stats.normalTurn <= 1e-7);
    std::swap(swapped.fibreI, swapped.fibreJ);
    std::swap(swapped.sI, swapped.sJ);
    std::swap(swapped.xiI1, swapped.xiJ1);
    std::swap(swapped.xiI2, swapped.xiJ2);
    for (std::uint8_t& f : swapped.fallback)  // an end face of I becomes one of J
      f = std::uint8_t((f & ~(kEndFaceI | kEndFaceJ)) | (f & kEndFaceI ? kEndFaceJ : 0) |
                       (f & kEndFaceJ ? kEndFaceI : 0));
    updateNormalsAndGaps(fs, q, p, swapped, stats, nullptr);
    for (Index e = 0; e < d.el.size(); ++e) {
      const Vec3 x0I = sectionAt(fs, q, locate(fs, d.el.fibreI[e], d.el.sI[e])).x0;
      const Vec3 x0J = sectionAt(fs, q, locate(fs, d.el.fibreJ[e], d.el.sJ[e])).x0;
      CHECK(d.el.normal[e].norm() == doctest::Approx(1).epsilon(1e-12));
      CHECK(d.el.normal[e].dot(x0I - x0J) >= -1e-12);
      CHECK((again.normal[e] - d.el.normal[e]).norm() <= 1e-14);
      CHECK(std::abs(again.gap[e] - d.el.gap[e]) <= 1e-14);
      // to round-off, which the crossing weight's factor for ends (contact_normals.h) divides by
      // 1 - (t_I.t_J)^2 >= sin^2 theta_parallel: 1e-16 in the tangents shows as up to 1e-13
      CHECK((swapped.normal[e] + d.el.normal[e]).norm() <= 1e-12);
      CHECK(std::abs(swapped.gap[e] - d.el.gap[e]) <= 1e-12);
      CHECK(swapped.theta[e] == doctest::Approx(d.el.theta[e]).epsilon(1e-14));
    }
  }
}

TEST_CASE("exactly parallel fibres: one zone along the overlap, zero gaps, centre-line normals") {
  const double R = 0.05;
  const FibreStore fs = pair(fixtures::polylineFibre("a", R, 8, 2, {Vec3(0, 0, 0), Vec3(1.6, 0, 0)}),
                             fixtures::polylineFibre("b", R, 8, 2, {Vec3(0, 2 * R, 0), Vec3(1.6, 2 * R, 0)}));
  Detected d;
  detect(fs, fs.q, defaults(fs), d);
  REQUIRE(d.zones.size() == 1);
  CHECK(d.zones.sI1[0] == 0);
  CHECK(d.zones.sI2[0] == doctest::Approx(1.6));
  CHECK(d.zones.sJ2[0] == doctest::Approx(1.6));
  CHECK(d.zones.minDistance[0] == doctest::Approx(2 * R).scale(0));
  CHECK(d.zones.elementCount[0] == 16);  // floor(2 L_int / h) = 2 per element
  REQUIRE(finite(d.el));
  for (Index e = 0; e < d.el.size(); ++e) {
    CHECK(d.el.fallback[e] == 0);
    CHECK(d.el.theta[e] <= 1e-12);
    CHECK(d.el.crossWeight[e] == 0);
    CHECK((d.el.normal[e] - Vec3(0, -1, 0)).norm() <= 1e-12);  // from J (y = 2R) to I (y = 0)
    CHECK(std::abs(d.el.gap[e]) <= 1e-12);
    CHECK(d.el.sI[e] == doctest::Approx(d.el.sJ[e]).epsilon(1e-12));
  }
}

TEST_CASE("coincident centrelines: full penetration along N from the particles, no NaN") {
  const double R = 0.05;
  const FibreDef f = fixtures::polylineFibre("a", R, 6, 2, {Vec3(0, 0, 0), Vec3(1.2, 0, 0)});
  const FibreStore fs = pair(f, f);
  Detected d;
  detect(fs, fs.q, defaults(fs), d);
  REQUIRE(d.zones.size() == 1);
  CHECK(d.zones.minDistance[0] == 0);
  REQUIRE(d.el.size() == 12);
  REQUIRE(finite(d.el));
  for (Index e = 0; e < d.el.size(); ++e) {
    CHECK((d.el.fallback[e] & (kFallbackParticleI | kFallbackParticleJ | kFallbackNormal)) ==
          (kFallbackParticleI | kFallbackParticleJ | kFallbackNormal));
    CHECK(d.el.normal[e].norm() == doctest::Approx(1));
    CHECK(d.el.gap[e] == doctest::Approx(-2 * R).scale(0));
  }
}

TEST_CASE("a fibre ending inside a zone: its sections stop at its ends, by the closest point") {
  const double R = 0.05;
  const FibreStore fs = pair(fixtures::polylineFibre("long", R, 10, 2, {Vec3(0, 0, 0), Vec3(2, 0, 0)}),
                             fixtures::polylineFibre("short", R, 4, 2, {Vec3(0.6, 2.2 * R, 0), Vec3(1.4, 2.2 * R, 0)}));
  Detected d;
  detect(fs, fs.q, defaults(fs), d);
  REQUIRE(d.zones.size() == 1);
  // the zone on the long fibre runs past the short one's ends while its ends stay within Delta
  CHECK(d.zones.sI1[0] < 0.6);
  CHECK(d.zones.sI2[0] > 1.4);
  CHECK(d.zones.sJ1[0] == 0);
  CHECK(d.zones.sJ2[0] == doctest::Approx(0.8));
  REQUIRE(finite(d.el));
  int ended = 0;
  for (Index e = 0; e < d.el.size(); ++e) {
    CHECK(d.el.sJ[e] >= 0);
    CHECK(d.el.sJ[e] <= 0.8 + 1e-12);
    if (d.el.fallback[e] & kFallbackSectionJ) {
      ++ended;
      CHECK((d.el.sJ[e] == 0 || d.el.sJ[e] == doctest::Approx(0.8)));
    } else {
      CHECK(d.el.gap[e] == doctest::Approx(0.2 * R).scale(0));
    }
  }
  CHECK(ended >= 2);  // both ends
}

TEST_CASE("perpendicular crossing: J's sections are the closest points, N along t_I x t_J") {
  const double R = 0.05;
  const FibreStore fs = pair(fixtures::polylineFibre("x", R, 6, 2, {Vec3(0, 0, 0), Vec3(1.2, 0, 0)}),
                             fixtures::polylineFibre("y", R, 6, 2, {Vec3(0.55, -0.6, 2.1 * R), Vec3(0.55, 0.6, 2.1 * R)}));
  Detected d;
  detect(fs, fs.q, defaults(fs), d);
  REQUIRE(d.zones.size() == 1);
  CHECK(d.zones.sJ1[0] == doctest::Approx(0.6));  // every test point projects on the crossing
  CHECK(d.zones.sJ2[0] == doctest::Approx(0.6));
  REQUIRE(d.el.size() >= 1);
  REQUIRE(finite(d.el));
  for (Index e = 0; e < d.el.size(); ++e) {
    CHECK((d.el.fallback[e] & kFallbackSectionJ) != 0);
    CHECK(d.el.sJ[e] == doctest::Approx(0.6).epsilon(1e-12));
    CHECK(d.el.crossWeight[e] == 1);
    CHECK((d.el.normal[e] - Vec3(0, 0, -1)).norm() <= 1e-12);  // I lies below J
  }
  const Index mid = d.zones.elementCount[0] / 2;  // elements straddle the crossing symmetrically
  CHECK(std::abs(d.el.sI[mid] - 0.55) <= 0.5 * 1.2 / 6);
}

TEST_CASE("a crossing in a zone of several elements: the nearest element moves to the closest points") {
  // J crosses x at 90 deg over s_I = 0.57 (between eq. 8 elements), its centreline 1.95 R above:
  // the fibres overlap by 0.05 R at s_I = 0.57, s_J = 0.6, and nowhere more.
  const double R = 0.05;
  const FibreStore fs = pair(fixtures::polylineFibre("x", R, 24, 2, {Vec3(0, 0, 0), Vec3(1.2, 0, 0)}),
                             fixtures::polylineFibre("y", R, 24, 2, {Vec3(0.57, -0.6, 1.95 * R), Vec3(0.57, 0.6, 1.95 * R)}));
  const ContactParams p = defaults(fs);
  // The patch where a penetration p_max can reach, l = sqrt(2 (2R) p_max / 1), is shorter than
  // a quarter element, h = 0.05 mm (docs/CONTACT.md "Crossings in long zones").
  REQUIRE(2 * std::sqrt(4 * R * p.pMax) < 0.5 * 0.05);
  Detected d;
  detect(fs, fs.q, p, d);
  REQUIRE(d.zones.size() == 1);
  REQUIRE(d.zones.elementCount[0] > 1);
  int moved = 0;
  double deepest = 1e300;
  for (Index e = 0; e < d.el.size(); ++e) {
    deepest = std::min(deepest, d.el.gap[e]);
    if (!d.el.crossing[e]) continue;
    ++moved;
    CHECK(d.el.sI[e] == doctest::Approx(0.57).epsilon(1e-12));
    CHECK(d.el.sJ[e] == doctest::Approx(0.6).epsilon(1e-12));
    CHECK(d.el.gap[e] == doctest::Approx(-0.05 * R).epsilon(1e-9));
  }
  CHECK(moved == 1);
  CHECK(deepest == doctest::Approx(-0.05 * R).epsilon(1e-9));  // the zone reports the overlap

  // At 10 deg the patch is longer than the elements' spacing: a line contact, eq. 8 sections.
  const double a = 10 * std::numbers::pi / 180;
  const Vec3 c(0.57, 0, 1.95 * R), t(std::cos(a), std::sin(a), 0);
  const FibreStore shallow = pair(fixtures::polylineFibre("x", R, 24, 2, {Vec3(0, 0, 0), Vec3(1.2, 0, 0)}),
                                  fixtures::polylineFibre("y", R, 24, 2, {c - 0.6 * t, c + 0.6 * t}));
  Detected e;
  detect(shallow, shallow.q, defaults(shallow), e);
  REQUIRE(e.zones.size() == 1);
  REQUIRE(e.zones.elementCount[0] > 1);
  for (Index k = 0; k < e.el.size(); ++k) CHECK(!e.el.crossing[k]);
}

TEST_CASE("zero-length zone: one proximate test point gives one element at zeta = 1/2") {
  const double R = 0.05;  // test points every 2R = 0.1 on x; J crosses over x = 0.6 at 2.95 R
  const FibreStore fs = pair(fixtures::polylineFibre("x", R, 6, 2, {Vec3(0, 0, 0), Vec3(1.2, 0, 0)}),
                             fixtures::polylineFibre("y", R, 6, 2, {Vec3(0.6, -0.6, 2.95 * R), Vec3(0.6, 0.6, 2.95 * R)}));
  Detected d;
  detect(fs, fs.q, defaults(fs), d);
  REQUIRE(d.zones.size() == 1);
  CHECK(d.zones.testPoints[0] == 1);
  CHECK(d.zones.sI1[0] == d.zones.sI2[0]);
  CHECK(d.zones.intermediateLength[0] == 0);
  REQUIRE(d.el.size() == 1);
  REQUIRE(finite(d.el));
  CHECK(d.el.zeta[0] == 0.5);
  CHECK((d.el.fallback[0] & kFallbackTangent) != 0);
  CHECK(d.el.sI[0] == doctest::Approx(0.6));
  CHECK(d.el.sJ[0] == doctest::Approx(0.6));
  CHECK(d.el.gap[0] == doctest::Approx(0.95 * R).scale(0));
}

TEST_CASE("parameter defaults follow the radii and element lengths, given values win") {
  FibreStore fs = pair(fixtures::polylineFibre("a", 0.05, 5, 2, {Vec3(0, 0, 0), Vec3(1, 0, 0)}),
                       fixtures::polylineFibre("b", 0.02, 4, 2, {Vec3(0, 1, 0), Vec3(2, 1, 0)}));
  const ContactParams p = defaults(fs);
  CHECK(proximityDistance(p, 0, 1) == doctest::Approx(1.5 * (0.05 + 0.02)).scale(0));
  CHECK(testIntervalsPerElement(fs, p, 0, 1) == 3);  // h = 0.2: l_zp = min(0.1, 0.07) -> 0.2 / 3
  CHECK(testIntervalsPerElement(fs, p, 0, 0) == 2);  // min(0.1, 0.1)
  CHECK(p.thetaParallel == doctest::Approx(5 * std::numbers::pi / 180).scale(0));
  CHECK(p.thetaCross == doctest::Approx(20 * std::numbers::pi / 180));
  CHECK(p.skin == doctest::Approx(0.01).scale(0));
  CHECK(p.selfSeparation[0] == doctest::Approx(0.3));  // 6 R
  CHECK(p.selfSeparation[1] == doctest::Approx(0.5));  // h = 0.5 > 6 R
  ContactDef def;
  def.proximityDistance = 0.3;
  def.testPointSpacing = 0.04;
  def.thetaCross = 0.5;
  def.thetaParallel = 0.1;
  def.skin = 0;
  const ContactParams g = resolveContactParams(fs, def);
  CHECK(proximityDistance(g, 0, 1) == doctest::Approx(0.3));
  CHECK(testIntervalsPerElement(fs, g, 0, 1) == 5);
  CHECK(g.thetaCross == 0.5);
  CHECK(g.skin == 0);
  def.thetaParallel = 0.6;
  CHECK_THROWS_AS(resolveContactParams(fs, def), SceneError);
  def.thetaParallel = 0.1;
  def.skin = -1;
  CHECK_THROWS_AS(resolveContactParams(fs, def), SceneError);
  // Newton's step limit (contact `step_penetration`) reaches the parameters, within its bounds.
  SceneDef scene;
  scene.contact.enabled = true;
  CHECK(resolveContact(fs, scene).stepPenetration == 10);
  scene.contact.stepPenetration = 3;
  CHECK(resolveContact(fs, scene).stepPenetration == 3);
  scene.contact.stepPenetration = 0.5;
  CHECK_THROWS_AS(resolveContact(fs, scene), SceneError);
}

TEST_CASE("a fibre's half-width along a direction normal to it: circle, sheared and stretched sections") {
  // The true overlap measure (systems/contact_queries.h) uses R |G^T n|: the outline's extent
  // along n, which is the width of the fibre there since n is normal to the centreline.
  const double R = 0.1, gamma = 0.09;  // mm, rad (a 5-degree shear)
  Section S;
  S.x0 = Vec3::Zero();
  S.dx0ds = Vec3::UnitX();
  S.g1 = Vec3::UnitY();
  S.g2 = Vec3::UnitZ();
  CHECK(halfWidth(S, R, Vec3::UnitY()) == doctest::Approx(R));
  CHECK(halfWidth(S, R, Vec3(0, 1, 1).normalized()) == doctest::Approx(R));
  // Section plane tilted by gamma about z (shear): seen along y the disc is R cos(gamma) wide.
  S.g1 = Vec3(std::sin(gamma), std::cos(gamma), 0);
  CHECK(halfWidth(S, R, Vec3::UnitY()) == doctest::Approx(R * std::cos(gamma)));
  CHECK(halfWidth(S, R, Vec3::UnitZ()) == doctest::Approx(R));
  // A section stretched by 10% along z: 1.1 R wide along z.
  S.g2 = 1.1 * Vec3::UnitZ();
  CHECK(halfWidth(S, R, Vec3::UnitZ()) == doctest::Approx(1.1 * R));
}

TEST_CASE("true overlap: crossing fibres with sheared sections, from a pair apart along a fibre") {
  // I along y with its axis h above J's, J along x (R = 0.1 both); J's sections sheared by gamma
  // towards its axis, g2 = (sin gamma, 0, cos gamma): J is R cos gamma high, and the fibres
  // overlap by R + R cos gamma - h, whichever of their sections an element pairs. Moved 0.0075 mm
  // along J (the plectoneme's loop over its clamped end: gamma 6.6 deg, the pair 0.0074 mm
  // apart), the pair's centres point through J's tilted disc lengthwise, where it is wider:
  // measured along them, 1.06e-3 mm for the true 8.4e-4.
  const double R = 0.1, gamma = 0.115, h = 0.1985;
  FibreStore fs;
  fixtures::add(fs, fixtures::polylineFibre("i", R, 4, 2, {Vec3(0, -1, h), Vec3(0, 1, h)}));
  fixtures::add(fs, fixtures::polylineFibre("j", R, 4, 2, {Vec3(-1, 0, 0), Vec3(1, 0, 0)}));
  Eigen::VectorXd q = fs.q;
  for (Index n = fs.firstNode[1]; n < fs.firstNode[1] + fs.nodeCount[1]; ++n)
    g2Of(q, n) = Vec3(std::sin(gamma), 0, std::cos(gamma));
  fs.q = q;
  const ContactParams p = defaults(fs);
  Detected d;
  detect(fs, q, p, d);
  REQUIRE(d.el.size() == 1);
  const double truth = R + R * std::cos(gamma) - h;
  ContactState state;
  state.zones = d.zones;
  state.elements = d.el;
  CHECK(trueOverlap(fs, q, d.cache.centrelines, state, p).depth ==
        doctest::Approx(truth).epsilon(1e-9).scale(0));
  const double sJ = state.elements.sJ[0];
  for (const double shift : {-0.0075, 0.0075}) {
    CAPTURE(shift);
    state.elements.sJ[0] = sJ + shift;
    const Overlap o = trueOverlap(fs, q, d.cache.centrelines, state, p);
    CHECK(o.depth == doctest::Approx(truth).epsilon(1e-9).scale(0));
    // what the pair's own centres read: over the truth on the side the disc tilts to
    const Section I = contactSection(fs, q, 0, state.elements.sI[0]);
    const Section J = contactSection(fs, q, 1, state.elements.sJ[0]);
    const Vec3 dd = I.x0 - J.x0, n = dd.normalized();
    const double centres = halfWidth(I, R, n) + halfWidth(J, R, n) - dd.norm();
    MESSAGE("shift " << shift << ": true " << truth << ", measured " << o.depth
                     << ", along the pair's centres " << centres);
    if (shift < 0) CHECK(centres > 1.2 * truth);
  }
}
