// Contact elements at the minima of the centreline distance (systems/contact_elements.h):
// - self-contact has the section rules of contact between two fibres: a fibre that crosses over
//   itself is sampled at the closest points of its two strands, and a fibre's end pressed against
//   its own side touches it with its flat end face. Each scene is one fibre through a dense
//   polyline, clamped whole (one increment: the contact elements of the reference state), and
//   the same polyline cut into two fibres away from the contact, whose two-fibre rules are tested
//   elsewhere (tests/test_contact_reference.cpp, tests/test_fibre_ends.cpp);
// - a strand bent round another fibre that comes closest to it twice within one zone (the
//   plectoneme's loop) has an element at each of the two minima.
// The penetrations the elements report must be the true overlaps, known in closed form or
// measured from the centrelines (tests/centreline_measure.h).
#include "centreline_measure.h"
#include "contact_fixtures.h"

#include "components/contact_state.h"
#include "engine/world.h"
#include "io/scene_loader.h"
#include "systems/contact_params.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace fibra;

namespace {

constexpr double kR = 0.1, kPMax = 1e-4;  // radius, p_max, mm

std::string polyline(const std::vector<Vec3>& points, std::size_t from, std::size_t to) {
  std::ostringstream out;
  out.precision(17);
  for (std::size_t k = from; k <= to; ++k)
    out << (k > from ? ", " : "") << "[" << points[k].x() << ", " << points[k].y() << ", "
        << points[k].z() << "]";
  return out.str();
}

std::string fibre(const std::string& name, const std::vector<Vec3>& points, std::size_t from,
                  std::size_t to, int elements) {
  return R"({"name": ")" + name + R"(", "material": "m", "radius": 0.1, "elements": )" +
         std::to_string(elements) + R"(, "geometry": {"type": "polyline", "points": [)" +
         polyline(points, from, to) + R"(], "director": [0, 0, 1]}})";
}

SceneDef heldScene(const std::string& fibres, const std::string& clamps, const char* placement);

// The polyline as one fibre of `elements` quadratic elements with self-contact, or (cut > 0) as
// two fibres, vertices [0, cut] and [cut + kCutGap, end] (their ends apart, so that they do not
// touch end to end: 0.5 mm and more), their element counts in proportion; everything clamped.
constexpr std::size_t kCutGap = 100;
SceneDef heldScene(const std::vector<Vec3>& points, int elements, std::size_t cut,
                   const char* placement) {
  std::string fibres, clamps;
  if (cut == 0) {
    fibres = fibre("f", points, 0, points.size() - 1, elements);
    clamps = R"({"type": "clamp", "group": "f.all"})";
  } else {
    double lengthA = 0, length = 0;
    for (std::size_t k = 1; k < points.size(); ++k) {
      const double l = (points[k] - points[k - 1]).norm();
      length += l;
      if (k <= cut) lengthA += l;
    }
    const int a = std::max(1, int(std::lround(elements * lengthA / length)));
    fibres = fibre("a", points, 0, cut, a) + ", " +
             fibre("b", points, cut + kCutGap, points.size() - 1, elements - a);
    clamps = R"({"type": "clamp", "group": "a.all"}, {"type": "clamp", "group": "b.all"})";
  }
  return heldScene(fibres, clamps, placement);
}

SceneDef heldScene(const std::string& fibres, const std::string& clamps, const char* placement) {
  const std::string text = R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [)" + fibres + R"(],
    "boundary_conditions": [)" + clamps + R"(],
    "contact": {"self_contact": true, "max_penetration": 1e-4, "element_placement": ")" +
                           placement + R"("},
    "steps": [{"end_time": 1, "increments": 1}]})";
  return loadSceneFromString(text, "held.json");
}

struct Held {
  double deepest = 0;  // the deepest penetration -g_N the elements report, mm
  int endFaces = 0;    // elements on an end face
  FibreStore fibres;
  Eigen::VectorXd q;
};

