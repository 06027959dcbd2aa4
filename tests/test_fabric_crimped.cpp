// The woven fabric's crimped start (io/fabric_generator.h, "start": "crimped"), measured from the
// expanded polylines alone, not from the generator's formulas: the smallest distance between the
// centrelines of fibres of different yarns and of one yarn (exact segment-to-segment distances
// over every pair of polyline segments), the heights of the yarns at every crossing against the
// pattern and the level tables, the ends and the directors of the built fibres; the `start` and
// spacing errors; "flat" the same scene as no `start` at all. samples/woven_crimped.json (7-fibre
// yarns, Table 1 fibres) solves under its end tensions with the crossings in order and no
// overlap between yarns beyond p_max, measured from the nodes (tests/weave_crossings.h).
#include "engine/world.h"
#include "io/fabric_generator.h"
#include "io/generators.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"
#include "weave_crossings.h"
#include "woven_scene.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

using namespace fibra;
using namespace fibra::test;
using Json = nlohmann::json;

namespace {

// bench/woven_thick_7_crimped.json: Table 1 fibres, 7 per yarn, 0.65 mm between yarn axes (the
// least for a crimped start of these yarns is 0.6326 mm).
constexpr double kR = 0.026, kGap = 0.002, kSpacing = 0.65;  // mm
// Polylines against their curves: the fibres of a yarn are parallel curves sampled at the same
// x, so two of them, d apart in the section (d = 2R + gap = 54 um for neighbours, dv of it along
// the normal), have chords at least sqrt(d^2 - dv^2 sin^2(dth/2)) ~ d - dv^2 dth^2/(8 d) apart,
// dth = h/rho the axis' turn over a chord of length h: h <= 8.2 um (16 chords per element,
// elements of at most 2.6/20 mm), rho >= 0.33 mm, dv <= 47 um give 0.01 um. Fibres of two
// yarns are nearest on the plateaus, where the polylines are exact (straight). 0.1 um (p_max/2
// for these fibres, R/260) bounds the discretisation with room.
constexpr double kTolerance = 1e-4;  // mm

Json crimpedScene(const Json& pattern, int yarns, int perYarn, double spacing) {
  Json s = wovenScene({{"name", "glass"}, {"young_modulus", 73000}, {"bending_factor", 0.12}}, pattern,
                      yarns, yarns,
                      {{"spacing", spacing}, {"fibres_per_yarn", perYarn}, {"fibre_radius", kR},
                       {"gap", kGap}, {"elements", 20}});
  s["generators"][0]["start"] = "crimped";
  return s;
}

SceneDef load(const Json& j) { return loadSceneFromString(j.dump(), "s.json"); }

// Distance from p to the segment [a, b], mm.
double pointSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

// Smallest distance between the segments [p1, q1] and [p2, q2]: the least of the four endpoint
// distances and, where the segments are not parallel, the interior pair whose connecting line is
// normal to both when it lies inside both (mm).
double segmentDistance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  double d = std::min({pointSegment(p1, p2, q2), pointSegment(q1, p2, q2),
                       pointSegment(p2, p1, q1), pointSegment(q2, p1, q1)});
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), b = d1.dot(d2), e = d2.squaredNorm();
  const double denom = a * e - b * b;
  if (denom <= 1e-12 * a * e) return d;
  const double s = (b * d2.dot(r) - e * d1.dot(r)) / denom;
  const double t = (a * d2.dot(r) - b * d1.dot(r)) / denom;
  if (s >= 0 && s <= 1 && t >= 0 && t <= 1) d = std::min(d, (p1 + s * d1 - p2 - t * d2).norm());
  return d;
}

// Smallest distance between two polylines over every pair of their segments, but for pairs
// whose bounding spheres are more than `beyond` mm apart (mm; above `beyond` means none nearer).
double polylineDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double beyond) {
  double best = 1e300;
  for (size_t i = 0; i + 1 < a.size(); ++i) {
    const Vec3 ma = (a[i] + a[i + 1]) / 2;
    const double ra = (a[i + 1] - a[i]).norm() / 2;
    for (size_t j = 0; j + 1 < b.size(); ++j) {
      const double rb = (b[j + 1] - b[j]).norm() / 2;
      if ((ma - (b[j] + b[j + 1]) / 2).norm() - ra - rb > beyond) continue;
      best = std::min(best, segmentDistance(a[i], a[i + 1], b[j], b[j + 1]));
    }
  }
  return best;
}

