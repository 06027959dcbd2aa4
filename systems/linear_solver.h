// Linear solver system: solves K dq = -r on the free DOFs.
//
// Reads  LinearSystem (K, revision, symmetric). Owns its factorisation; no shared state.
// Symmetric K: CHOLMOD supernodal LL^T; the symbolic analysis (ordering, supernodes) is redone
//   only when the pattern revision changes, the numeric factorisation every call. A tangent
//   that is not positive definite (unstable equilibria, buckling) falls back to CHOLMOD's
//   simplicial LDL^T for that call, and the report says so.
// Non-symmetric K (friction): sparse LU with the same analysis reuse, by UMFPACK or by Eigen's
//   SparseLU (LuSolver; which is faster is measured in bench/contact_mechanics.cpp).
// Time is spent in BLAS: link OpenBLAS (reference BLAS is ~17x slower here). OpenBLAS's thread
// count is a process-wide setting: with setBlasThreads(n), every factorisation first sets it to
// n (the world passes its own thread count); 0 leaves it alone.
#pragma once

#include "components/linear_system.h"

#include <memory>
#include <string>

namespace fibra {

struct LinearSolveStats {
  double analyse = 0, factorise = 0, solve = 0;  // seconds, accumulated
  int analyses = 0, factorisations = 0, fallbacks = 0;
};

enum class LuSolver { Umfpack, EigenSparseLu };

class LinearSolver {
 public:
  LinearSolver();
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Factorises ls.K; false (with a message) if it is singular.
  bool factorise(const LinearSystem& ls, std::string& message);
  // x = K^-1 b (free DOFs); after a successful factorise.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  const LinearSolveStats& stats() const;
  void setLuSolver(LuSolver lu);  // for non-symmetric K; default EigenSparseLu
  void setBlasThreads(int threads);  // > 0: OpenBLAS threads set before each factorisation

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fibra