Held solveHeld(const SceneDef& s) {
  World w(s);
  REQUIRE(w.step().status == StepStatus::Converged);
  Held out;
  const ContactElementStore& el = w.contact().elements;
  for (Index e = 0; e < el.size(); ++e) {
    out.deepest = std::max(out.deepest, -el.gap[e]);
    out.endFaces += (el.fallback[e] & (kEndFaceI | kEndFaceJ)) != 0;
  }
  out.fibres = w.fibres();
  out.q = w.fibres().q;
  return out;
}

// A loop that crosses over itself: x = S (u^2 - 1), y = S k (u^3 - u), the strands at u = -1
// and u = +1 meeting over the origin at 2 atan(k); z = c u + b u^2 tilts them so that the
// closest points lie off the loop's symmetry, where a zone's eq. 8 sections do not look.
std::vector<Vec3> crossingLoop(double S, double k, double c, double b, double u0, double u1,
                               int vertices) {
  std::vector<Vec3> p;
  for (int i = 0; i <= vertices; ++i) {
    const double u = u0 + (u1 - u0) * i / vertices;
    p.emplace_back(S * (u * u - 1), S * k * (u * u * u - u), c * u + b * u * u);
  }
  return p;
}

}  // namespace

TEST_CASE("self-contact: a fibre crossing over itself reports the overlap at its closest points") {
  // S = 2 mm, crossing angles 90 and 40 degrees, strands 2R - delta apart at u = -+1 before the
  // tilt b; the true overlap from the centrelines (closest approach by sampling).
  for (const double k : {1.0, 0.364}) {
    for (const double shift : {0.0, 0.07, 0.13}) {
      CAPTURE(k);
      CAPTURE(shift);
      const double u0 = -1.5 - shift, u1 = 1.6;
      const int vertices = 1200;
      const auto points = crossingLoop(2, k, 0.5 * (2 * kR - 3e-4), 0.02, u0, u1, vertices);
      const Held self = solveHeld(heldScene(points, 40, 0, "weighted"));
      const Held two = solveHeld(heldScene(points, 40, vertices / 2, "weighted"));
      // The centrelines' closest approach near u = -1 and u = +1 (their arc lengths along the
      // polyline, which the fibre's reference length follows).
      std::vector<double> s{0};
      for (std::size_t i = 1; i < points.size(); ++i) s.push_back(s.back() + (points[i] - points[i - 1]).norm());
      auto at = [&](double u) { return s[std::size_t(std::lround((u - u0) / (u1 - u0) * vertices))]; };
      const test::Closest cl = test::closestApproach(self.fibres, self.q, 0, 0, at(-1), at(1));
      REQUIRE(cl.sJ - cl.sI > 1.0);
      const double overlap = test::overlapAt(self.fibres, self.q, 0, 0, cl);
      // The cut fibres, meshed otherwise, interpolate the polyline a little differently.
      const double cutAt = s[vertices / 2 + kCutGap];
      const test::Closest c2 = test::closestApproach(two.fibres, two.q, 0, 1, at(-1), at(1) - cutAt);
      const double overlapTwo = test::overlapAt(two.fibres, two.q, 0, 1, c2);
      MESSAGE("k " << k << " shift " << shift << ": true overlap " << overlap << ", self "
                   << self.deepest << "; two fibres: true " << overlapTwo << ", reported " << two.deepest);
      REQUIRE(overlap > 2 * kPMax);
      CHECK(std::abs(self.deepest - overlap) <= 1e-3 * overlap);
      CHECK(std::abs(two.deepest - overlapTwo) <= 1e-3 * overlapTwo);
    }
  }
}