struct Separation {
  double betweenYarns = 1e300, withinYarn = 1e300;  // smallest centreline distances, mm
};

// Over every pair of fibres (yarn by yarn, perYarn fibres each, as the generator lists them).
Separation separations(const SceneDef& s, int perYarn) {
  Separation m;
  for (size_t I = 0; I < s.fibres.size(); ++I)
    for (size_t J = I + 1; J < s.fibres.size(); ++J) {
      const auto &a = s.fibres[I].geometry.points, &b = s.fibres[J].geometry.points;
      const double d = polylineDistance(a, b, 0.1);
      double& smallest = I / perYarn == J / perYarn ? m.withinYarn : m.betweenYarns;
      smallest = std::min(smallest, d);
    }
  return m;
}

// Where coordinate `axis` of the polyline reaches `at` (it increases along the polyline): the
// point there and the arc length from the start to it (mm).
std::pair<Vec3, double> pointAt(const std::vector<Vec3>& p, int axis, double at) {
  double s = 0;
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const double l = (p[i + 1] - p[i]).norm();
    if (p[i + 1](axis) >= at) {
      const double t = (at - p[i](axis)) / (p[i + 1](axis) - p[i](axis));
      return {p[i] + t * (p[i + 1] - p[i]), s + t * l};
    }
    s += l;
  }
  FAIL("the polyline does not reach " << at);
  return {};
}

double levelAt(const FibreDef& f, double s) {
  double level = 0;
  for (const LevelDef& p : f.levels)
    if (p.from <= s) level = p.level;
  return level;
}

// At every crossing (warp c, weft r), the mean height of each yarn's fibres there: the pattern's
// over yarn above, the warp fibres' levels +1 or -1 to match; returns the crossings in order.
int crossingsInOrder(const SceneDef& s, const WeavePattern& p, int yarns, int perYarn) {
  int inOrder = 0;
  const auto axis = [&](int k) { return (k - (yarns - 1) / 2.0) * kSpacing; };
  for (int c = 0; c < yarns; ++c)
    for (int r = 0; r < yarns; ++r) {
      double warpZ = 0, weftZ = 0;
      const bool warpOver = p[size_t(r) % p.size()][size_t(c) % p[0].size()] == 1;
      for (int k = 0; k < perYarn; ++k) {
        const FibreDef& warp = s.fibres[size_t(c * perYarn + k)];
        const auto [x, arc] = pointAt(warp.geometry.points, 0, axis(r));
        CHECK(levelAt(warp, arc) == (warpOver ? 1 : -1));
        warpZ += x.z() / perYarn;
        const auto& weft = s.fibres[size_t((yarns + r) * perYarn + k)].geometry.points;
        weftZ += pointAt(weft, 1, axis(c)).first.z() / perYarn;
      }
      inOrder += warpOver ? warpZ > weftZ : weftZ > warpZ;
    }
  return inOrder;
}

void checkCrimped(const Json& pattern, const WeavePattern& p, int yarns) {
  const SceneDef s = load(crimpedScene(pattern, yarns, 7, kSpacing));
  REQUIRE(s.fibres.size() == size_t(2 * yarns * 7));
  const Separation m = separations(s, 7);
  MESSAGE("crimped " << yarns << " x " << yarns << ": fibres of different yarns " << m.betweenYarns
                     << " mm apart at least (2R = " << 2 * kR << "), of one yarn " << m.withinYarn
                     << " (2R + gap = " << 2 * kR + kGap << ")");
  CHECK(m.betweenYarns >= 2 * kR - kTolerance);
  CHECK(m.withinYarn >= 2 * kR + kGap - kTolerance);
  CHECK(crossingsInOrder(s, p, yarns, 7) == yarns * yarns);
}

std::string errorAfter(const std::function<void(Json&)>& change) {
  Json j = crimpedScene("plain", 2, 7, kSpacing);
  change(j);
  return errorOf([&] { load(j); });
}

}  // namespace

TEST_CASE("woven fabric crimped: no fibres of two yarns overlap, a yarn's keep their spacing") {
  SUBCASE("plain 2 x 2") { checkCrimped("plain", plainWeave(), 2); }
  SUBCASE("twill 3 x 3") {
    checkCrimped({{"weave", "twill"}, {"over", 2}, {"under", 1}}, twillWeave(2, 1), 3);
  }
}

