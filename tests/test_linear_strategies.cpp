// Linear-solve strategies (systems/linear_solver.h): each solves a frictional (non-symmetric)
// and a frictionless (symmetric) contact tangent of a squeezed 7-fibre bundle to its tolerance,
// checked here with the full K; the Krylov strategy re-uses its factor across tangents of one
// pattern, refactorises when asked by its iteration count, shifts a symmetric part that is not
// positive definite and still solves the true (indefinite) K; a squeezed 7-fibre bundle reaches
// the same final state with every strategy, deterministically for a thread count; the scene's
// `solver` section is read and checked with field-named errors. Every strategy is run with
// each fill-reducing ordering (auto, AMD, METIS); MUMPS also with a block low-rank factor inside
// GMRES, reports a singular tangent with its error code, and repeats itself bitwise. The Schwarz
// preconditioner alone: tests/test_schwarz_preconditioner.cpp.
#include "bench/contact_scenes.h"
#include "engine/world_state.h"
#include "systems/krylov.h"
#include "systems/schwarz_preconditioner.h"
#include "io/scene_loader.h"
#include "linear_fixtures.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

#include <random>

#include <tbb/task_arena.h>

using namespace fibra;
using namespace fibra::linear_fixtures;

namespace {

constexpr LinearStrategy kStrategies[] = {LinearStrategy::Direct, LinearStrategy::Umfpack,
                                          LinearStrategy::Krylov, LinearStrategy::KrylovLu,
                                          LinearStrategy::Mumps, LinearStrategy::Schwarz};

// The largest difference between two states in what the mechanics fixes: the centrelines x0
// (mm), each section's metric g_a . g_b (stretch and shear in its plane, -) and its tilt against
// the bundle's axis x (g_a . e_x: the fibres lie along x). Not the sections' spin about the axis: frictionless contact on facing particles (the default) puts no torque on a
// fibre, and a fibre whose ends hold only x and y has no torsional support, so the spin is a
// rigid mode that only the stabilisation springs fix (a KrylovLu run of the frictionless bundle
// below differs from the direct one by 5e-11 in a director, 1.8e-12 in these).
double mechanicalDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double d = 0;
  for (Eigen::Index n = 0; n < a.size() / 9; ++n) {
    const auto node = [n](const Eigen::VectorXd& q, int at) { return Vec3(q.segment<3>(9 * n + at)); };
    d = std::max(d, (node(a, 0) - node(b, 0)).cwiseAbs().maxCoeff());
    for (int i : {3, 6}) {
      d = std::max(d, std::abs(node(a, i).x() - node(b, i).x()));
      for (int j : {3, 6}) d = std::max(d, std::abs(node(a, i).dot(node(a, j)) - node(b, i).dot(node(b, j))));
    }
  }
  return d;
}

}  // namespace

TEST_CASE("every linear strategy solves a frictional and a frictionless contact tangent, with every ordering") {
  // Frictionless with fixed normals: symmetric; with linearised normals, or friction: not.
  using enum NormalUpdate;
  for (const auto& [mu, update] :
       {std::pair(0.0, Loop), std::pair(0.0, Newton), std::pair(0.1, Newton)}) {
    auto w = squeezedBundle(mu, update);
    const LinearSystem& ls = w->system;
    CHECK(ls.symmetric == (update == Loop));
    const Eigen::VectorXd b = randomVector(ls.freeCount, 7);
    for (LinearStrategy s : kStrategies)
      for (Ordering o : {Ordering::Auto, Ordering::Amd, Ordering::Metis}) {
        CAPTURE(mu);
        CAPTURE(strategyName(s));
        CAPTURE(int(o));
        LinearSolver solver;
        solver.setOrdering(o);
        const double res = solveWith(s, ls, b, solver, &w->fibres);
        // Krylov: its own tolerance; the direct factorisations: their round-off, well below it.
        CHECK(res <= KrylovSettings{}.tolerance);
        if (s == LinearStrategy::Krylov) CHECK(solver.stats().krylovIterations > 0);
        if (s == LinearStrategy::Schwarz) {  // by its own preconditioner, not the fallback
          CHECK(solver.stats().krylovIterations > 1);
          CHECK(solver.stats().fallbacks == 0);
        }
        if (s == LinearStrategy::Mumps) CHECK(solver.stats().krylovIterations == 0);
      }
    // MUMPS with a block low-rank factor (a coarse 1e-2, so that it is approximate): GMRES on
    // the true K reaches the Krylov tolerance.
    for (Ordering o : {Ordering::Auto, Ordering::Amd, Ordering::Metis}) {
      CAPTURE(mu);
      CAPTURE(int(o));
      LinearSolver solver;
      solver.setOrdering(o);
      solver.setKrylov({.blrTolerance = 1e-2});
      CHECK(solveWith(LinearStrategy::Mumps, ls, b, solver) <= KrylovSettings{}.tolerance);
      CHECK(solver.stats().krylovIterations >= 1);
      CHECK(solver.stats().krylovFailures == 0);
    }
  }
}

