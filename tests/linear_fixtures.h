// Fixtures of the linear-solver tests (test_linear_strategies.cpp,
// test_schwarz_preconditioner.cpp): a squeezed 7-fibre bundle's tangent, seeded right-hand
// sides, and a solve checked with the full K.
#pragma once

#include "bench/contact_scenes.h"
#include "engine/world_state.h"
#include "systems/linear_solver.h"

#include <doctest/doctest.h>

#include <memory>
#include <random>
#include <string>

namespace fibra::linear_fixtures {

// A 7-fibre bundle after its first converged squeeze increment, with the tangent Newton last
// assembled (at the converged state).
// firstElements > 0: the first fibre (the centre one) gets that many elements, the others 10.
inline std::unique_ptr<WorldState> squeezedBundle(double mu, NormalUpdate update = NormalUpdate::Newton,
                                                  int firstElements = 0) {
  auto w = std::make_unique<WorldState>();
  w->scene = scenes::bundle(1, 10, 0.01, 5e-4, mu);
  w->scene.contact.normalUpdate = update;
  if (firstElements > 0) w->scene.fibres[0].elements = firstElements;
  w->def.threads = 1;
  buildWorld(*w);
  REQUIRE(advance(*w).status == StepStatus::Converged);
  return w;
}

inline Eigen::VectorXd randomVector(Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd b(n);
  for (Index i = 0; i < n; ++i) b(i) = u(rng);
  return b;
}

// |K x - b| / |b| with the full K.
inline double residualOf(const LinearSystem& ls, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  const Eigen::VectorXd Kx = ls.symmetric ? Eigen::VectorXd(ls.K.selfadjointView<Eigen::Upper>() * x)
                                          : Eigen::VectorXd(ls.K * x);
  return (Kx - b).norm() / b.norm();
}

// Solves ls with strategy s (Schwarz: following `fibres`); returns |K x - b| / |b|.
inline double solveWith(LinearStrategy s, const LinearSystem& ls, const Eigen::VectorXd& b,
                 LinearSolver& solver, const FibreStore* fibres = nullptr) {
  solver.setStrategy(s);
  solver.setFibres(fibres);
  std::string message;
  REQUIRE(solver.factorise(ls, message));
  Eigen::VectorXd x;
  solver.solve(b, x);
  return residualOf(ls, x, b);
}

// ls with every entry (i, i + 40) of K stored as an explicit zero, on top of K's own entries.
inline LinearSystem withExplicitZeros(const LinearSystem& ls) {
  std::vector<Eigen::Triplet<double>> t;
  for (Index j = 0; j < ls.K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(ls.K, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (Index i = 0; i + 40 < ls.freeCount; ++i) t.emplace_back(i, i + 40, 0.0);
  LinearSystem padded = ls;
  padded.K.setFromTriplets(t.begin(), t.end());
  return padded;
}

}  // namespace fibra::linear_fixtures
