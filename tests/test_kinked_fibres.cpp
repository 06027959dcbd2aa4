// A fibre with a kink (a polyline's vertex at a node: the centreline only C0 there) resting by
// its vertex on a straight fibre. Fibre A lies along x at z = 0; fibre B is a V in the same
// plane y = 0, its arms rising with slope 0.2 from the vertex at (0, 0, zk); both R = 0.1 mm,
// both clamped at their ends, p_max 1e-3 mm. The arms make 11.3 deg with A, between
// theta_parallel and theta_cross, so eq. 10 blends in the crossing normal t_A x t_B, which is
// normal to the plane; its tangent lines meet A's axis in the plane far from the vertex, past
// the kink. The kink ends the tangent line's room as an end does (systems/contact_normals.h,
// kinkRoom), a vertex that points at the other fibre gets an element of its own
// (systems/contact_elements.cpp, kinkMinima), and the acceptance measures the overlap at the
// kink itself (contact_queries.cpp).
// Before: with the vertex 0.01 mm clear, N turned 33 deg out of the plane and 0.15 p_max of
// penetration pushed the fibres apart with 9 mN per element.
#include "engine/world.h"
#include "engine/world_state.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace fibra;

namespace {

// B's vertex at height zk; A straight, or (invertedA) an upside-down V with its vertex at 0;
// `extra`: more top-level keys (with a leading comma), over `increments` increments.
SceneDef kinkScene(double zk, bool invertedA = false, const std::string& extra = "",
                   int increments = 1) {
  const std::string z = std::to_string(zk), arm = std::to_string(zk + 0.4);
  const std::string a = invertedA ? R"({"type": "polyline", "points": [[-2, 0, -0.4], [0, 0, 0],
                                        [2, 0, -0.4]], "director": [0, 0, 1]})"
                                  : R"({"type": "line", "points": [[-2, 0, 0], [2, 0, 0]],
                                        "director": [0, 0, 1]})";
  return loadSceneFromString(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [
      {"name": "A", "material": "m", "radius": 0.1, "elements": 10, "geometry": )" + a + R"(},
      {"name": "B", "material": "m", "radius": 0.1, "elements": 10,
       "geometry": {"type": "polyline", "points": [[-2, 0, )" + arm + R"(], [0, 0, )" + z +
                                 R"(], [2, 0, )" + arm + R"(]], "director": [0, 0, 1]}}],
    "boundary_conditions": [{"type": "clamp", "group": "A.start"},
                            {"type": "clamp", "group": "A.end"},
                            {"type": "clamp", "group": "B.start"},
                            {"type": "clamp", "group": "B.end"}],
    "contact": {"max_penetration": 1e-3})" + extra + R"(,
    "steps": [{"end_time": 1, "increments": )" + std::to_string(increments) + R"(}]})",
                             "kink.json");
}

// The largest |N . e_y| over the contact elements: their normals' tilt out of the fibres' plane.
double outOfPlane(const World& w) {
  double most = 0;
  for (const Vec3& n : w.contact().elements.normal) most = std::max(most, std::abs(n.y()));
  return most;
}

// The overlap of the sections at nodes a and b (R = 0.1 mm) along their line of centres n: each
// section, the ellipse R (cos t g1 + sin t g2) about x0, reaches R sqrt((g1.n)^2 + (g2.n)^2)
// along n (its support function), mm.
double nodeOverlap(const Eigen::VectorXd& q, Index a, Index b) {
  const Vec3 d = x0Of(q, b) - x0Of(q, a), n = d.normalized();
  const auto reach = [&](Index v) {
    return 0.1 * std::hypot(g1Of(q, v).dot(n), g2Of(q, v).dot(n));
  };
  return reach(a) + reach(b) - d.norm();
}

}  // namespace

