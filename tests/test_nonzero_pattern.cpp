// The non-zero pattern (systems/nonzero_pattern.h): the compact K holds K's non-zeros and its
// diagonal with K's values; the pattern is kept while it holds every non-zero within its slack,
// grown by union when new non-zeros appear, rebuilt when it is too empty, carried over by
// coordinates when K's stored pattern changes, restarted on request; off (slack 0) it is K
// itself. Through the linear solver: a K padded with explicit
// zeros is factorised on the same compact matrix as K (bitwise the same solution with every
// exact strategy), the pattern's revision drives the analyses, and slack 0 solves the stored
// pattern to the same accuracy.
#include "bench/contact_scenes.h"
#include "linear_fixtures.h"
#include "engine/world_state.h"
#include "systems/linear_solver.h"
#include "systems/nonzero_pattern.h"

#include <doctest/doctest.h>


using namespace fibra;
using fibra::linear_fixtures::randomVector;
using fibra::linear_fixtures::withExplicitZeros;

namespace {

// A 6 x 6 non-symmetric K on a stored pattern of the diagonal, the first super- and
// sub-diagonals and a band (i, i + 3) held as explicit zeros; K(2, 2) stored as 0.
LinearSystem bandSystem() {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 6; ++i) {
    t.emplace_back(i, i, i == 2 ? 0.0 : 4.0 + i);
    if (i + 1 < 6) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -0.5);
    if (i + 3 < 6) t.emplace_back(i, i + 3, 0.0);
  }
  LinearSystem ls;
  ls.freeCount = 6;
  ls.symmetric = false;
  ls.K.resize(6, 6);
  ls.K.setFromTriplets(t.begin(), t.end());
  ls.revision = 3;
  return ls;
}

// The stored value of K(i, j) (which must be stored).
double& entry(SparseMatrix& K, int i, int j) { return K.coeffRef(i, j); }

}  // namespace

TEST_CASE("the non-zero pattern holds K's non-zeros and diagonal, and follows the slack rule") {
  LinearSystem ls = bandSystem();
  REQUIRE(ls.K.nonZeros() == 6 + 10 + 3);
  NonzeroPattern p;
  SUBCASE("off: K itself") {
    CHECK(&updateNonzeroPattern(ls, p) == &ls);
    CHECK(p.passes == 0);
  }
  p.slack = 1.5;
  const LinearSystem& c = updateNonzeroPattern(ls, p);
  REQUIRE(&c == &p.compact);
  // the band of zeros dropped; the zero diagonal K(2, 2) kept
  CHECK(c.K.nonZeros() == 16);
  CHECK(c.K.coeff(2, 2) == 0);
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));
  CHECK(c.freeCount == 6);
  CHECK_FALSE(c.symmetric);
  const Index first = c.revision;
  CHECK(p.patterns == 1);

  // the same non-zeros with other values: the same pattern, the new values
  ls.K *= 2;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first);
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));

  // a non-zero where the stored pattern held a zero: a new pattern, the union
  entry(ls.K, 0, 3) = 7;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 1);
  CHECK(c.K.nonZeros() == 17);
  CHECK(c.K.coeff(0, 3) == 7);

  // back to 0: the pattern (17 entries, 16 needed) is kept within the slack, holding the zero
  entry(ls.K, 0, 3) = 0;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 1);
  CHECK(c.K.nonZeros() == 17);
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));

  // the off-diagonals zeroed: 17 entries for the 6 needed is beyond 1.5 x; rebuilt
  for (int i = 0; i + 1 < 6; ++i) entry(ls.K, i, i + 1) = entry(ls.K, i + 1, i) = 0;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 2);
  CHECK(c.K.nonZeros() == 6);

  // told to start afresh (LinearSolver::forgetPattern): K's needed entries again
  entry(ls.K, 0, 3) = 0;
  p.storedRevision = -1;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 3);
  CHECK(c.K.nonZeros() == 6);

  // a new revision of the stored pattern: P (the 6 diagonal entries) carried over, then the
  // union with the 10 new non-zeros
  ls = bandSystem();
  ls.revision = 4;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 4);
  CHECK(c.K.nonZeros() == 16);
  CHECK(p.patterns == 5);
  CHECK(p.passes == 7);
  // another stored revision with the same non-zeros: P carried over whole, the same revision
  ls.revision = 5;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 4);
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));
  // a stored pattern without K(0, 1) (and without the zeros): P loses it, a new revision
  entry(ls.K, 0, 1) = 0;
  ls.K.prune([](Index, Index, double v) { return v != 0; });
  ls.revision = 6;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 5);
  CHECK(c.K.nonZeros() == 14);  // K(2, 2), no longer stored, is not in P either
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));
  CHECK(p.patterns == 6);
  // the same entries stored in another order within column 0 (rows 1, 0): the same matrix, but
  // other arrays for the factorisations, so a new revision
  REQUIRE(ls.K.outerIndexPtr()[1] - ls.K.outerIndexPtr()[0] == 2);
  std::swap(ls.K.innerIndexPtr()[0], ls.K.innerIndexPtr()[1]);
  std::swap(ls.K.valuePtr()[0], ls.K.valuePtr()[1]);
  ls.revision = 7;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == first + 6);
  CHECK(c.K.nonZeros() == 14);
  CHECK(c.K.innerIndexPtr()[0] == 1);
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));
}