TEST_CASE("self-contact: a fibre's end pressed against its own side touches it with its end face") {
  // A hook: a shank along x (y = 0), a half turn of radius 0.8 mm, a run back, a quarter turn
  // down, and a straight end along -y whose flat end face stands at y = R - delta over the
  // shank's top (y = R): the overlap is delta, in closed form. Without the end face the end
  // section's outline would report the sections' distance against 2R: R + delta.
  constexpr double delta = 3e-4, rho = 0.8;
  std::vector<Vec3> p;
  auto line = [&](Vec3 a, Vec3 b, int n) {
    for (int i = p.empty() ? 0 : 1; i <= n; ++i) p.push_back(a + (b - a) * double(i) / n);
  };
  auto arc = [&](Vec3 centre, double from, double to, int n) {
    for (int i = 1; i <= n; ++i) {
      const double a = from + (to - from) * i / n;
      p.push_back(centre + rho * Vec3(std::cos(a), std::sin(a), 0));
    }
  };
  const double pi = std::numbers::pi;
  line(Vec3(-1, 0, 0), Vec3(2.5, 0, 0), 140);
  arc(Vec3(2.5, rho, 0), -pi / 2, pi / 2, 200);
  line(p.back(), Vec3(1.2, 2 * rho, 0), 52);
  arc(Vec3(1.2, rho, 0), pi / 2, pi, 100);
  line(p.back(), Vec3(1.2 - rho, kR - delta, 0), 60);
  for (const char* placement : {"weighted", "lobatto"}) {
    const std::string name = placement;
    CAPTURE(name);
    const Held self = solveHeld(heldScene(p, 48, 0, placement));
    const Held two = solveHeld(heldScene(p, 48, 140, placement));
    MESSAGE(std::string(placement) << ": true overlap " << delta << ", self " << self.deepest << " ("
                      << self.endFaces << " on the end face), two fibres " << two.deepest);
    CHECK(self.endFaces >= 1);
    CHECK(std::abs(self.deepest - delta) <= 1e-3 * delta);
    CHECK(std::abs(two.deepest - delta) <= 1e-3 * delta);
  }
}

TEST_CASE("a strand bent round a fibre that comes closest to it twice has an element at each") {
  // I straight along x. J crosses it (at 45 degrees, in the plane x = y) and bends round it
  // more tightly than its distance (curvature x distance > 1, the plectoneme's loop): its middle
  // quadratic element has the nodes (-w, -w, z0 + k), (0, 0, z0), (w, w, z0 + k), so
  //   min over I of |x_I - x_J(xi)|^2 = w^2 xi^2 + (z0 + k xi^2)^2 (at x_I = x_J),
  // a maximum z0 at xi = 0 and minima at xi = -+1/2 where, with k^2 = 16 (z0^2 - rho^2) and
  // w^2 = -k^2 / 2 - 2 k z0, the distance is rho = 2R - delta: two overlaps of delta, 0.11 mm
  // apart along J, a ridge 0.003 mm higher between them (tests/contact_fixtures.h, bentRound).
  // With I in 8 elements the zone is long and each minimum is a narrow crossing; with I in 2
  // and J's elements longer (its reference length 4 mm), a point zone (one eq. 6 element) that
  // takes an element at each. One element at one minimum
  // let the fibres through at the other (the plectoneme's loop at t = 0.735, docs/CONTACT.md 1.4).
  constexpr double delta = 3e-4, rho = 2 * kR - delta, z0 = rho + 3e-3;
  for (const int elementsI : {8, 2}) {
    CAPTURE(elementsI);
    const fixtures::BentRound b = fixtures::bentRound(kR, elementsI, elementsI == 8 ? 2 : 4, rho, z0);
    const FibreStore& fs = b.fs;
    const Eigen::VectorXd& q = b.q;
    const double w = b.w;
    fixtures::Detected d;
    const ContactParams p = fixtures::defaults(fs);
    fixtures::detect(fs, q, p, d);
    REQUIRE(d.zones.size() == 1);
    // J's middle element spans s in [h, 2h]; the minima at its xi = -+1/2.
    const double h = fs.length[1] / 3, s1 = 1.25 * h, s2 = 1.75 * h;
    // (The fixture's directors are those of the straight start, not normal to J's bent
    // centreline: the sections and their centres are checked, not the gaps.)
    int atFirst = 0, atSecond = 0;
    double closest = 1e300;
    for (Index e = 0; e < d.el.size(); ++e) {
      const double dc = (test::centreline(fs, q, 0, d.el.sI[e]) - test::centreline(fs, q, 1, d.el.sJ[e])).norm();
      if (elementsI == 2) MESSAGE("element " << e << ": sI " << d.el.sI[e] << ", sJ " << d.el.sJ[e] << ", centres " << dc << " mm apart");
      closest = std::min(closest, dc);
      atFirst += std::abs(d.el.sJ[e] - s1) < 1e-6 && std::abs(d.el.sI[e] - (1 - w / 2)) < 1e-6;
      atSecond += std::abs(d.el.sJ[e] - s2) < 1e-6 && std::abs(d.el.sI[e] - (1 + w / 2)) < 1e-6;
    }
    CHECK((elementsI == 8 ? d.el.size() > 2 : d.el.size() == 2));
    CHECK(atFirst == 1);
    CHECK(atSecond == 1);
    CHECK(std::abs(closest - rho) <= 1e-9);
    // Independently: the minima of the centre distance along J (I's nearest point at
    // x_I = x_J), by dense sampling: two, at s1 and s2, rho from I's axis, the ridge z0 between.
    std::vector<std::pair<double, double>> minima;
    const int n = 20000;
    auto distance = [&](double sJ) {
      const Vec3 x = test::centreline(fs, q, 1, sJ);
      return std::hypot(x.y(), x.z());
    };
    for (int i = 1; i < n; ++i) {
      const double a = fs.length[1] * (i - 1) / n, m = fs.length[1] * i / n, c = fs.length[1] * (i + 1) / n;
      if (distance(m) < distance(a) && distance(m) <= distance(c)) minima.push_back({m, distance(m)});
    }
    REQUIRE(minima.size() == 2);
    CHECK(std::abs(minima[0].first - s1) < 2e-4);
    CHECK(std::abs(minima[1].first - s2) < 2e-4);
    CHECK(std::abs(minima[0].second - rho) < 1e-9);
    CHECK(std::abs(distance(1.5 * h) - z0) < 1e-12);
  }
}

