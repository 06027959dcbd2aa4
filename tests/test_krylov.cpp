// GMRES (systems/krylov.h) on a non-symmetric system with restarts: it converges to its
// tolerance on the true residual, computed here, and agrees with a direct solve.
#include "linear_fixtures.h"
#include "systems/krylov.h"

#include <Eigen/SparseLU>
#include <doctest/doctest.h>

using namespace fibra;

namespace {

// A non-symmetric, diagonally dominant n x n matrix: 4 on the diagonal, -1.5 below, -0.5 above,
// and 0.3 at (i, 7919 i mod n) off the band, so that GMRES needs tens of iterations.
SparseMatrix testMatrix(Index n) {
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i > 0) t.emplace_back(i, i - 1, -1.5);
    if (i + 1 < n) t.emplace_back(i, i + 1, -0.5);
    const Index j = (7919 * i) % n;
    if (j != i && std::abs(j - i) > 1) t.emplace_back(i, j, 0.3);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST_CASE("GMRES(8) with a Jacobi preconditioner: restarted, converged, the direct solve's x") {
  const Index n = 5000;
  const SparseMatrix A = testMatrix(n);
  const Eigen::VectorXd b = linear_fixtures::randomVector(n, 3);
  const LinearOperator op = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = A * v; };
  const LinearOperator jacobi = [](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = v / 4.0; };
  Eigen::VectorXd x;
  GmresWorkspace ws;
  const GmresResult r = gmres(op, jacobi, b, x, {.tolerance = 1e-10, .restart = 8, .maxIterations = 400}, ws);
  REQUIRE(r.converged);
  MESSAGE("GMRES(8): " << r.iterations << " iterations, residual " << r.residual);
  CHECK(r.iterations > 8);  // restarted at least once
  const double trueResidual = (b - A * x).norm() / b.norm();
  CHECK(trueResidual <= 1e-10);
  CHECK(std::abs(trueResidual - r.residual) <= 1e-12);  // the result reports the true residual
  Eigen::SparseLU<SparseMatrix> lu(A);
  REQUIRE(lu.info() == Eigen::Success);
  const Eigen::VectorXd exact = lu.solve(b);
  CHECK((x - exact).norm() <= 1e-8 * exact.norm());
  // allowed fewer iterations than it needs, it says it has not converged, and x is its last iterate
  Eigen::VectorXd partial;
  const GmresResult cut = gmres(op, jacobi, b, partial, {.tolerance = 1e-10, .restart = 8, .maxIterations = 5}, ws);
  CHECK_FALSE(cut.converged);
  CHECK(cut.iterations == 5);
  CHECK(cut.residual == doctest::Approx((b - A * partial).norm() / b.norm()).epsilon(1e-9));
  CHECK(cut.residual < 1);
}