TEST_CASE("the union grows the pattern only within the slack, else it is rebuilt from K's non-zeros") {
  LinearSystem ls = bandSystem();
  NonzeroPattern p;
  p.slack = 1.05;  // 16 needed: at most 16.8 entries
  const LinearSystem& c = updateNonzeroPattern(ls, p);
  entry(ls.K, 0, 3) = 1;  // 17 needed, the union of 17 within 1.05 x 17 = 17.85: the union
  updateNonzeroPattern(ls, p);
  CHECK(c.K.nonZeros() == 17);
  entry(ls.K, 0, 3) = 0, entry(ls.K, 1, 4) = 1;  // a union of 18 > 17.85: rebuilt, 17 entries
  const Index before = c.revision;
  updateNonzeroPattern(ls, p);
  CHECK(c.revision == before + 1);
  CHECK(c.K.nonZeros() == 17);
  CHECK(c.K.coeff(1, 4) == 1);
  CHECK(Eigen::MatrixXd(c.K) == Eigen::MatrixXd(ls.K));
}

TEST_CASE("the exact strategies factorise a K padded with explicit zeros as K itself") {
  auto w = std::make_unique<WorldState>();
  w->scene = scenes::bundle(1, 10, 0.01, 5e-4, 0.1);
  w->def.threads = 1;
  buildWorld(*w);
  REQUIRE(advance(*w).status == StepStatus::Converged);
  const LinearSystem& ls = w->system;
  // every entry (i, i + 40) stored with value 0 on top of the tangent's own zeros
  LinearSystem padded = withExplicitZeros(ls);
  ++padded.revision;
  REQUIRE(padded.K.nonZeros() > ls.K.nonZeros() + ls.freeCount / 2);
  const Eigen::VectorXd b = randomVector(ls.freeCount, 11);
  const auto residual = [&](const Eigen::VectorXd& x) { return (ls.K * x - b).norm() / b.norm(); };
  for (LinearStrategy s : {LinearStrategy::Direct, LinearStrategy::Umfpack, LinearStrategy::Mumps,
                           LinearStrategy::KrylovLu}) {
    const std::string name = strategyName(s);
    CAPTURE(name);
    Eigen::VectorXd x[3];
    long entries[3];
    for (int k = 0; k < 3; ++k) {
      LinearSolver solver;
      solver.setStrategy(s);
      if (k == 2) solver.setKrylov({.patternSlack = 0});  // the stored pattern, zeros included
      std::string message;
      REQUIRE(solver.factorise(k == 0 ? ls : padded, message));
      solver.solve(b, x[k]);
      entries[k] = solver.stats().patternEntries;
      // once more with the same values: no new pattern, no new analysis
      REQUIRE(solver.factorise(k == 0 ? ls : padded, message));
      CHECK(solver.stats().analyses == 1);
      CHECK(solver.stats().patterns == (k == 2 ? 0 : 1));
    }
    CHECK(entries[0] == entries[1]);
    CHECK(entries[0] < ls.K.nonZeros() + 1);
    CHECK(entries[2] == padded.K.nonZeros());
    // the same compact matrix: bitwise the same solution
    CHECK((x[0] - x[1]).lpNorm<Eigen::Infinity>() == 0);
    // on the stored pattern: another ordering, the same solution to the strategy's accuracy
    CHECK(residual(x[1]) <= KrylovSettings{}.tolerance);
    CHECK(residual(x[2]) <= KrylovSettings{}.tolerance);
  }
}
