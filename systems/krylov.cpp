#include "systems/krylov.h"

#include <cmath>

namespace fibra {
namespace {

// Sizes the workspace for n unknowns and m vectors (reallocates only on a change of size).
void size(GmresWorkspace& ws, Eigen::Index n, int m) {
  if (ws.V.rows() != n || ws.V.cols() != m + 1) ws.V.resize(n, m + 1), ws.Z.resize(n, m);
  ws.H.setZero(m + 1, m);
  ws.g.setZero(m + 1);
  ws.c.setZero(m);
  ws.s.setZero(m);
  ws.r.resize(n);
  ws.w.resize(n);
}

// r = b - A x; returns |r|.
double residual(const LinearOperator& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x,
                GmresWorkspace& ws) {
  A(x, ws.w);
  ws.r = b - ws.w;
  return ws.r.norm();
}

// Arnoldi step j: z_j = M^-1 v_j, w = A z_j orthogonalised against v_0..v_j (modified
// Gram-Schmidt) into H(:, j) and v_{j+1}.
void arnoldi(const LinearOperator& A, const LinearOperator& Minv, int j, GmresWorkspace& ws) {
  ws.v = ws.V.col(j);  // the operators take vectors: kept ones, not a fresh one per step
  Minv(ws.v, ws.z);
  ws.Z.col(j) = ws.z;
  A(ws.z, ws.w);
  for (int i = 0; i <= j; ++i) {
    ws.H(i, j) = ws.V.col(i).dot(ws.w);
    ws.w -= ws.H(i, j) * ws.V.col(i);
  }
  ws.H(j + 1, j) = ws.w.norm();
  if (ws.H(j + 1, j) > 0) ws.V.col(j + 1) = ws.w / ws.H(j + 1, j);
}

// Applies the previous rotations to column j, makes the rotation that zeroes H(j+1, j) and
// applies it to g; returns |g(j+1)|, the residual of the least-squares problem.
double rotate(int j, GmresWorkspace& ws) {
  auto& H = ws.H;
  for (int i = 0; i < j; ++i) {
    const double a = H(i, j), b = H(i + 1, j);
    H(i, j) = ws.c(i) * a + ws.s(i) * b;
    H(i + 1, j) = -ws.s(i) * a + ws.c(i) * b;
  }
  const double a = H(j, j), b = H(j + 1, j), d = std::hypot(a, b);
  ws.c(j) = d > 0 ? a / d : 1;
  ws.s(j) = d > 0 ? b / d : 0;
  H(j, j) = d;
  H(j + 1, j) = 0;
  ws.g(j + 1) = -ws.s(j) * ws.g(j);
  ws.g(j) = ws.c(j) * ws.g(j);
  return std::abs(ws.g(j + 1));
}

}  // namespace

GmresResult gmres(const LinearOperator& A, const LinearOperator& Minv, const Eigen::VectorXd& b,
                  Eigen::VectorXd& x, const GmresSettings& settings, GmresWorkspace& ws) {
  GmresResult res;
  const Eigen::Index n = b.size();
  if (x.size() != n) x.setZero(n);
  const double bNorm = b.norm();
  if (bNorm == 0) {
    x.setZero();
    res.converged = true;
    return res;
  }
  const double target = settings.tolerance * bNorm;
  const int m = std::max(1, settings.restart);
  double beta = residual(A, b, x, ws);
  while (beta > target && res.iterations < settings.maxIterations) {
    size(ws, n, m);
    ws.V.col(0) = ws.r / beta;
    ws.g(0) = beta;
    int k = 0;
    while (k < m && res.iterations < settings.maxIterations) {
      arnoldi(A, Minv, k, ws);
      const bool breakdown = !(ws.H(k + 1, k) > 0);
      const double estimate = rotate(k, ws);
      ++k;
      ++res.iterations;
      if (estimate <= target || breakdown) break;
    }
    // y from the triangular system, x += Z y
    const Eigen::VectorXd y =
        ws.H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(ws.g.head(k));
    x += ws.Z.leftCols(k) * y;
    beta = residual(A, b, x, ws);
    if (!std::isfinite(beta)) break;
  }
  res.residual = beta / bNorm;
  res.converged = beta <= target;
  return res;
}

}  // namespace fibra