TEST_CASE("the MUMPS strategy analyses once per pattern and repeats itself bitwise") {
  for (double blr : {0.0, 1e-2}) {
    CAPTURE(blr);
    auto w = squeezedBundle(0.1);
    const LinearSystem& ls = w->system;
    const Eigen::VectorXd b = randomVector(ls.freeCount, 13);
    LinearSolver solver, other;
    solver.setKrylov({.blrTolerance = blr});
    other.setKrylov({.blrTolerance = blr});
    std::vector<Eigen::VectorXd> x(3);
    std::string message;
    for (int k = 0; k < 2; ++k) {
      solver.setStrategy(LinearStrategy::Mumps);
      REQUIRE(solver.factorise(ls, message));
      solver.solve(b, x[k]);
    }
    other.setStrategy(LinearStrategy::Mumps);
    REQUIRE(other.factorise(ls, message));
    other.solve(b, x[2]);
    CHECK(solver.stats().analyses == 1);
    CHECK(solver.stats().factorisations == 2);
    CHECK(solver.stats().solves == 2);
    CHECK(x[0] == x[1]);  // bitwise: the same solver twice, and a fresh one
    CHECK(x[0] == x[2]);
    // Another BLR tolerance (or none) is another analysis.
    solver.setKrylov({.blrTolerance = blr > 0 ? 0 : 1e-2});
    REQUIRE(solver.factorise(ls, message));
    CHECK(solver.stats().analyses == 2);
  }
}

TEST_CASE("auto picks the direct path below kMumpsFromEquations and MUMPS from there") {
  LinearSolver solver;
  CHECK(solver.resolved(kMumpsFromEquations - 1) == LinearStrategy::Direct);
  CHECK(solver.resolved(kMumpsFromEquations) == LinearStrategy::Mumps);
  solver.setStrategy(LinearStrategy::Umfpack);
  CHECK(solver.resolved(kMumpsFromEquations) == LinearStrategy::Umfpack);
  // From there, Schwarz on a heavy fill when the fibres are known.
  CHECK(autoTakesSchwarz(kSchwarzFromFlopsPerEntry, true));
  CHECK_FALSE(autoTakesSchwarz(0.99 * kSchwarzFromFlopsPerEntry, true));
  CHECK_FALSE(autoTakesSchwarz(10 * kSchwarzFromFlopsPerEntry, false));
}

TEST_CASE("the fill measure of auto's rule: MUMPS's flops per non-zero of a dense K are 2n/3") {
  // A dense n x n LU costs sum over the pivots k of 2 (n - k)^2 + (n - k) ~ 2n^3/3 flops; per
  // non-zero (n^2), 2n/3: independent of MUMPS's own count.
  const int n = 90;
  Eigen::MatrixXd A = Eigen::MatrixXd::Random(n, n);
  A.diagonal().array() += 2.0 * n;
  LinearSystem ls;
  ls.freeCount = n;
  ls.symmetric = false;
  ls.K = A.sparseView();
  LinearSolver solver;
  solver.setStrategy(LinearStrategy::Mumps);
  std::string message;
  REQUIRE(solver.factorise(ls, message));
  double exact = 0;
  for (int k = 1; k <= n; ++k) exact += 2.0 * (n - k) * (n - k) + (n - k);
  CHECK(solver.stats().flopsPerEntry == doctest::Approx(exact / (n * n)).epsilon(0.05).scale(0));
  CHECK(solver.stats().schwarzChoices == 0);
}