TEST_CASE("woven fabric crimped: the ends stay at +-L/2, flat, and G1 is normal to the fibre") {
  const SceneDef s = load(crimpedScene("plain", 2, 7, kSpacing));
  const double half = 3 * kSpacing / 2;  // default length: (2 + 1) spacings
  for (size_t f = 0; f < s.fibres.size(); ++f) {
    CAPTURE(f);
    const std::vector<Vec3>& p = s.fibres[f].geometry.points;
    REQUIRE(p.size() == size_t(16 * 20 + 1));
    const int along = f < 14 ? 0 : 1;
    CHECK(p.front()(along) == doctest::Approx(-half).epsilon(1e-14));
    CHECK(p.back()(along) == doctest::Approx(half).epsilon(1e-14));
    CHECK(p[1].z() == p[0].z());
    CHECK(p[p.size() - 2].z() == p.back().z());
  }
  // Transported from +z at the start, G1 stays in the yarn's vertical plane, normal to it.
  const World w(s);
  const FibreStore& fs = w.fibres();
  double across = 0, lowest = 1;  // G1's largest part across the yarn, its least z
  for (Index n = 0; n < fs.nodes(); ++n) {
    const Vec3 g1 = g1Of(fs.qRef, n);
    across = std::max(across, std::abs(g1(fs.nodeFibre[n] < 14 ? 1 : 0)));
    lowest = std::min(lowest, g1.z());
  }
  CHECK(across < 1e-12);
  CHECK(lowest > 0.85);  // the ramps' slope is at most pi H / g = 0.47 (25 degrees)
}

TEST_CASE("woven fabric crimped: errors name the start key and the spacing") {
  CHECK(errorAfter([](Json&) {}) == "(no error)");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["start"] = "wavy"; }) ==
        "s.json: generators[0].start: unknown value \"wavy\" (expected one of: flat, crimped)");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["weft"]["spacing"] = 0.3; }) ==
        "s.json: generators[0].weft.spacing: a crimped start needs spacing > 0.632584 mm (the warp "
        "yarns' ramps between weft yarns 0.16 mm wide, crimp height 0.0737654 mm: radius of "
        "curvature (spacing - width)^2/(pi^2 H) above the warp fibres' offset 0.0467654 mm plus 10 "
        "fibre radii, 0.26 mm), got 0.3");
  CHECK(errorAfter([](Json& j) { j["generators"][0]["warp"]["spacing"] = 0.15; }) ==
        "s.json: generators[0].warp.spacing: a crimped start needs the spacing to exceed the yarn "
        "width 0.16 mm (side by side, with room for the weft yarns' ramps), got 0.15");
  // 19 fibres a yarn at 0.65 mm: too close for their crimp (0.9165 mm needed).
  CHECK(errorAfter([](Json& j) {
          for (const char* dir : {"warp", "weft"}) j["generators"][0][dir]["fibres_per_yarn"] = 19;
        }).find("generators[0].weft.spacing: a crimped start needs spacing > 0.916504 mm") !=
        std::string::npos);
  // One weft yarn: no warp ramps, so only the weft spacing's width bound applies (none here).
  CHECK(errorAfter([](Json& j) {
          j["generators"][0]["weft"]["yarns"] = 1;
          j["generators"][0]["weft"]["spacing"] = 0.1;
        }) == "(no error)");
}

TEST_CASE("woven fabric: start flat expands to the same scene as no start") {
  Json flat = crimpedScene("twill", 4, 3, 1.0), none = flat;
  flat["generators"][0]["start"] = "flat";
  none["generators"][0].erase("start");
  CHECK(expandGenerators(flat) == expandGenerators(none));
  CHECK(expandGenerators(none)["fibres"][0]["geometry"]["type"] == "line");
}

TEST_CASE("woven fabric crimped: the 7-fibre sample solves under its end tensions, crossings kept") {
  const SceneDef s = loadScene(sourcePath("samples/woven_crimped.json"));
  World w(s);
  int increments = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    ++increments;
  }
  CHECK(increments == 5);  // no cutback
  const Crossings m = measureCrossings(w, plainWeave(), {.yarns = 2, .spacing = kSpacing, .fibres = 7});
  MESSAGE("under the end tensions: largest overlap between yarns " << m.worstOverlap << " mm (p_max "
          << s.contact.maxPenetration << "), " << m.inOrder << " of " << m.total << " crossings in order");
  CHECK(m.total == 4);
  CHECK(m.inOrder == m.total);
  CHECK(m.worstOverlap <= s.contact.maxPenetration);
}
