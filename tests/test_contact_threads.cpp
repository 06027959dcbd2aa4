// Contact detection determinism and zone identity (systems/contact_detection.h,
// systems/zone_identity.h): the stores are bitwise the same with 1 and 2 threads and from one
// call to the next when nothing moves; zones keep their ids under a motion within the skin; a
// zone that splits, merges or vanishes is reported through `id` and `previous` as documented.
#include "contact_fixtures.h"
#include "systems/contact_detection.h"

#include <doctest/doctest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>

using namespace fibra;

namespace {

using fixtures::Detected;
using fixtures::defaults;

void detectIn(tbb::task_arena& arena, const FibreStore& fs, const Eigen::VectorXd& q,
              const ContactParams& p, Detected& d) {
  arena.execute([&] { d.report = detectContacts(fs, q, p, d.cache, d.zones, d.el); });
}

void detectIn(int threads, const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
              Detected& d) {
  tbb::task_arena arena(threads);
  detectIn(arena, fs, q, p, d);
}

// Detection with 1 thread, then several times with 2 (fresh caches): every store bitwise equal.
// The 2-thread arena is kept across the repeats, so that its worker has joined it and takes
// part even in the short parallel loops.
void checkThreadIndependence(const FibreStore& fs, const Eigen::VectorXd& q, Index minZones) {
  const ContactParams p = defaults(fs);
  tbb::task_arena single(1), dual(2);
  Detected one;
  detectIn(single, fs, q, p, one);
  REQUIRE(one.zones.size() >= minZones);
  REQUIRE(one.report.candidatePairs > 0);
  for (int repeat = 0; repeat < 4; ++repeat) {
    CAPTURE(repeat);
    Detected two;
    detectIn(dual, fs, q, p, two);
    CHECK(two.report.candidatePairs == one.report.candidatePairs);
    CHECK(fixtures::sameBits(two.cache.broadphase.candidateFirst, one.cache.broadphase.candidateFirst));
    CHECK(fixtures::sameBits(two.cache.broadphase.candidate, one.cache.broadphase.candidate));
    CHECK(fixtures::sameBits(two.zones, one.zones));
    CHECK(fixtures::sameBits(two.el, one.el));
  }
}

// A second call on the same cache with the same state: the candidate set is reused, every zone
// keeps its id and points at itself, no fresh id is drawn, and the stores are otherwise equal.
void checkRepeatable(const FibreStore& fs, const Eigen::VectorXd& q) {
  const ContactParams p = defaults(fs);
  Detected d;
  detectIn(2, fs, q, p, d);
  CHECK(d.report.broadphaseRebuilt);
  const ZoneStore first = d.zones;
  const ContactElementStore firstEl = d.el;
  const std::uint64_t nextId = d.zones.nextId;
  CHECK(std::all_of(first.previous.begin(), first.previous.end(), [](Index o) { return o == -1; }));
  bool numbered = true;  // a fresh cache numbers the zones 1, 2, ... in zone order
  for (Index z = 0; z < first.size(); ++z) numbered &= first.id[z] == std::uint64_t(z) + 1;
  CHECK(numbered);
  detectIn(2, fs, q, p, d);
  CHECK_FALSE(d.report.broadphaseRebuilt);
  CHECK(d.zones.nextId == nextId);
  CHECK(fixtures::sameBits(d.zones.id, first.id));
  bool selfPrevious = true;
  for (Index z = 0; z < d.zones.size(); ++z) selfPrevious &= d.zones.previous[z] == z;
  CHECK(selfPrevious);
  ZoneStore expected = first;
  expected.previous = d.zones.previous;
  CHECK(fixtures::sameBits(d.zones, expected));
  CHECK(fixtures::sameBits(d.el, firstEl));
}

FibreStore mat() { return assemblies::randomMat(1000, 10, 1.0, 0.01, 0.15, 21, 0.3, true); }

FibreStore fabric() { return assemblies::wovenFabric(); }

}  // namespace

TEST_CASE("contact detection gives bitwise the same stores with 1 and 2 threads: random mat") {
  const FibreStore fs = mat();
  REQUIRE(fs.elements() == 10000);
  checkThreadIndependence(fs, fixtures::deformed(fs, 3, 0.002), 1000);
}

