// Inexact Newton: Eisenstat-Walker's forcing term (systems/newton.h) and the GMRES strategies
// stopping at it (KrylovSettings::forcingMax, systems/linear_solver.h).
#include "bench/tangent_cases.h"
#include "engine/world_state.h"
#include "systems/newton.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

using namespace fibra;

using bench::relativeResidual;

namespace {

// The frictional 7-fibre squeeze after its first increment: a real contact tangent.
std::unique_ptr<WorldState> squeezedBundle() {
  auto w = std::make_unique<WorldState>();
  w->scene = scenes::bundle(1, 10, 0.01, 5e-4, 0.1);
  w->def.threads = 1;
  buildWorld(*w);
  REQUIRE(advance(*w).status == StepStatus::Converged);
  return w;
}

// One Schwarz solve of w's tangent with settings k and the forcing term `forcing`, b a fixed
// ramp; returns |K x - b| / |b| and the solver's counts in `stats`.
double schwarzSolve(const WorldState& w, const KrylovSettings& k, double forcing,
                    LinearSolveStats& stats) {
  const LinearSystem& ls = w.system;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(ls.freeCount, -1, 1);
  LinearSolver solver;
  solver.setStrategy(LinearStrategy::Schwarz);
  solver.setFibres(&w.fibres);
  solver.setKrylov(k);
  std::string message;
  REQUIRE(solver.factorise(ls, message));
  Eigen::VectorXd x;
  solver.solve(b, x, forcing);
  stats = solver.stats();
  return relativeResidual(ls, x, b);
}

}  // namespace

TEST_CASE("the forcing term follows Eisenstat and Walker's choice 2 with its safeguards") {
  const double tol = 1e-8;
  // A pass's first solve: 1 (the solver clamps it to forcingMax).
  CHECK(forcingTerm(1e-3, 0, 1, tol) == 1);
  // 0.9 (rho_k / rho_{k-1})^2 = 0.9 (1e-2)^2; the last term 0.1 gives 0.9 * 0.01 < 0.1: no safeguard.
  CHECK(forcingTerm(1e-3, 1e-1, 0.1, tol) == doctest::Approx(9e-5).epsilon(1e-12));
  // The last term 0.5 gives 0.9 * 0.25 = 0.225 > 0.1: the safeguard keeps it.
  CHECK(forcingTerm(1e-3, 1e-1, 0.5, tol) == doctest::Approx(0.225).epsilon(1e-12));
  // Near convergence no solve need be finer than 0.5 tol / rho.
  CHECK(forcingTerm(1e-7, 1e-3, 1e-3, tol) == doctest::Approx(0.05).epsilon(1e-12));
  // A residual that grew: capped at 1.
  CHECK(forcingTerm(10, 1, 0.01, tol) == 1);
  // The residual test passed, the increment test not: exact directions (0: the solver's tolerance).
  CHECK(forcingTerm(5e-9, 1e-6, 1e-2, tol) == 0);
}

TEST_CASE("with forcing_max the Schwarz strategy stops at the forcing term, within its bounds") {
  const auto w = squeezedBundle();
  const auto solve = [&](double forcingMax, double forcing, int& iterations) {
    LinearSolveStats stats;
    const double r = schwarzSolve(*w, {.forcingMax = forcingMax}, forcing, stats);
    iterations = stats.krylovIterations;
    CHECK(stats.fallbacks == 0);
    return r;
  };
  int exact = 0, loose = 0, capped = 0, off = 0, floor = 0;
  const double tol = KrylovSettings{}.tolerance;
  CHECK(solve(0, 0, exact) <= tol);
  // forcing 0.1 under forcing_max 1e-2: solved to 1e-2, in fewer iterations, and not to 1e-8.
  const double r = solve(1e-2, 0.1, capped);
  CHECK(r <= 1e-2);
  CHECK(r > tol);
  CHECK(capped < exact);
  // forcing 1e-3 within the bounds: that tolerance.
  CHECK(solve(1e-2, 1e-3, loose) <= 1e-3);
  CHECK(loose >= capped);
  // forcing_max 0 (off): the forcing term is ignored.
  CHECK(solve(0, 0.1, off) <= tol);
  CHECK(off == exact);
  // A forcing term below the tolerance: the tolerance.
  CHECK(solve(1e-2, 1e-14, floor) <= tol);
  CHECK(floor == exact);
}

TEST_CASE("a Schwarz solve that misses its forcing term by less than 10x keeps its iterate") {
  CHECK(keepsInexactMiss(1e-2, 1e-8, 0.05));
  CHECK_FALSE(keepsInexactMiss(1e-2, 1e-8, 0.2));      // beyond 10x the forcing term
  CHECK_FALSE(keepsInexactMiss(0.05, 1e-8, 0.2));      // beyond kInexactMissBound
  CHECK_FALSE(keepsInexactMiss(1e-8, 1e-8, 5e-8));     // an exact solve: falls back
  // On a real tangent, GMRES cut short at 1, 2, ... iterations with the forcing term 1e-2:
  // every miss either keeps an iterate within 0.1 (no fallback) or falls back to MUMPS's exact
  // solve; both happen.
  const auto w = squeezedBundle();
  int kept = 0, fellBack = 0;
  for (int limit = 1; limit <= 30; ++limit) {
    LinearSolveStats stats;
    const double r = schwarzSolve(*w, {.maxIterations = limit, .forcingMax = 1e-2}, 1e-2, stats);
    CAPTURE(limit);
    if (stats.krylovFailures == 0) {
      CHECK(r <= 1e-2);
      continue;
    }
    if (stats.fallbacks == 0) {
      ++kept;
      CHECK(r > 1e-2);
      CHECK(r <= 0.1);
    } else {
      ++fellBack;
      CHECK(r <= 1e-10);
    }
  }
  CHECK(kept > 0);
  CHECK(fellBack > 0);
}

