// The Schwarz preconditioner (systems/schwarz_preconditioner.h) on a squeezed 7-fibre bundle's
// tangents: bitwise the same in 1 and 2 threads, GMRES converges with it and not without it, a
// miss falls back to MUMPS; its two levels apply what a dense reference written from the header
// does (frictional, frictionless, symmetric in upper storage; with more coarse pieces than node
// intervals); K's explicit zeros change nothing, and a preconditioner built again and again on
// other tangents (its storage kept) applies as a fresh one.
#include "linear_fixtures.h"
#include "systems/krylov.h"
#include "systems/schwarz_preconditioner.h"

#include <doctest/doctest.h>

#include <tbb/task_arena.h>

using namespace fibra;
using namespace fibra::linear_fixtures;

TEST_CASE("the Schwarz strategy: its preconditioner alone, bitwise across thread counts, and its fallback") {
  auto w = squeezedBundle(0.1);
  const LinearSystem& ls = w->system;
  const Eigen::VectorXd b = randomVector(ls.freeCount, 11);
  // The preconditioner applied in arenas of 1 and 2 threads: the fibre blocks write disjoint
  // equations, so the result is bitwise the same.
  std::vector<Eigen::VectorXd> y(2);
  for (int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      SchwarzPreconditioner p;
      std::string message;
      REQUIRE(p.build(ls, w->fibres, 8, message));
      p.apply(b, y[size_t(threads - 1)]);
    });
  }
  CHECK(y[0] == y[1]);
  // More pieces than a fibre has node intervals (50 on fibres of 21 nodes) is not a singular
  // coarse level (two hats would share their only node): solved by GMRES, no fallback.
  LinearSolver fine;
  fine.setKrylov({.coarseSegments = 50});
  CHECK(solveWith(LinearStrategy::Schwarz, ls, b, fine, &w->fibres) <= KrylovSettings{}.tolerance);
  CHECK(fine.stats().fallbacks == 0);
  CHECK(fine.stats().krylovIterations > 1);
  // The preconditioner does the work: with it GMRES(40) reaches 1e-8 in under 100 iterations,
  // without it (M = I) not in 200.
  LinearSolver solver;
  CHECK(solveWith(LinearStrategy::Schwarz, ls, b, solver, &w->fibres) <= KrylovSettings{}.tolerance);
  CHECK(solver.stats().fallbacks == 0);
  CHECK(solver.stats().maxKrylovIterations < 100);
  MESSAGE("Schwarz: " << solver.stats().maxKrylovIterations << " GMRES iterations");
  const SparseMatrix K = ls.symmetric ? SparseMatrix(ls.K.selfadjointView<Eigen::Upper>()) : ls.K;
  const LinearOperator A = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = K * v; };
  const LinearOperator identity = [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; };
  Eigen::VectorXd x;
  GmresWorkspace ws;
  CHECK_FALSE(gmres(A, identity, b, x, {.tolerance = 1e-8, .restart = 40, .maxIterations = 200}, ws).converged);
  // GMRES allowed a single iteration cannot reach the tolerance: the solve falls back to MUMPS's
  // exact LU of the same K, counted, and is still solved.
  LinearSolver limited;
  limited.setKrylov({.maxIterations = 1});
  CHECK(solveWith(LinearStrategy::Schwarz, ls, b, limited, &w->fibres) <= 1e-10);
  CHECK(limited.stats().krylovFailures == 1);
  CHECK(limited.stats().fallbacks == 1);
  // Without the fibres the strategy says so.
  LinearSolver blind;
  blind.setStrategy(LinearStrategy::Schwarz);
  std::string message;
  CHECK_FALSE(blind.factorise(ls, message));
  CHECK(message.find("no fibres") != std::string::npos);
}