TEST_CASE("the MUMPS strategy reports a singular tangent with MUMPS's error code") {
  // Equation 5's column and row zeroed: numerically singular. Non-symmetric (LU) and
  // symmetric (LDL^T) tangents.
  for (NormalUpdate update : {NormalUpdate::Newton, NormalUpdate::Loop}) {
    auto w = squeezedBundle(0, update);
    LinearSystem ls = w->system;
    for (Index j = 0; j < ls.K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(ls.K, j); it; ++it)
        if (it.row() == 5 || j == 5) it.valueRef() = 0;
    for (double blr : {0.0, 1e-2}) {
      CAPTURE(ls.symmetric);
      CAPTURE(blr);
      LinearSolver solver;
      solver.setStrategy(LinearStrategy::Mumps);
      solver.setKrylov({.blrTolerance = blr});
      std::string message;
      CHECK_FALSE(solver.factorise(ls, message));
      CHECK(message.find("MUMPS error -") == 0);
      CHECK(message.find("singular") != std::string::npos);
      // The solver stays usable: the intact tangent factorises.
      CHECK(solveWith(LinearStrategy::Mumps, w->system, randomVector(ls.freeCount, 1), solver) <=
            KrylovSettings{}.tolerance);
    }
  }
}

TEST_CASE("the Krylov strategy re-uses its factor, refactorises when asked, and counts both") {
  auto w = squeezedBundle(0.1);
  LinearSystem ls = w->system;
  const Eigen::VectorXd b = randomVector(ls.freeCount, 11);
  LinearSolver solver;
  solver.setKrylov({.tolerance = 1e-10, .refactorAbove = 1000});
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  const int first = solver.stats().krylovIterations;
  // Another tangent of the same pattern, D K D with D = diag(1 + 0.05 u), u in [-1, 1] (a
  // congruence keeps the beams' structure): the factor is kept.
  const Eigen::VectorXd d = Eigen::VectorXd::Ones(ls.freeCount) + 0.05 * randomVector(ls.freeCount, 3);
  for (Index j = 0; j < ls.K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(ls.K, j); it; ++it) it.valueRef() *= d(it.row()) * d(j);
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  CHECK(solver.stats().factorisations == 1);
  CHECK(solver.stats().reuses == 1);
  CHECK(solver.stats().krylovIterations > 2 * first);  // the stale factor costs iterations
  // Asked to refactorise above one iteration: GMRES with the re-used factor stops after one
  // iteration and the factor is renewed at once, the solve redone with it.
  solver.setKrylov({.tolerance = 1e-10, .refactorAbove = 1});
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  CHECK(solver.stats().reuses == 2);
  CHECK(solver.stats().refactorisations == 1);
  CHECK(solver.stats().factorisations == 2);
  // That fresh solve needed more than one iteration (K is not symmetric): the next call
  // refactorises before solving.
  const int before = solver.stats().krylovIterations;
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  CHECK(solver.stats().refactorisations == 2);
  CHECK(solver.stats().factorisations == 3);
  CHECK(solver.stats().reuses == 2);
  CHECK(solver.stats().krylovIterations - before > 1);
  // A new stored pattern revision with the same non-zeros: the non-zero pattern carries over
  // whole, no new analysis (systems/nonzero_pattern.h); a pattern started afresh (each
  // increment) gets a new one; on the stored pattern (slack 0) each revision does.
  ++ls.revision;
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  CHECK(solver.stats().analyses == 1);
  solver.forgetPattern();
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  CHECK(solver.stats().analyses == 2);
  solver.setKrylov({.tolerance = 1e-10, .refactorAbove = 1, .patternSlack = 0});
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  ++ls.revision;
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, solver) <= 1e-10);
  CHECK(solver.stats().analyses == 4);
}