TEST_CASE("inexact Newton reaches the exact solves' states on a frictional bundle") {
  // The 7-fibre squeeze, 4 of its 10 increments, with Schwarz to 1e-8 every solve and with the
  // forcing term up to 0.1: every increment converges to the same force tolerance, so the
  // states agree to what that tolerance lets through.
  std::vector<Eigen::VectorXd> q;
  std::vector<double> force;
  std::vector<int> krylov;
  for (double forcingMax : {0.0, 0.1}) {
    SceneDef scene = scenes::bundle(1, 10, 0.01, 5e-4, 0.1);
    scene.solver.strategy = LinearStrategy::Schwarz;
    scene.solver.krylov.forcingMax = forcingMax;
    World w(scene, {.threads = 1});
    int iterations = 0;
    for (int k = 0; k < 4; ++k) {
      const StepReport rep = w.step();
      REQUIRE(rep.status == StepStatus::Converged);
      iterations += rep.linear.krylovIterations;
    }
    q.push_back(w.fibres().q);
    force.push_back(w.toolReaction(1).z());
    krylov.push_back(iterations);
  }
  MESSAGE("GMRES iterations, exact " << krylov[0] << ", inexact " << krylov[1]);
  CHECK(krylov[1] < krylov[0]);
  CHECK(std::abs(force[1] - force[0]) <= 1e-6 * std::abs(force[0]));
  CHECK((q[1] - q[0]).lpNorm<Eigen::Infinity>() <= 1e-8);
}

TEST_CASE("progress after each Newton iteration: step length, the GMRES solve and the contact counts") {
  // The 7-fibre squeeze's first increment with Schwarz and the forcing term up to 0.1, and with
  // the direct strategy. Every iteration is reported; the last one's contact counts are those of
  // the accepted state, which the report computes apart.
  for (const LinearStrategy strategy : {LinearStrategy::Schwarz, LinearStrategy::Direct}) {
    const bool krylov = strategy == LinearStrategy::Schwarz;
    CAPTURE(krylov);
    SceneDef scene = scenes::bundle(1, 10, 0.01, 5e-4, 0.1);
    scene.solver.strategy = strategy;
    if (krylov) scene.solver.krylov.forcingMax = 0.1;
    std::vector<Progress> seen;
    WorldDef def;
    def.threads = 1;
    def.progress = [&](const Progress& p) { seen.push_back(p); };
    World w(scene, def);
    const StepReport rep = w.step();
    REQUIRE(rep.status == StepStatus::Converged);
    REQUIRE(int(seen.size()) == rep.totalIterations);
    int gmres = 0;
    for (const Progress& p : seen) {
      CHECK(p.stepLength > 0);
      CHECK(p.stepLength <= 1);
      gmres += p.krylovIterations;
      if (krylov) {
        CHECK(p.krylovIterations > 0);
        CHECK(p.tolerance >= 1e-8);
        CHECK(p.tolerance <= 0.1);
        // met, or kept within 10x and 0.1 (systems/linear_solver.h), or redone exactly
        CHECK((p.reached <= std::min(0.1, 10 * p.tolerance) || rep.linear.fallbacks > 0));
      } else {
        CHECK(p.krylovIterations == 0);
        CHECK(p.tolerance == 0);
        CHECK(p.reached == 0);
      }
      CHECK(p.largest.starts_with("fibre 'f"));
    }
    // the records leave out only the exact solve that checks the converged increment
    CHECK(gmres <= rep.linear.krylovIterations);
    if (krylov) CHECK(gmres > 0);
    CHECK(seen.back().activeElements == rep.contact.active);
    CHECK(seen.back().slidingElements == rep.contact.sliding);
    CHECK(seen.back().deepest == doctest::Approx(rep.contact.maxPenetrationRatio));
    CHECK(rep.contact.active > 0);
  }
}

TEST_CASE("the solver section's forcing_max: read, bounded, and only for the GMRES strategies") {
  const auto scene = [](const std::string& solver) {
    return R"({"units": "mm-N-MPa", "materials": [{"name": "m", "young_modulus": 4000}],
      "fibres": [{"name": "b", "material": "m", "radius": 0.1, "elements": 4,
                  "geometry": {"type": "line", "points": [[0, 0, 0], [10, 0, 0]]}}],
      "boundary_conditions": [{"type": "clamp", "group": "b.start"}],
      "steps": [{"end_time": 1, "increments": 1}], "solver": )" + solver + "}";
  };
  const auto error = [&](const std::string& solver) {
    return test::errorOf([&] { loadSceneFromString(scene(solver), "s.json"); });
  };
  CHECK(loadSceneFromString(scene(R"({"strategy": "schwarz", "forcing_max": 0.1})"), "s.json")
            .solver.krylov.forcingMax == 0.1);
  CHECK(error(R"({"forcing_max": 1})") == "s.json: solver.forcing_max: must be in [0, 1), got 1");
  CHECK(error(R"({"forcing_max": -0.1})") == "s.json: solver.forcing_max: must be in [0, 1), got -0.1");
  CHECK(error(R"({"strategy": "mumps", "forcing_max": 0.1})") ==
        "s.json: solver.forcing_max: applies to the GMRES strategies (schwarz, krylov, krylov-lu, "
        "mumps with blr_tolerance, auto), not to 'mumps'");
  CHECK(error(R"({"strategy": "mumps", "blr_tolerance": 1e-6, "forcing_max": 0.1})") == "(no error)");
}
