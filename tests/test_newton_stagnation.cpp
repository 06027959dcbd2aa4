// Newton stagnation: one node whose first DOF has a residual on which Newton cycles or creeps
// away without diverging, the others linear. The attempt must stop early with the stagnation
// message, not run to max_iterations; a problem that converges must not be stopped.
//   r0(q) = q^(1/2) (q > 0), -2 (-q)^(1/2) (q < 0): the Newton step maps q to -q exactly, so
//     the residual alternates between sqrt(a) and 2 sqrt(a): a cycle of period 2;
//   r0(q) = sign(q) |q|^(1/3): the Newton step maps q to -2q, the residual grows by 2^(1/3)
//     per iteration: no new smallest residual, far below the divergence bound for 20 iterations.
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

  NewtonResult solve(double q0, int maxIterations) {
    q.setZero();
    q(0) = q0;
    NewtonSettings s;
    s.maxIterations = maxIterations;
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