TEST_CASE("contact detection gives bitwise the same stores with 1 and 2 threads: woven fabric") {
  const FibreStore fs = fabric();
  REQUIRE(fs.elements() == 480 * 40);
  checkThreadIndependence(fs, fs.q, 1000);
}

TEST_CASE("contact detection run twice without motion gives the same stores and zone ids") {
  checkRepeatable(mat(), mat().q);
  const FibreStore fs = fabric();
  checkRepeatable(fs, fs.q);
}

namespace {

// Old zones of the same fibre pair that overlap new zone z on both fibres within the
// identity tolerance l_zp (systems/zone_identity.h), recomputed here from the two stores.
std::vector<Index> overlapping(const FibreStore& fs, const ContactParams& p, const ZoneStore& old,
                               const ZoneStore& zones, Index z) {
  const Index I = zones.fibreI[z], J = zones.fibreJ[z];
  const double tol = fs.length[I] / fs.elementCount[I] / testIntervalsPerElement(fs, p, I, J);
  auto ov = [](double a1, double a2, double b1, double b2) {
    return std::min(std::max(a1, a2), std::max(b1, b2)) - std::max(std::min(a1, a2), std::min(b1, b2));
  };
  std::vector<Index> out;
  for (Index o = 0; o < old.size(); ++o)
    if (old.fibreI[o] == I && old.fibreJ[o] == J &&
        ov(zones.sI1[z], zones.sI2[z], old.sI1[o], old.sI2[o]) >= -tol &&
        ov(zones.sJ1[z], zones.sJ2[z], old.sJ1[o], old.sJ2[o]) >= -tol)
      out.push_back(o);
  return out;
}

}  // namespace

TEST_CASE("zones keep their ids under a motion within the skin, the grid is reused") {
  const FibreStore fs = assemblies::randomMat(300, 8, 1.0, 0.01, 0.15, 5, 0.3);
  const ContactParams p = defaults(fs);
  Detected d;
  detectIn(2, fs, fs.q, p, d);
  const ZoneStore old = d.zones;
  const std::uint64_t firstFresh = d.zones.nextId;
  // Every node moves by less than skin / 2 (each component by at most skin / 4).
  const Eigen::VectorXd q = fixtures::deformed(fs, 9, p.skin / 4, false);
  detectIn(2, fs, q, p, d);
  CHECK_FALSE(d.report.broadphaseRebuilt);

  Detected fresh;  // the same state from scratch: the reused candidate set loses nothing
  detectIn(2, fs, q, p, fresh);
  CHECK(fresh.report.broadphaseRebuilt);
  ZoneStore expected = fresh.zones;
  expected.id = d.zones.id;
  expected.previous = d.zones.previous;
  expected.nextId = d.zones.nextId;  // ids handed out so far: this store made more calls
  CHECK(fixtures::sameBits(d.zones, expected));
  CHECK(fixtures::sameBits(d.el, fresh.el));

  // A zone and an old zone that overlap only each other: same id, previous = the old zone.
  std::vector<int> claims(old.size(), 0);
  std::vector<std::vector<Index>> match(d.zones.size());
  for (Index z = 0; z < d.zones.size(); ++z) {
    match[z] = overlapping(fs, p, old, d.zones, z);
    for (Index o : match[z]) ++claims[o];
  }
  Index oneToOne = 0, kept = 0;
  for (Index z = 0; z < d.zones.size(); ++z) {
    if (match[z].empty()) {
      CHECK(d.zones.previous[z] == -1);
      CHECK(d.zones.id[z] >= firstFresh);
      continue;
    }
    CHECK(std::find(match[z].begin(), match[z].end(), d.zones.previous[z]) != match[z].end());
    if (match[z].size() != 1 || claims[match[z][0]] != 1) continue;
    ++oneToOne;
    kept += d.zones.previous[z] == match[z][0] && d.zones.id[z] == old.id[match[z][0]];
  }
  CHECK(kept == oneToOne);
  CHECK(oneToOne >= Index(0.95 * std::min(old.size(), d.zones.size())));
  CHECK(old.size() >= 200);
}

