// Contact detection against the brute-force reference (tests/contact_reference.h): the same
// zones (same intervals within 1e-9 mm) and the same contact elements, on seeded assemblies of
// every kind: straight, curved, crossing, nearly parallel, touching at element ends, mixed orders.
#include "contact_fixtures.h"
#include "contact_reference.h"
#include "systems/contact_detection.h"

#include <doctest/doctest.h>

using namespace fibra;

namespace {

struct Coverage {
  int zones = 0, elements = 0, checkedElements = 0, zeroLength = 0, sectionFallbacks = 0;
  int tangentFallbacks = 0, crossing = 0, parallel = 0, blended = 0, endFaces = 0;
  int movedToClosest = 0;  // elements of zones of several moved to a crossing's closest points
  int dips = 0;            // elements at one of a point zone's several minima
  int faceTies = 0;        // end-face elements whose deepest face point is not unique
  int pastEnd = 0;         // crossing normals from the segments' closest points past an end
};

void compareElements(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
                     const ZoneStore& zones, const ContactElementStore& el,
                     const reference::Zone& rz, Index z, Coverage& cov) {
  bool ambiguousCount = false;
  const std::vector<reference::Element> ref = reference::elements(fs, q, p, rz, ambiguousCount);
  if (ambiguousCount) return;
  REQUIRE(zones.elementCount[z] == Index(ref.size()));
  for (Index k = 0; k < zones.elementCount[z]; ++k) {
    const Index e = zones.firstElement[z] + k;
    const reference::Element& r = ref[k];
    ++cov.elements;
    if (r.ambiguous) continue;
    ++cov.checkedElements;
    CAPTURE(z);
    CAPTURE(k);
    CHECK(el.zone[e] == z);
    CHECK(std::abs(el.zeta[e] - r.zeta) <= 1e-10);
    // A point contact carries L_int, which the pipeline integrates by two-point Gauss on each
    // piece (|t_int| is the root of a quadratic there: 1.7% off on a curved crossing whose t_int
    // nearly cancels), the reference by Richardson-extrapolated chords; a line element's length
    // is the same Gauss weight in both.
    CHECK(std::abs(el.length[e] - r.length) <= (ref.size() == 1 || r.dip ? 0.02 : 1e-9) * (1e-3 + r.length));
    CHECK((el.fallback[e] & (7 | kEndFaceI | kEndFaceJ)) == r.fallback);
    cov.endFaces += (r.fallback & (kEndFaceI | kEndFaceJ)) != 0;
    cov.movedToClosest += zones.elementCount[z] > 1 && el.crossing[e] && !r.dip;
    cov.dips += r.dip;
    cov.faceTies += r.faceTie;
    cov.pastEnd += r.pastEnd;
    CHECK(std::abs(el.gap[e] - r.gap) <= 1e-8);
    if (r.faceTie) continue;
    // an end face's partner section is the foot of its face point, found by two searches (1e-7)
    const double sTol = r.fallback & (kEndFaceI | kEndFaceJ) ? 1e-7 : 1e-8;
    CHECK(std::abs(el.sI[e] - r.sI) <= sTol);
    CHECK(std::abs(el.sJ[e] - r.sJ) <= sTol);
    CHECK(std::abs(el.xiI1[e] - r.xiI[0]) <= 1e-8);
    CHECK(std::abs(el.xiI2[e] - r.xiI[1]) <= 1e-8);
    CHECK(std::abs(el.xiJ1[e] - r.xiJ[0]) <= 1e-8);
    CHECK(std::abs(el.xiJ2[e] - r.xiJ[1]) <= 1e-8);
    CHECK((el.normal[e] - r.normal).norm() <= 1e-6);
    CHECK(std::abs(el.theta[e] - r.theta) <= 1e-6);
    cov.sectionFallbacks += (r.fallback & 3) != 0;
    cov.tangentFallbacks += (r.fallback & kFallbackTangent) != 0;
    cov.crossing += el.crossWeight[e] == 1;
    cov.parallel += el.crossWeight[e] == 0;
    cov.blended += el.crossWeight[e] > 0 && el.crossWeight[e] < 1;
  }
}

Coverage compareWithReference(const FibreStore& fs, const Eigen::VectorXd& q,
                              const ContactParams& p) {
  ContactCache cache;
  ZoneStore zones;
  ContactElementStore el;
  detectContacts(fs, q, p, cache, zones, el);
  const reference::Detection ref = reference::detect(fs, q, p);
  REQUIRE(ref.ambiguousPoints == 0);
  REQUIRE(zones.size() == Index(ref.zones.size()));
  Coverage cov;
  for (Index z = 0; z < zones.size(); ++z) {
    const reference::Zone& r = ref.zones[z];
    CAPTURE(z);
    REQUIRE(zones.fibreI[z] == r.I);
    REQUIRE(zones.fibreJ[z] == r.J);
    CHECK(zones.sI1[z] == r.sI1);  // the same test-point grid: exact
    CHECK(zones.sI2[z] == r.sI2);
    CHECK(std::abs(zones.sJ1[z] - r.sJ1) <= 1e-9);
    CHECK(std::abs(zones.sJ2[z] - r.sJ2) <= 1e-9);
    CHECK(std::abs(zones.minDistance[z] - r.minDistance) <= 1e-9);
    CHECK(zones.testPoints[z] == r.testPoints);
    cov.zeroLength += r.testPoints == 1;
    compareElements(fs, q, p, zones, el, r, z, cov);
  }
  cov.zones = zones.size();
  return cov;
}

using fixtures::defaults;

}  // namespace