TEST_CASE("a V-shaped fibre on a straight one: no force while its vertex is clear, an element at its vertex when it presses") {
  const double pMax = 1e-3;
  {  // the vertex 0.01 mm (10 p_max) above A: nothing touches
    World w(kinkScene(0.21));
    const Eigen::VectorXd q0 = w.fibres().q;
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    REQUIRE(w.contact().elements.size() > 0);  // the zone is there (within reach)
    CHECK(r.contact.active == 0);
    CHECK(r.contact.maxPenetration == 0);
    CHECK(outOfPlane(w) <= 1e-9);
    CHECK((w.fibres().q - q0).lpNorm<Eigen::Infinity>() == 0);
  }
  {  // the vertex 0.01 mm deep in A: an element at the vertex pushes it out
    World w(kinkScene(0.19));
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    CHECK(r.contact.active > 0);
    // an element at the vertex (a narrow minimum the Newton search on smooth pieces misses)
    const ContactElementStore& el = w.contact().elements;
    const double halfB = 0.5 * w.fibres().length[1], hB = halfB / 5;
    bool atVertex = false;
    for (Index e = 0; e < el.size(); ++e) {
      const double sB = el.fibreI[e] == 1 ? el.sI[e] : el.sJ[e];
      atVertex = atVertex || std::abs(sB - halfB) <= 1e-3 * hB;
    }
    CHECK(atVertex);
    CHECK(outOfPlane(w) <= 1e-9);
    // independently: the sections' outlines x0 + R (cos a g1 + sin a g2), sampled every 0.01
    // deg, at the vertex (B's node 10) and at A's middle node, both near x = 0 by symmetry (to
    // the elements' placement); the overlap is how far A's highest point stands above B's lowest
    const Eigen::VectorXd& q = w.fibres().q;
    const Index vertex = w.fibres().firstNode[1] + 10, middle = w.fibres().firstNode[0] + 10;
    REQUIRE(std::abs(x0Of(q, vertex).x()) <= 1e-4);
    REQUIRE(std::abs(x0Of(q, middle).x()) <= 1e-4);
    const auto extremeZ = [&](Index n, double sign) {
      double most = -HUGE_VAL;
      for (int k = 0; k < 36000; ++k) {
        const double a = 2 * std::numbers::pi * k / 36000;
        const Vec3 x = x0Of(q, n) + 0.1 * (std::cos(a) * g1Of(q, n) + std::sin(a) * g2Of(q, n));
        most = std::max(most, sign * x.z());
      }
      return sign * most;
    };
    const double overlap = extremeZ(middle, 1) - extremeZ(vertex, -1);
    CAPTURE(overlap);
    CHECK(overlap > 0);       // still pressed: the clamped arms hold it down
    CHECK(overlap <= pMax);   // within p_max (10 p_max at the start)
    CHECK(r.contact.maxOverlap == doctest::Approx(overlap).epsilon(1e-3).scale(0));
    CHECK(r.contact.maxPenetration == doctest::Approx(overlap).epsilon(0.01).scale(0));
  }
  {  // the vertex 0.001 mm clear, pushed onto A by 1 N: before the vertex had an element of its
     // own, every attempt of the third increment failed as an inconsistent set (1.5 p_max at the
     // vertex where the Gauss elements reported 0.49)
    World w(kinkScene(0.201, false,
                      R"(, "groups": [{"name": "vertex", "fibre": "B", "nodes": [10]}],
                         "loads": [{"type": "force", "group": "vertex", "vector": [0, 0, -1]}])",
                      5));
    StepReport last;
    while (!w.finished()) {
      last = w.step();
      REQUIRE_MESSAGE(last.status == StepStatus::Converged, last.message);
    }
    const Eigen::VectorXd& q = w.fibres().q;
    const Index vB = w.fibres().firstNode[1] + 10, mA = w.fibres().firstNode[0] + 10;
    REQUIRE(std::abs(x0Of(q, vB).x()) <= 1e-4);
    REQUIRE(std::abs(x0Of(q, mA).x()) <= 1e-4);
    const double overlap = nodeOverlap(q, mA, vB);
    CAPTURE(overlap);
    CHECK(overlap > 0);
    CHECK(overlap <= pMax);
    CHECK(last.contact.maxOverlap == doctest::Approx(overlap).epsilon(0.01).scale(0));
    CHECK(last.contact.maxPenetration == doctest::Approx(overlap).epsilon(0.01).scale(0));
  }
  {  // vertex on vertex, 0.007 mm (7 p_max) deep: the acceptance seeks the closest point to a
     // kink element by element, so the other fibre's vertex is found (before: accepted as it
     // was, no force, overlap 0 reported)
    World w(kinkScene(0.193, true));
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    CHECK(r.contact.active > 0);
    const Eigen::VectorXd& q = w.fibres().q;
    const Index vB = w.fibres().firstNode[1] + 10, vA = w.fibres().firstNode[0] + 10;
    const double overlap = nodeOverlap(q, vA, vB);  // the vertices' sections
    CAPTURE(overlap);
    CHECK(overlap > 0);
    CHECK(overlap <= pMax);
    CHECK(r.contact.maxOverlap == doctest::Approx(overlap).epsilon(0.01).scale(0));
    CHECK(r.contact.maxPenetration == doctest::Approx(overlap).epsilon(0.01).scale(0));
  }
}