// The header's two levels written out densely and independently of the class: Phi from its
// hats and rigid motions, A_c = Phi^T K Phi (1 on the diagonal of an empty column), each fibre's
// block restricted to its band and solved by a dense LU; y = y_c + B^-1 (v - K y_c),
// y_c = Phi A_c^-1 Phi^T v. Without rotations their columns of Phi stay empty.
Eigen::VectorXd denseSchwarz(const LinearSystem& ls, const FibreStore& fs, int segments,
                             const Eigen::VectorXd& v, bool rotations = true) {
  const Eigen::MatrixXd K(ls.symmetric ? SparseMatrix(ls.K.selfadjointView<Eigen::Upper>()) : ls.K);
  const Index per = 6 * (segments + 1), n = ls.freeCount;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(n, fs.fibres() * per);
  for (Index f = 0; f < fs.fibres(); ++f)
    for (Index k = 0; k < fs.nodeCount[f]; ++k) {
      const Index node = fs.firstNode[f] + k;
      const auto eq = [&](int dof) { return ls.equation[size_t(kNodeDofs * node + dof)]; };
      const Index pieces = std::min<Index>(segments, fs.nodeCount[f] - 1);  // hats beyond: empty
      for (int c = 0; c <= pieces; ++c) {
        const double phi = std::max(0.0, 1 - std::abs(double(k) * pieces / double(fs.nodeCount[f] - 1) - c));
        for (int i = 0; i < 3; ++i) {
          const Index col = f * per + 6 * c;
          if (eq(i) >= 0) Phi(eq(i), col + i) = phi;
          for (int a = 0; a < 2 && rotations; ++a) {
            const Vec3 g = fs.q.segment<3>(kNodeDofs * node + 3 + 3 * a);
            const Vec3 dg = Vec3::Unit(i).cross(g) * phi;
            for (int r = 0; r < 3; ++r)
              if (eq(3 + 3 * a + r) >= 0) Phi(eq(3 + 3 * a + r), col + 3 + i) = dg(r);
          }
        }
      }
    }
  Eigen::MatrixXd Ac = Phi.transpose() * K * Phi;
  for (Index j = 0; j < Ac.cols(); ++j)
    if (Phi.col(j).squaredNorm() == 0) Ac(j, j) = 1;
  const Eigen::VectorXd yc = Phi * Ac.partialPivLu().solve(Phi.transpose() * v);
  Eigen::VectorXd rest = v - K * yc, y = yc;
  for (Index f = 0; f < fs.fibres(); ++f) {
    Index first = -1, last = -1;
    for (Index d = kNodeDofs * fs.firstNode[f]; d < kNodeDofs * (fs.firstNode[f] + fs.nodeCount[f]); ++d)
      if (ls.equation[size_t(d)] >= 0) last = ls.equation[size_t(d)], first = first < 0 ? last : first;
    if (first < 0) continue;
    const Index m = last - first + 1, band = std::min<Index>(m - 1, kNodeDofs * (fs.order[f] + 1) - 1);
    Eigen::MatrixXd B = K.block(first, first, m, m);
    for (Index i = 0; i < m; ++i)
      for (Index j = 0; j < m; ++j)
        if (std::abs(i - j) > band) B(i, j) = 0;
    y.segment(first, m) += B.partialPivLu().solve(rest.segment(first, m));
  }
  return y;
}

TEST_CASE("the Schwarz preconditioner applies the two levels of its header (dense reference)") {
  // Fixed normals and no friction: K symmetric, kept as its upper triangle.
  using enum NormalUpdate;
  for (const auto& [mu, update] : {std::pair(0.0, Loop), std::pair(0.0, Newton), std::pair(0.1, Newton)}) {
    CAPTURE(mu);
    auto w = squeezedBundle(mu, update);
    const LinearSystem& ls = w->system;
    CHECK(ls.symmetric == (update == Loop));
    const Eigen::VectorXd v = randomVector(ls.freeCount, 5);
    // 50 pieces on fibres of 21 nodes: 20 pieces, the hats beyond empty
    for (int segments : {1, 4, 50}) {
      CAPTURE(segments);
      SchwarzPreconditioner p;
      std::string message;
      REQUIRE(p.build(ls, w->fibres, segments, message));
      Eigen::VectorXd y;
      p.apply(v, y);
      const Eigen::VectorXd ref = denseSchwarz(ls, w->fibres, segments, v);
      MESSAGE("relative difference " << (y - ref).norm() / ref.norm());
      CHECK((y - ref).norm() <= 1e-9 * ref.norm());
      // the coarse level without the rotations: their columns empty
      REQUIRE(p.build(ls, w->fibres, segments, message, CoarseRotations::Off));
      CHECK_FALSE(p.rotations());
      p.apply(v, y);
      const Eigen::VectorXd translations = denseSchwarz(ls, w->fibres, segments, v, false);
      CHECK((y - translations).norm() <= 1e-9 * translations.norm());
      // the rotations change y by far more than the tolerance above
      CHECK((translations - ref).norm() > 1e-6 * ref.norm());
    }
  }
}

TEST_CASE("the Schwarz coarse level on fibres of different lengths (dense reference)") {
  // The centre fibre has 3 elements (7 nodes), the others 10 (21 nodes): 50 pieces are 20 for the
  // long fibres and 6 for the short one, whose hats beyond stay empty.
  auto w = squeezedBundle(0.1, NormalUpdate::Newton, 3);
  REQUIRE(w->fibres.nodeCount[0] == 7);
  REQUIRE(w->fibres.nodeCount[1] == 21);
  const LinearSystem& ls = w->system;
  const Eigen::VectorXd v = randomVector(ls.freeCount, 3);
  for (int segments : {4, 10, 50}) {
    CAPTURE(segments);
    for (CoarseRotations r : {CoarseRotations::On, CoarseRotations::Off}) {
      SchwarzPreconditioner p;
      std::string message;
      REQUIRE(p.build(ls, w->fibres, segments, message, r));
      Eigen::VectorXd y;
      p.apply(v, y);
      const Eigen::VectorXd ref = denseSchwarz(ls, w->fibres, segments, v, r == CoarseRotations::On);
      CHECK((y - ref).norm() <= 1e-9 * ref.norm());
    }
  }
}