TEST_CASE("a point zone with one touching minimum of two has its element there") {
  // bentRound tilted by 0.004 mm: one minimum 4 p_max deep, the other outside the touching band
  // (R_I + R_J + 2 p_max), the ridge between them. The zone's one element must sit at the deep
  // one: from zeta = 1/2 alone its Newton ended on the ridge (found by a review, 2026-12-06).
  constexpr double rho = 2 * kR - 3e-4, z0 = rho + 3e-3;
  const fixtures::BentRound b = fixtures::bentRound(kR, 2, 4, rho, z0, 0.004);
  const FibreStore& fs = b.fs;
  fixtures::Detected d;
  const ContactParams p = fixtures::defaults(fs);
  fixtures::detect(fs, b.q, p, d);
  REQUIRE(d.zones.size() == 1);
  // Independently: the minima of the distance from I's axis along J, by dense sampling.
  std::vector<std::pair<double, double>> minima;
  const int n = 40000;
  auto distance = [&](double sJ) {
    const Vec3 x = test::centreline(fs, b.q, 1, sJ);
    return std::hypot(x.y(), x.z());
  };
  for (int i = 1; i < n; ++i) {
    const double a = fs.length[1] * (i - 1) / n, m = fs.length[1] * i / n, c = fs.length[1] * (i + 1) / n;
    if (distance(m) < distance(a) && distance(m) <= distance(c)) minima.push_back({m, distance(m)});
  }
  REQUIRE(minima.size() == 2);
  const auto deep = std::min_element(minima.begin(), minima.end(),
                                     [](const auto& x, const auto& y) { return x.second < y.second; });
  const double band = 2 * kR + 2 * pairPMax(p, 0, 1);
  MESSAGE("minima " << minima[0].second << " and " << minima[1].second << " mm, band " << band);
  REQUIRE(deep->second < 2 * kR - 2 * pairPMax(p, 0, 1));
  REQUIRE(std::max(minima[0].second, minima[1].second) > band);
  REQUIRE(d.el.size() == 1);
  const double dc = (test::centreline(fs, b.q, 0, d.el.sI[0]) - test::centreline(fs, b.q, 1, d.el.sJ[0])).norm();
  MESSAGE("element: sJ " << d.el.sJ[0] << ", centres " << dc << " mm apart");
  CHECK(std::abs(d.el.sJ[0] - deep->first) < 1e-4);
  CHECK(std::abs(dc - deep->second) < 1e-9);
}