namespace {

// Fibres I (y = 0) and J (y = 2R) along x over [0, 2]: one zone along the whole length. With
// `gap`, J's nodes over x in [a, b] are lifted by 6 R, far beyond Delta_prox = 3 R: the zone
// splits in two around that stretch.
struct Parallel {
  static constexpr double R = 0.05;
  FibreStore fs;
  Parallel() {
    fixtures::add(fs, fixtures::polylineFibre("I", R, 20, 2, {Vec3(0, 0, 0), Vec3(2, 0, 0)}));
    fixtures::add(fs, fixtures::polylineFibre("J", R, 20, 2, {Vec3(0, 2 * R, 0), Vec3(2, 2 * R, 0)}));
  }
  Eigen::VectorXd lifted(double a, double b) const {
    Eigen::VectorXd q = fs.q;
    for (Index n = fs.firstNode[1]; n < fs.firstNode[1] + fs.nodeCount[1]; ++n)
      if (x0Of(q, n)[0] >= a - 1e-9 && x0Of(q, n)[0] <= b + 1e-9) x0Of(q, n)[1] += 6 * R;
    return q;
  }
};

}  // namespace

TEST_CASE("a zone that splits keeps its id on its larger part, the other part is new") {
  const Parallel s;
  const ContactParams p = defaults(s.fs);
  Detected d;
  detectIn(2, s.fs, s.fs.q, p, d);
  REQUIRE(d.zones.size() == 1);
  const std::uint64_t parent = d.zones.id[0];

  // Parts [0, ~1.15] and [~1.45, 2]: I's test points near the lifted stretch still reach J
  // beside it, so I's gap is narrower than J's lifted stretch.
  detectIn(2, s.fs, s.lifted(1.1, 1.5), p, d);
  REQUIRE(d.zones.size() == 2);
  CHECK(d.zones.sI2[0] < 1.2);
  CHECK(d.zones.sI1[1] > 1.4);
  CHECK(d.zones.previous[0] == 0);  // both parts come from the parent
  CHECK(d.zones.previous[1] == 0);
  CHECK(d.zones.id[0] == parent);   // the larger part keeps the parent's id
  CHECK(d.zones.id[1] > parent);    // the smaller one is new

  Detected mirror;  // the same split, the larger part now second
  detectIn(2, s.fs, s.fs.q, p, mirror);
  detectIn(2, s.fs, s.lifted(0.5, 0.9), p, mirror);
  REQUIRE(mirror.zones.size() == 2);
  CHECK(mirror.zones.id[1] == 1);
  CHECK(mirror.zones.id[0] == 2);
  CHECK(mirror.zones.previous[0] == 0);
}

TEST_CASE("zones that merge take the id of the part they overlap best, vanished ids never return") {
  const Parallel s;
  const ContactParams p = defaults(s.fs);
  Detected d;
  detectIn(2, s.fs, s.lifted(0.5, 0.9), p, d);  // small part [0, ~0.55], large part [~0.95, 2]
  REQUIRE(d.zones.size() == 2);
  const std::uint64_t small = d.zones.id[0], large = d.zones.id[1];

  detectIn(2, s.fs, s.fs.q, p, d);  // straightened: one zone
  REQUIRE(d.zones.size() == 1);
  CHECK(d.zones.previous[0] == 1);
  CHECK(d.zones.id[0] == large);

  Eigen::VectorXd away = s.fs.q;  // J moved away: the zone vanishes
  for (Index n = s.fs.firstNode[1]; n < s.fs.firstNode[1] + s.fs.nodeCount[1]; ++n) x0Of(away, n)[2] += 1;
  detectIn(2, s.fs, away, p, d);
  CHECK(d.zones.size() == 0);
  CHECK(d.el.size() == 0);

  detectIn(2, s.fs, s.lifted(0.5, 0.9), p, d);  // back: the same two zones, with fresh ids
  REQUIRE(d.zones.size() == 2);
  CHECK(d.zones.previous[0] == -1);
  CHECK(d.zones.previous[1] == -1);
  for (std::uint64_t id : d.zones.id) {
    CHECK(id != small);
    CHECK(id != large);
    CHECK(id > std::max(small, large));
  }
}