TEST_CASE("the Krylov strategy shifts an indefinite symmetric part and solves the true K") {
  // The frictionless bundle's tangent is not positive definite (the direct strategy falls back
  // to LDL^T): Krylov factorises its symmetric part shifted and still solves K itself. (Fixed
  // normals: the tangent is symmetric.)
  auto w = squeezedBundle(0, NormalUpdate::Loop);
  const LinearSystem& ls = w->system;
  const Eigen::VectorXd b = randomVector(ls.freeCount, 5);
  LinearSolver direct;
  CHECK(solveWith(LinearStrategy::Direct, ls, b, direct) <= KrylovSettings{}.tolerance);
  REQUIRE(direct.stats().fallbacks == 1);
  LinearSolver krylov;
  CHECK(solveWith(LinearStrategy::Krylov, ls, b, krylov) <= KrylovSettings{}.tolerance);
  CHECK(krylov.stats().shifted == 1);
  CHECK(krylov.stats().shift > 0);
  CHECK(krylov.stats().fallbacks == 0);
}

TEST_CASE("a squeezed 7-fibre bundle reaches the same state with every linear strategy") {
  // The first 4 of its 10 increments (0.004 mm of squeeze), to keep the test short. Fixed
  // normals (contact normal_update "loop"): with linearised normals the tangent is indefinite
  // (fibres lying on fibres have a negative lateral stiffness) and the strategies' round-off
  // sends Newton along different paths (UMFPACK stagnates at the 4th frictional increment where
  // sparse LU converges; docs/RESULTS.md).
  for (double mu : {0.0, 0.1}) {
    std::vector<Eigen::VectorXd> finals;
    std::vector<double> forces;
    for (LinearStrategy s : kStrategies) {
      CAPTURE(mu);
      const std::string name = strategyName(s);
      CAPTURE(name);
      SceneDef scene = scenes::bundle(1, 10, 0.01, 5e-4, mu);
      scene.contact.normalUpdate = NormalUpdate::Loop;
      World w(scene, {.threads = 1, .linearStrategy = s});
      for (int k = 0; k < 4; ++k) REQUIRE(w.step().status == StepStatus::Converged);
      finals.push_back(w.fibres().q);
      forces.push_back(w.toolReaction(1).z());
    }
    // Tool force: within Newton's force tolerance (1e-8 of the reference force). State: the
    // Krylov runs no farther from the direct one than the two exact factorisations (direct and
    // UMFPACK, both to round-off) are from each other, plus 1e-11 mm; they differ in the soft
    // modes that the stabilisation springs, anchored at each increment's start, carry from
    // increment to increment (measured over these 4 increments: 6e-16 mm frictionless, 1e-11
    // with friction; over all 10: 9e-8 and 2e-11).
    const double exactSpread = mechanicalDifference(finals[1], finals[0]);
    CAPTURE(mu);
    CAPTURE(exactSpread);
    for (size_t k = 2; k < finals.size(); ++k) {
      CAPTURE(k);
      MESSAGE("state difference " << mechanicalDifference(finals[k], finals[0]));
      CHECK(mechanicalDifference(finals[k], finals[0]) <= exactSpread + 1e-11);
    }
    for (size_t k = 1; k < forces.size(); ++k) CHECK(std::abs(forces[k] - forces[0]) <= 1e-8 * std::abs(forces[0]));
  }
}

TEST_CASE("the Krylov strategy is deterministic for a thread count") {
  std::vector<Eigen::VectorXd> q;
  for (int run = 0; run < 2; ++run) {
    World w(scenes::bundle(1, 10, 0.01, 5e-4, 0.1),
            {.threads = 2, .linearStrategy = LinearStrategy::Krylov});
    for (int k = 0; k < 3; ++k) REQUIRE(w.step().status == StepStatus::Converged);
    q.push_back(w.fibres().q);
  }
  CHECK(q[0] == q[1]);
}