TEST_CASE("contact detection matches the brute-force reference: straight fibres") {
  for (unsigned seed : {1u, 2u, 3u}) {
    CAPTURE(seed);
    const FibreStore fs = fixtures::straight(seed);
    const Coverage cov = compareWithReference(fs, fs.q, defaults(fs));
    CHECK(cov.zones >= 5);
    CHECK(cov.checkedElements >= 0.9 * cov.elements);
  }
}

TEST_CASE("contact detection matches the brute-force reference: curved and deformed fibres") {
  for (unsigned seed : {4u, 5u}) {
    CAPTURE(seed);
    const FibreStore fs = fixtures::curved(seed);
    const ContactParams p = defaults(fs);
    const Coverage a = compareWithReference(fs, fs.q, p);
    const Coverage b = compareWithReference(fs, fixtures::deformed(fs, seed, 0.02), p);
    CHECK(a.zones >= 5);
    CHECK(b.zones >= 5);
  }
}

TEST_CASE("contact detection matches the brute-force reference: crossings at every angle") {
  Coverage total;
  for (unsigned seed : {6u, 7u, 8u}) {
    CAPTURE(seed);
    const FibreStore fs = fixtures::crossing(seed);
    const Coverage c = compareWithReference(fs, fs.q, defaults(fs));
    total.zones += c.zones;
    total.sectionFallbacks += c.sectionFallbacks;
    total.crossing += c.crossing;
    total.blended += c.blended;
    total.movedToClosest += c.movedToClosest;
  }
  CHECK(total.zones >= 20);
  CHECK(total.sectionFallbacks > 0);  // steep crossings: J's section by the closest point
  CHECK(total.crossing > 0);
  MESSAGE("elements moved to the closest points of a crossing: " << total.movedToClosest);
  CHECK(total.movedToClosest > 0);
}

TEST_CASE("contact detection matches the brute-force reference: nearly parallel fibres") {
  Coverage total;
  for (unsigned seed : {9u, 10u}) {
    CAPTURE(seed);
    const FibreStore fs = fixtures::nearlyParallel(seed);
    const Coverage c = compareWithReference(fs, fixtures::deformed(fs, seed, 0.005, false), defaults(fs));
    total.zones += c.zones;
    total.parallel += c.parallel;
    total.blended += c.blended;
    total.checkedElements += c.checkedElements;
  }
  CHECK(total.zones >= 20);
  CHECK(total.parallel > 0);
  CHECK(total.checkedElements >= 200);
}

TEST_CASE("contact detection matches the brute-force reference: contacts at element ends") {
  const FibreStore fs = fixtures::elementEnds();
  const Coverage c = compareWithReference(fs, fs.q, defaults(fs));
  CHECK(c.zones >= 10);
  CHECK(c.zeroLength >= 1);  // the end-to-end pair meets at one test point
  CHECK(c.endFaces >= 1);    // an end face against another fibre's side
}

TEST_CASE("contact detection matches the brute-force reference: end faces at their deepest point, crossings past an end") {
  // Every end face of the straight and curved assemblies against the reference's polar grid and
  // compass search over the disc (tests/contact_reference.h): the face point deepest in the
  // partner, the partner's section at its foot, the gap. Ties (a chord of equal depth) are
  // compared by their gap alone; they must not be all there is.
  Coverage total;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    CAPTURE(seed);
    const FibreStore fs = seed <= 3 ? fixtures::straight(seed) : fixtures::curved(seed);
    const Coverage c = compareWithReference(fs, seed <= 3 ? fs.q : fixtures::deformed(fs, seed, 0.02),
                                            defaults(fs));
    total.endFaces += c.endFaces;
    total.faceTies += c.faceTies;
    total.pastEnd += c.pastEnd;
  }
  MESSAGE("end-face elements " << total.endFaces << ", of which ties " << total.faceTies
                               << "; crossing normals past an end " << total.pastEnd);
  CHECK(total.endFaces - total.faceTies >= 10);
  CHECK(total.pastEnd >= 10);  // side elements whose tangent lines meet past an end
}

TEST_CASE("contact detection matches the brute-force reference: mixed orders and self-contact") {
  for (unsigned seed : {11u, 12u}) {
    CAPTURE(seed);
    const FibreStore fs = fixtures::mixedOrders(seed);
    compareWithReference(fs, fixtures::deformed(fs, seed, 0.01), defaults(fs));
  }
  FibreStore coil;  // a tight helix whose turns touch: self-contact zones between turns
  fixtures::add(coil, fixtures::helixFibre(0.05, 24, Vec3::Zero(), Vec3::UnitZ(), 0.3, 0.11, 3, 0));
  ContactDef def;
  def.selfContact = true;
  const ContactParams p = resolveContactParams(coil, def);
  const Coverage c = compareWithReference(coil, coil.q, p);
  CHECK(c.zones >= 1);
  CHECK(c.elements >= 20);
}

TEST_CASE("contact detection matches the brute-force reference: a strand bent round a fibre") {
  // Two minima of the centre distance in one zone (tests/contact_fixtures.h, bentRound): a long
  // zone whose two narrow crossings take an element each (I in 8 elements), and a point zone
  // that takes an element at each minimum (I in 2).
  for (const int elementsI : {8, 2}) {
    CAPTURE(elementsI);
    const fixtures::BentRound b = fixtures::bentRound(0.1, elementsI, elementsI == 8 ? 2 : 4, 0.1997, 0.2027);
    const Coverage cov = compareWithReference(b.fs, b.q, defaults(b.fs));
    CHECK(cov.zones == 1);
    CHECK(cov.elements >= 2);
    CHECK(cov.checkedElements == cov.elements);
    CHECK((elementsI == 8 ? cov.movedToClosest : cov.dips) == 2);
  }
}
