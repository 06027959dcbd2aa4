// Newton stagnation: one node whose first DOF has a residual on which Newton cycles or creeps
// away without diverging, the others linear. The attempt must stop early with the stagnation
// message, not run to max_iterations; a problem that converges must not be stopped.
//   r0(q) = q^(1/2) (q > 0), -2 (-q)^(1/2) (q < 0): the Newton step maps q to -q exactly, so
//     the residual alternates between sqrt(a) and 2 sqrt(a): a cycle of period 2;
//   r0(q) = sign(q) |q|^(1/3): the Newton step maps q to -2q, the residual grows by 2^(1/3)
//     per iteration: no new smallest residual, far below the divergence bound for 20 iterations.
//   r0(q) = atan(q) from just outside Newton's 2-cycle: full steps creep away, residuals
//     repeating to 1e-2, until the cycle damping halves one step (systems/newton.h).
#include "systems/newton.h"

#include <doctest/doctest.h>

#include <cmath>

using namespace fibra;

namespace {

struct OneNode {
  LinearSystem ls;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(kNodeDofs);
  std::function<std::pair<double, double>(double)> law;  // q0 -> (r0, dr0/dq0)

  OneNode() {
    ls.equation.resize(kNodeDofs);
    ls.dofOf.resize(kNodeDofs);
    for (Index d = 0; d < kNodeDofs; ++d) ls.equation[d] = ls.dofOf[d] = d;
    ls.freeCount = kNodeDofs;
    ls.K.resize(kNodeDofs, kNodeDofs);
    for (Index d = 0; d < kNodeDofs; ++d) ls.K.insert(d, d) = 1;
    ls.K.makeCompressed();
    ls.r = Eigen::VectorXd::Zero(kNodeDofs);
    ls.fext = Eigen::VectorXd::Zero(kNodeDofs);
  }

  void assemble(bool) {
    const auto [r0, k0] = law(q(0));
    ls.r = q;
    ls.r(0) = r0;
    ls.K.coeffRef(0, 0) = k0;
  }

  NewtonResult solve(double q0, int maxIterations, bool cycleDamping = false) {
    q.setZero();
    q(0) = q0;
    NewtonSettings s;
    s.maxIterations = maxIterations;
    s.cycleDamping = cycleDamping;
    s.forceFloor = 1;  // F_ref = 1 N: residuals read as forces
    NewtonCallbacks cb;
    cb.assemble = [this](bool t) { assemble(t); };
    LinearSolver solver;
    StepTimings timings;
    return solveNewton(q, ls, solver, s, cb, timings);
  }
};

}  // namespace

TEST_CASE("Newton stops on a residual cycle with the stagnation message") {
  OneNode n;
  n.law = [](double x) -> std::pair<double, double> {
    if (x > 0) return {std::sqrt(x), 0.5 / std::sqrt(x)};
    return {-2 * std::sqrt(-x), 1 / std::sqrt(-x)};
  };
  const NewtonResult r = n.solve(0.25, 10000);
  CHECK(r.outcome == NewtonOutcome::Failed);
  CHECK(r.iterations == 4);  // the cycle seen twice
  CHECK(r.message.find("stagnation: the residual repeats a cycle of 2 iterations") == 0);
  REQUIRE(r.history.size() == 4);
  CHECK(r.history[0].residual == doctest::Approx(1.0));  // q = -0.25: 2 sqrt(0.25)
  CHECK(r.history[1].residual == doctest::Approx(0.5));
}

TEST_CASE("Newton stops when no iteration brings a smaller residual") {
  OneNode n;
  n.law = [](double x) -> std::pair<double, double> {
    const double a = std::cbrt(std::abs(x));
    return {std::copysign(a, x), 1 / (3 * a * a)};
  };
  const NewtonResult r = n.solve(1e-3, 10000);
  CHECK(r.outcome == NewtonOutcome::Failed);
  CHECK(r.iterations == 21);  // the first residual, then 20 without a smaller one
  CHECK(r.message.find("stagnation: no smaller residual in 20 iterations") == 0);
  CHECK(r.residual == doctest::Approx(0.1 * std::pow(2.0, 21.0 / 3)));
}

TEST_CASE("a Newton attempt that converges slowly at first is not called stagnant") {
  // r0 = atan(q): from q0 = 1.38, just inside Newton's 2-cycle at 1.3917, the iterates
  // alternate in sign and shrink slowly for several iterations before converging.
  OneNode n;
  n.law = [](double x) -> std::pair<double, double> { return {std::atan(x), 1 / (1 + x * x)}; };
  const NewtonResult r = n.solve(1.38, 30);
  CHECK(r.outcome == NewtonOutcome::Converged);
  CHECK(r.message.empty());
}

TEST_CASE("the cycle damping halves a step of a repeating residual, and Newton converges") {
  // r0 = atan(q) from q0 = 1.392, just outside Newton's 2-cycle at 1.3917: full steps swap the
  // sign of q and creep outwards (residuals 0.94798, 0.94835, 0.94934, 0.95194, ...) until
  // they run away to |q| ~ 1e23.
  OneNode n;
  n.law = [](double x) -> std::pair<double, double> { return {std::atan(x), 1 / (1 + x * x)}; };
  const NewtonResult plain = n.solve(1.392, 30);
  CHECK(plain.outcome == NewtonOutcome::Failed);
  CHECK(plain.dampedSteps == 0);
  REQUIRE(plain.history.size() >= 3);
  CHECK(plain.history[2].residual == doctest::Approx(0.94934).epsilon(1e-4).scale(0));
  CHECK(std::abs(n.q(0)) > 1e3);

  // With it: the first four residuals repeat to 1e-2 (period 1, within the reference force),
  // so the fifth step is halved (q = -0.0103, residual 1.026e-2) and full steps converge.
  const NewtonResult damped = n.solve(1.392, 30, true);
  CHECK(damped.outcome == NewtonOutcome::Converged);
  CHECK(damped.iterations == 7);
  CHECK(damped.dampedSteps == 1);
  REQUIRE(damped.history.size() == 7);
  for (int k = 0; k < 4; ++k) CHECK(damped.history[k].lineSearch == 1.0);
  CHECK(damped.history[4].lineSearch == 0.5);
  CHECK(damped.history[4].residual == doctest::Approx(1.02561e-2).epsilon(1e-3).scale(0));
  CHECK(damped.history[5].lineSearch == 1.0);
  CHECK(std::abs(n.q(0)) < 1e-15);
}

TEST_CASE("the cycle damping leaves converging attempts and exact cycles alone") {
  OneNode n;
  n.law = [](double x) -> std::pair<double, double> { return {std::atan(x), 1 / (1 + x * x)}; };
  const NewtonResult plain = n.solve(1.38, 30), damped = n.solve(1.38, 30, true);
  CHECK(damped.outcome == NewtonOutcome::Converged);
  CHECK(damped.iterations == plain.iterations);
  CHECK(damped.dampedSteps == 0);
  // the exact 2-cycle of sqrt: still stopped as stagnation, after the same 4 iterations
  n.law = [](double x) -> std::pair<double, double> {
    if (x > 0) return {std::sqrt(x), 0.5 / std::sqrt(x)};
    return {-2 * std::sqrt(-x), 1 / std::sqrt(-x)};
  };
  const NewtonResult cycle = n.solve(0.25, 10000, true);
  CHECK(cycle.iterations == 4);
  CHECK(cycle.message.find("stagnation: the residual repeats a cycle of 2 iterations") == 0);
}