TEST_CASE("the scene's solver section sets the strategy and the Krylov settings") {
  const std::string base = R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000}],
    "fibres": [{"name": "b", "material": "m", "radius": 0.1, "elements": 4,
                "geometry": {"type": "line", "points": [[0, 0, 0], [10, 0, 0]]}}],
    "boundary_conditions": [{"type": "clamp", "group": "b.start"}],
    "steps": [{"end_time": 1, "increments": 1}],
    "solver": SOLVER
  })";
  auto scene = [&](const std::string& solver) {
    std::string text = base;
    text.replace(text.find("SOLVER"), 6, solver);
    return text;
  };
  const SceneDef s = loadSceneFromString(
      scene(R"({"strategy": "mumps", "ordering": "metis", "krylov_tolerance": 1e-9,
                "krylov_restart": 30, "krylov_max_iterations": 100, "refactor_above": 25,
                "blr_tolerance": 1e-6})"),
      "s.json");
  CHECK(s.solver.strategy == LinearStrategy::Mumps);
  CHECK(s.solver.ordering == Ordering::Metis);
  CHECK(s.solver.krylov.tolerance == 1e-9);
  CHECK(s.solver.krylov.restart == 30);
  CHECK(s.solver.krylov.maxIterations == 100);
  CHECK(s.solver.krylov.refactorAbove == 25);
  CHECK(s.solver.krylov.blrTolerance == 1e-6);
  CHECK(loadSceneFromString(scene(R"({"strategy": "krylov"})"), "s.json").solver.strategy ==
        LinearStrategy::Krylov);
  CHECK(loadSceneFromString(scene(R"({"blr_tolerance": 1e-6})"), "s.json")
            .solver.krylov.blrTolerance == 1e-6);  // auto: mumps from 7000 equations
  CHECK(loadSceneFromString(scene("{}"), "s.json").solver.krylov.blrTolerance == 0);
  CHECK(loadSceneFromString(scene("{}"), "s.json").solver.strategy == LinearStrategy::Auto);
  CHECK(loadSceneFromString(scene("{}"), "s.json").solver.ordering == Ordering::Auto);
  auto error = [&](const std::string& solver) {
    return test::errorOf([&] { loadSceneFromString(scene(solver), "s.json"); });
  };
  CHECK(error(R"({"strategy": "cg"})") ==
        "s.json: solver.strategy: unknown value \"cg\" (expected one of: auto, direct, umfpack, "
        "krylov, krylov-lu, mumps, schwarz)");
  CHECK(error(R"({"ordering": "colamd"})") ==
        "s.json: solver.ordering: unknown value \"colamd\" (expected one of: auto, amd, metis)");
  CHECK(error(R"({"krylov_tolerance": 0})") == "s.json: solver.krylov_tolerance: must be in (0, 1), got 0");
  CHECK(error(R"({"krylov_restart": 0})") == "s.json: solver.krylov_restart: must be >= 1, got 0");
  CHECK(error(R"({"refactor_above": 0})") == "s.json: solver.refactor_above: must be >= 1, got 0");
  CHECK(error(R"({"blr_tolerance": -1e-6})") ==
        "s.json: solver.blr_tolerance: must be in [0, 1), got -1e-06");
  CHECK(error(R"({"strategy": "krylov", "blr_tolerance": 1e-6})") ==
        "s.json: solver.blr_tolerance: applies to the strategies mumps and auto (mumps from 7000 "
        "equations), not to 'krylov'");
  const SceneDef schwarz =
      loadSceneFromString(scene(R"({"strategy": "schwarz", "coarse_segments": 4})"), "s.json");
  CHECK(schwarz.solver.strategy == LinearStrategy::Schwarz);
  CHECK(schwarz.solver.krylov.coarseSegments == 4);
  CHECK(error(R"({"strategy": "schwarz", "coarse_segments": 0})") ==
        "s.json: solver.coarse_segments: must be in [1, 1000], got 0");
  CHECK(error(R"({"strategy": "mumps", "coarse_segments": 4})") ==
        "s.json: solver.coarse_segments: applies to the strategies schwarz and auto, not to 'mumps'");
  CHECK(loadSceneFromString(scene(R"({"coarse_segments": 15})"), "s.json").solver.krylov.coarseSegments == 15);
  // the coarse rotations: auto by default, on or off, and only where a coarse level is built
  CHECK(loadSceneFromString(scene("{}"), "s.json").solver.krylov.coarseRotations == CoarseRotations::Auto);
  CHECK(loadSceneFromString(scene(R"({"strategy": "schwarz", "coarse_rotations": "off"})"), "s.json")
            .solver.krylov.coarseRotations == CoarseRotations::Off);
  CHECK(error(R"({"strategy": "schwarz", "coarse_rotations": "some"})") ==
        "s.json: solver.coarse_rotations: unknown value \"some\" (expected one of: auto, on, off)");
  CHECK(error(R"({"strategy": "umfpack", "coarse_rotations": "on"})") ==
        "s.json: solver.coarse_rotations: applies to the strategies schwarz and auto, not to 'umfpack'");
  // the non-zero pattern's slack: 0 (off) or in [1, 100]
  CHECK(loadSceneFromString(scene("{}"), "s.json").solver.krylov.patternSlack == 1.5);
  CHECK(loadSceneFromString(scene(R"({"pattern_slack": 0})"), "s.json").solver.krylov.patternSlack == 0);
  CHECK(loadSceneFromString(scene(R"({"pattern_slack": 2})"), "s.json").solver.krylov.patternSlack == 2);
  CHECK(error(R"({"pattern_slack": 0.5})") ==
        "s.json: solver.pattern_slack: must be 0 (off) or in [1, 100], got 0.5");
  // Newton's cycle damping (systems/newton.h): on unless the scene says false
  CHECK(loadSceneFromString(scene("{}"), "s.json").solver.cycleDamping);
  CHECK(!loadSceneFromString(scene(R"({"cycle_damping": false})"), "s.json").solver.cycleDamping);
  CHECK(error(R"({"cycle_damping": 1})") ==
        "s.json: solver.cycle_damping: expected true or false, got the number 1");
}

