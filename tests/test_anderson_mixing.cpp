// Anderson acceleration of a fixed point (systems/anderson_mixing.h) on linear maps
// G(x) = A x + b: with an eigenvalue of A beyond 1 plain iteration diverges, the mixed iterates
// converge to x* = (I - A)^{-1} b; the history restarts on a vector of another length and a
// rank-deficient history falls back to the plain step.
#include "systems/anderson_mixing.h"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <cmath>

using namespace fibra;

namespace {

// A = Q diag(eigenvalues) Q^T with a fixed rotation Q (deterministic).
Eigen::MatrixXd mapWith(const Eigen::VectorXd& eigenvalues) {
  const Eigen::Index n = eigenvalues.size();
  Eigen::MatrixXd M(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) M(i, j) = std::sin(1.0 + 3 * i + 7 * j);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(M).householderQ();
  return Q * eigenvalues.asDiagonal() * Q.transpose();
}

struct Run {
  double error;    // |x_k - x*| after the steps
  double largest;  // the largest |x_k - x*| on the way
};

// `steps` iterations from x = 0; memory 0: plain iteration x_{k+1} = G(x_k).
Run iterate(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int memory, int steps) {
  const Eigen::Index n = b.size();
  const Eigen::VectorXd xStar = (Eigen::MatrixXd::Identity(n, n) - A).lu().solve(b);
  AndersonMixer mixer(memory);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Run r{0, 0};
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd g = A * x + b;
    x = memory > 0 ? mixer.next(x, g) : g;
    r.error = (x - xStar).norm();
    r.largest = std::max(r.largest, r.error);
  }
  return r;
}

}  // namespace

TEST_CASE("Anderson mixing converges on a linear map where plain iteration diverges") {
  // Gain 3 and -2 on two modes (the laterally unstable fibre has ~700 on its first mode).
  Eigen::VectorXd eig(5);
  eig << 3, -2, 0.5, 0.1, -0.3;
  const Eigen::MatrixXd A = mapWith(eig);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(5, 1, 2);
  CHECK(iterate(A, b, 0, 12).error > 1e3);
  // Memory >= dim x: a secant method, exact after dim + 1 steps.
  CHECK(iterate(A, b, 5, 7).error <= 1e-10);
  CHECK(iterate(A, b, 5, 12).error <= 1e-10);
}

TEST_CASE("Anderson mixing with a small memory handles one strongly unstable mode") {
  // The line-contact picture: one lateral mode with a gain of 700 and stable ones.
  Eigen::VectorXd eig(6);
  eig << 700, 0.2, 0.1, -0.1, 0.05, 0;
  const Eigen::MatrixXd A = mapWith(eig);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(6, 1e-3);
  CHECK(iterate(A, b, 0, 4).error > 1e3);
  const Run mixed = iterate(A, b, 2, 12);
  CHECK(mixed.error <= 1e-9);
}

TEST_CASE("Anderson mixing restarts on a new length and falls back to the plain step") {
  AndersonMixer mixer(3);
  const Eigen::VectorXd x = Eigen::VectorXd::Zero(3), g = Eigen::VectorXd::Ones(3);
  CHECK(mixer.next(x, g) == g);  // no history: the plain step
  CHECK(mixer.used() == 0);
  // The same residual again: the difference is zero, rank 0, the plain step.
  CHECK(mixer.next(x, g) == g);
  CHECK(mixer.used() == 0);
  const Eigen::VectorXd g2 = 3 * Eigen::VectorXd::Ones(3);  // residual 2: a new direction
  mixer.next(g, g2);
  CHECK(mixer.used() == 1);
  // Another length: a new problem, the plain step.
  const Eigen::VectorXd y = Eigen::VectorXd::Zero(2), h = Eigen::VectorXd::Ones(2);
  CHECK(mixer.next(y, h) == h);
  CHECK(mixer.used() == 0);
}
