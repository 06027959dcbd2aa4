// Krylov system: right-preconditioned restarted GMRES(m) (Saad and Schultz, SIAM J. Sci. Stat.
// Comput. 7, 1986; the right-preconditioned form after Saad, Iterative Methods for Sparse Linear
// Systems, 2nd ed., section 9.3.2) for a non-symmetric sparse system A x = b.
//
// Reads  the operator A (a product), the preconditioner M^-1 (a solve), b.
// Writes x, and its workspace (the Krylov basis V and the preconditioned basis Z, kept between
//        calls so that large systems do not touch fresh memory every solve).
// Computes, per cycle from x0: r0 = b - A x0, V_1 = r0 / |r0|; for j = 1..m:
//   z_j = M^-1 v_j, w = A z_j, Arnoldi (modified Gram-Schmidt) H(:, j), v_{j+1} = w / H(j+1, j);
//   the least-squares problem min |beta e1 - H y| by Givens rotations, whose last entry is the
//   residual |b - A x_j| in exact arithmetic; then x = x0 + Z y. Right preconditioning keeps that
//   residual the true (unpreconditioned) one, and the convergence test, |b - A x| <= tol |b|, is
//   confirmed on the recomputed true residual before returning.
// No threads of its own: the products and solves passed in decide.
#pragma once

#include <Eigen/Dense>
#include <functional>

namespace fibra {

// y = Op x; both of the system's size n.
using LinearOperator = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

struct GmresSettings {
  double tolerance = 1e-10;  // relative residual |b - A x| / |b| asked for
  int restart = 40;          // m: basis vectors per cycle (memory: 2 (m + 1) n doubles)
  int maxIterations = 200;   // products A M^-1 over all cycles
};

struct GmresResult {
  bool converged = false;
  int iterations = 0;        // products A M^-1 done
  double residual = 0;       // final true relative residual |b - A x| / |b|
};

struct GmresWorkspace {
  Eigen::MatrixXd V, Z;      // n x (m + 1), n x m
  Eigen::MatrixXd H;         // (m + 1) x m, Hessenberg, rotated to upper triangular
  Eigen::VectorXd g, c, s;   // rotated right-hand side, Givens cosines and sines
  Eigen::VectorXd r, w;      // scratch of size n
  Eigen::VectorXd v, z;      // v_j and M^-1 v_j of the current Arnoldi step (size n)
};

// Solves A x = b from the initial guess x (resized to b's size and zeroed when its size
// differs). A, Minv: products of size n = b.size(). Never throws; not converging within
// maxIterations is reported in the result (x is then the last iterate).
GmresResult gmres(const LinearOperator& A, const LinearOperator& Minv, const Eigen::VectorXd& b,
                  Eigen::VectorXd& x, const GmresSettings& settings, GmresWorkspace& ws);

}  // namespace fibra
