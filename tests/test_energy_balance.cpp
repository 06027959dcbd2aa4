// The energy balance (systems/energy_balance.h, StepReport::energy): the strain energy gained
// equals the work of every force on the fibres, up to the trapezoidal rule's error, which is of
// second order in the increment; each term against an independent measure:
//   - a cantilever under a tip force ramped from 0: the balance error shrinks ~4x when the
//     increments double;
//   - frictionless line contact loaded and unloaded: the normal forces' net work over the cycle
//     is ~0 (penalty energy stored, then given back) and the strain energy returns to ~0;
//   - a fibre dragged along a parallel held one with friction: the friction work is
//     -integral mu q(t) L dx (Coulomb sliding over the imposed displacement), the supports'
//     work (the drag) pays for it.
#include "dragged_fibre.h"
#include "engine/world.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace fibra;

namespace {

const char* kMaterial = R"("units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],)";

SceneDef load(const std::string& text) { return loadSceneFromString(text, "energy.json"); }

EnergyBalance solve(const SceneDef& scene, double* largestNormalWork = nullptr) {
  World w(scene);
  EnergyBalance e;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    e = r.energy;
    if (largestNormalWork)
      *largestNormalWork = std::max(*largestNormalWork, std::abs(e.contactNormal));
  }
  return e;
}

std::string cantilever(int increments) {
  return std::string("{") + kMaterial + R"(
    "fibres": [{"name": "beam", "material": "m", "radius": 0.1, "elements": 8,
                "geometry": {"type": "line", "points": [[0, 0, 0], [10, 0, 0]]}}],
    "boundary_conditions": [{"type": "clamp", "group": "beam.start"}],
    "loads": [{"type": "force", "group": "beam.end", "vector": [0, -0.01, 0]}],
    "steps": [{"end_time": 1, "increments": )" +
         std::to_string(increments) + "}]}";
}

// U pressed onto a held parallel fibre D by a line load that rises and falls back to 0.
std::string pressedAndReleased() {
  return std::string("{") + kMaterial + R"(
    "fibres": [
      {"name": "U", "material": "m", "radius": 0.1, "elements": 8,
       "geometry": {"type": "line", "points": [[-2, 0, 0.2], [2, 0, 0.2]], "director": [0, 0, 1]}},
      {"name": "D", "material": "m", "radius": 0.1, "elements": 8,
       "geometry": {"type": "line", "points": [[-2, 0, 0], [2, 0, 0]], "director": [0, 0, 1]}}],
    "boundary_conditions": [
      {"type": "fix", "group": "U.start", "dofs": ["x", "y", "g1y"]},
      {"type": "fix", "group": "U.end", "dofs": ["y"]},
      {"type": "clamp", "group": "D.all"}],
    "loads": [{"type": "line_force", "group": "U.all", "vector": [0, 0, -0.2],
               "table": [[0, 0], [1, 1], [2, 0]]}],
    "contact": {"max_penetration": 5e-4},
    "stabilisation": {"stiffness": 1e-6, "fibres": ["U"]},
    "steps": [{"end_time": 2, "increments": 20}]})";
}

}  // namespace

TEST_CASE("energy balance: a cantilever's strain energy is the work of its load, to second order") {
  const EnergyBalance coarse = solve(load(cantilever(10))), fine = solve(load(cantilever(20)));
  CHECK(coarse.strain > 0);
  CHECK(coarse.external == doctest::Approx(coarse.strain).epsilon(0.01).scale(0));
  CHECK(coarse.supports == 0);  // held DOFs that do not move do no work
  CHECK(std::abs(fine.error()) < 0.35 * std::abs(coarse.error()));
  CHECK(std::abs(fine.error()) < 2e-3 * fine.strain);
}

TEST_CASE("energy balance: frictionless normal forces do no net work over a load cycle") {
  double largest = 0;
  const EnergyBalance e = solve(load(pressedAndReleased()), &largest);
  CHECK(largest > 1e-5);  // the contact stored energy on the way
  CHECK(std::abs(e.contactNormal) < 1e-3 * largest);
  CHECK(std::abs(e.external) < 1e-3 * largest);
  CHECK(std::abs(e.friction) < 1e-6 * largest);  // force - R_N N: round-off only
  CHECK(std::abs(e.error()) < 1e-3 * largest);
}

TEST_CASE("energy balance: friction dissipates mu q L per unit of slip, paid by the drag") {
  const EnergyBalance e = solve(test::draggedFibre(0.2));
  // -int_0^1 mu L q(t) 0.3 dt, q = 0.05 min(t / 0.2, 1): 0.2 x 3 x 0.05 x 0.3 x (0.1 + 0.8)
  const double coulomb = -0.2 * 3 * 0.05 * 0.3 * 0.9;
  CHECK(e.friction == doctest::Approx(coulomb).epsilon(0.01).scale(0));
  CHECK(e.friction > coulomb);  // less: B sticks until its reversible slip is used up
  CHECK(e.supports == doctest::Approx(-e.friction).epsilon(0.01).scale(0));
  CHECK(std::abs(e.error()) < 0.01 * std::abs(e.friction));
}