TEST_CASE("the Schwarz coarse rotations: auto keeps them where A_c is cheap, off still solves") {
  auto w = squeezedBundle(0.1);
  const LinearSystem& ls = w->system;
  const Eigen::VectorXd v = randomVector(ls.freeCount, 9);
  SchwarzPreconditioner on, automatic;
  std::string message;
  REQUIRE(on.build(ls, w->fibres, 8, message, CoarseRotations::On));
  REQUIRE(automatic.build(ls, w->fibres, 8, message, CoarseRotations::Auto));
  // the rule of the header, with MUMPS's own estimate: far below the threshold on 7 fibres
  CHECK(automatic.coarseFlops() > 0);
  const double perNonzero = automatic.coarseFlops() / double(ls.K.nonZeros());
  MESSAGE("A_c: " << perNonzero << " flops per stored entry of K");
  CHECK(perNonzero < kRotationsUpToFlopsPerNonzero);
  CHECK(automatic.rotations());
  Eigen::VectorXd a, b;
  on.apply(v, a), automatic.apply(v, b);
  CHECK(a == b);
  // The rotations help GMRES here; without them it still solves, with more iterations.
  LinearSolver with, without;
  with.setKrylov({.coarseRotations = CoarseRotations::On});
  without.setKrylov({.coarseRotations = CoarseRotations::Off});
  CHECK(solveWith(LinearStrategy::Schwarz, ls, v, with, &w->fibres) <= KrylovSettings{}.tolerance);
  CHECK(solveWith(LinearStrategy::Schwarz, ls, v, without, &w->fibres) <= KrylovSettings{}.tolerance);
  CHECK(with.stats().fallbacks + without.stats().fallbacks == 0);
  CHECK(without.stats().schwarz.withoutRotations == without.stats().schwarz.builds);
  CHECK(with.stats().schwarz.withoutRotations == 0);
  MESSAGE("GMRES iterations with rotations " << with.stats().krylovIterations << ", without "
                                             << without.stats().krylovIterations);
  CHECK(with.stats().krylovIterations < without.stats().krylovIterations);
}

TEST_CASE("the Schwarz preconditioner ignores K's explicit zeros and times its applications") {
  auto w = squeezedBundle(0.1);
  const LinearSystem& ls = w->system;
  // explicit zeros on top of the tangent's own: every entry (i, i + 40) stored with value 0
  LinearSystem padded = withExplicitZeros(ls);
  Index zeros = 0;
  for (Index k = 0; k < padded.K.nonZeros(); ++k) zeros += padded.K.valuePtr()[k] == 0;
  REQUIRE(zeros > ls.freeCount / 2);
  const Eigen::VectorXd v = randomVector(ls.freeCount, 7);
  Eigen::VectorXd y[2], Kv[2];
  for (int k = 0; k < 2; ++k) {
    SchwarzPreconditioner p;
    std::string message;
    REQUIRE(p.build(k == 0 ? ls : padded, w->fibres, 4, message));
    p.apply(v, y[k]);
    p.apply(v, y[k]);
    p.product(v, Kv[k]);
    const SchwarzTimes times = p.takeTimes();
    CHECK(times.applications == 2);
    CHECK(times.coarseSolve > 0);
    CHECK(times.blockSolve > 0);
    CHECK(times.local + times.coarse > 0);
  }
  // the same products and the same A_c pattern, hence the same factors: bitwise equal
  CHECK((Kv[0] - Kv[1]).lpNorm<Eigen::Infinity>() == 0);
  CHECK((y[0] - y[1]).lpNorm<Eigen::Infinity>() == 0);
  // One preconditioner built again and again on other tangents (its storage is kept and grows,
  // core/sparse_room.h; frictionless with fixed normals: K symmetric, in upper storage): each
  // build applies and multiplies as a fresh one does.
  auto frictionless = squeezedBundle(0, NormalUpdate::Loop);
  const LinearSystem& sym = frictionless->system;
  REQUIRE(sym.symmetric);
  SchwarzPreconditioner again;
  std::string message;
  for (const LinearSystem* system : {&sym, static_cast<const LinearSystem*>(&padded), &ls, &sym}) {
    const FibreStore& fibres = system == &sym ? frictionless->fibres : w->fibres;
    SchwarzPreconditioner fresh;
    REQUIRE(fresh.build(*system, fibres, 4, message));
    REQUIRE(again.build(*system, fibres, 4, message));
    Eigen::VectorXd y0, y1, Kv0, Kv1;
    fresh.apply(v, y0), again.apply(v, y1);
    fresh.product(v, Kv0), again.product(v, Kv1);
    CHECK(y1 == y0);
    CHECK(Kv1 == Kv0);
  }
}
