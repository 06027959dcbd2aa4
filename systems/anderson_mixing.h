// Anderson acceleration of a fixed-point iteration x = G(x) (Walker & Ni 2011, "type II", no
// damping), used by loop B on the contact normals (systems/normal_acceleration.h).
//
// Reads  the iterate x_k and its image g_k = G(x_k) of each step (any unit; one vector length
//        for a whole history).
// Writes its own history of the last m + 1 pairs (g_i, f_i), f_i = g_i - x_i (the residual).
// Computes the next iterate
//   x_{k+1} = g_k - dG gamma,   gamma = argmin_gamma |f_k - dF gamma|_2,
// or with a mixing parameter beta, x_{k+1} = x_k - dX gamma + beta (f_k - dF gamma), dX = dG - dF
// (a small beta keeps the step along the residual the secant cannot explain small),
//   dF = [f_{i+1} - f_i],  dG = [g_{i+1} - g_i]  over the last min(m, k) differences,
// the least-squares problem solved by a column-pivoting QR whose columns below 1e-12 of the
// largest are dropped (rank-deficient histories fall back to fewer differences; none left: the
// plain step x_{k+1} = g_k). On a linear map G(x) = A x + b it is a secant method: with memory
// m >= dim x it reaches the fixed point x* = (I - A)^{-1} b in dim x + 1 steps whatever the
// spectral radius of A, where plain iteration diverges as soon as one |eig(A)| > 1.
// Deterministic: dense arithmetic in a fixed order, no threading.
#pragma once

#include <Eigen/Core>

#include <deque>

namespace fibra {

class AndersonMixer {
 public:
  explicit AndersonMixer(int memory) : memory_(memory) {}

  // The next iterate from x_k and g_k = G(x_k); a vector of another length than the history's
  // starts a new history (the plain step g_k).
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& g);

  // The same split as x_{k+1} = xBar + beta fBar (mixing parameter beta; next() is beta = 1):
  // xBar = x_k - dX gamma (dX = dG - dF), fBar = f_k - dF gamma, the residual the secant
  // predicts at xBar. Records the pair as next() does.
  struct Split {
    Eigen::VectorXd xBar, fBar;
  };
  Split split(const Eigen::VectorXd& x, const Eigen::VectorXd& g);

  // Forget the history (a new fixed-point problem).
  void reset();

  // Differences used by the last call of next (0: the plain step).
  int used() const { return used_; }

 private:
  int memory_;
  int used_ = 0;
  std::deque<Eigen::VectorXd> g_, f_;  // the last memory + 1 images and residuals, oldest first
};

}  // namespace fibra