TEST_CASE("the linear solver's spans appear in the trace with their counts, which the step report gives") {
  Trace trace;
  World w(scenes::bundle(1, 10, 0.01, 5e-4, 0.1),
          {.threads = 1, .trace = &trace, .linearStrategy = LinearStrategy::Krylov});
  const StepReport r = w.step();
  REQUIRE(r.status == StepStatus::Converged);
  int factorise = 0, solve = 0, krylov = 0;
  std::int64_t iterations = 0;
  for (const Trace::Event& e : trace.events()) {
    const std::string name = e.name;
    factorise += name == "factorise";
    solve += name == "solve";
    if (name == "krylov") ++krylov, iterations += e.items;
  }
  CHECK(factorise >= 1);
  CHECK(solve >= 1);
  CHECK(krylov >= solve);  // one GMRES run per solve, two when a re-used factor failed
  CHECK(iterations >= krylov);
  // The increment's report counts what the trace recorded (the first increment: the whole
  // trace), and the GMRES count reaches the history (linear.krylov_iterations).
  CHECK(r.linear.factorisations == factorise);
  CHECK(r.linear.solves == solve);
  CHECK(r.linear.krylovIterations == iterations);
  CHECK(r.linear.maxKrylovIterations >= 1);
  CHECK(r.linear.maxKrylovIterations <= 200);  // krylov_max_iterations
  CHECK(r.linear.krylovFailures == 0);
  // The next increment's counts start from zero.
  trace.clear();
  const StepReport next = w.step();
  REQUIRE(next.status == StepStatus::Converged);
  std::int64_t nextIterations = 0;
  for (const Trace::Event& e : trace.events())
    if (std::string(e.name) == "krylov") nextIterations += e.items;
  CHECK(next.linear.krylovIterations == nextIterations);
}
