// Schwarz preconditioner: a two-level preconditioner of the contact tangent that follows the
// fibres, for the `schwarz` strategy of systems/linear_solver.h (GMRES on the true K, right-
// preconditioned by it; docs/RESULTS.md "Fibre-block preconditioners" has the measurements that
// chose its form).
//
// Reads  LinearSystem (K: full, or the upper triangle of a symmetric K; the equation numbering,
//        in which a fibre's free DOFs are contiguous), FibreStore (node ranges, current x0, g1,
//        g2 for the coarse basis).
// Writes its own factors (no shared state).
// Computes
//   local level B: per fibre f, the banded LU (LAPACK dgbtrf, partial pivoting) of its diagonal
//     block K_ff restricted to the band of one element (|i - j| < 9 (order + 1) equations);
//     couplings outside it (other fibres, self-contact) act only through the products with K.
//   coarse level: Phi, per fibre and per hat function phi_c of the node index k over `segments`
//     pieces (c = 0..segments, phi_c(k) = max(0, 1 - |k segments / (n - 1) - c|); on a fibre of
//     n <= segments nodes, n - 1 pieces and the hats beyond empty; `segments` above every
//     fibre's node intervals is taken as the largest count of them), six columns:
//     the translations dx0 = e_i phi_c and the rotations of the section dg_a = (e_i x g_a) phi_c
//     (i = 1..3), the rotations' columns left empty when they are off; A_c = Phi^T K Phi, LU by
//     MUMPS (sequential, METIS nested dissection; its pattern analysed again whenever A_c's
//     non-zeros move). An empty column of Phi (DOFs held, rotations off, hats beyond the node
//     count) puts 1 on A_c's diagonal.
//     Rotations (CoarseRotations): Auto keeps them unless MUMPS's analysis estimates A_c's
//     factorisation at more than kRotationsUpToFlopsPerNonzero flops per non-zero of K; the
//     choice is made at the first build after forgetChoice() (each increment) and kept until
//     the next. Measured (docs/RESULTS.md "The fabric's coarse level"): on the 480-fibre fabric
//     A_c with rotations costs 9.3e10 flops (1 200 per non-zero of K) and the rotations save no
//     GMRES iteration; on a 37-fibre bundle they cut GMRES iterations 3.5x for a cheap A_c; the
//     250-fibre yarn's A_c costs 3e8-1e9 flops, and Auto keeps the rotations there.
//     K Phi and A_c are formed fibre by fibre from Phi's rows (a fibre's columns of Phi have
//     its own equations for rows): (K Phi)(:, l) = sum_j K(:, j) Phi(j, l) over the fibre's
//     equations j, A_c(:, l) = sum_i Phi(i, :)^T (K Phi)(i, l), in sparse accumulators kept
//     per thread (3.3x faster than Eigen's sparse products on a 37-fibre bundle, docs/RESULTS.md
//     "Storage kept between Newton iterations").
//   apply: z = A_c^-1 Phi^T v, y_c = Phi z;  y = y_c + B^-1 (v - (K Phi) z)   (multiplicative
//     two-level; K Phi is kept from forming A_c).
//   Storage (K without zeros, Phi, K Phi, A_c, the accumulators) is kept from build to build
//   and grows only when it must (core/sparse_room.h).
//   Every product uses K without its explicit zeros: K's fixed pattern holds every candidate
//   contact element of the proximity zones, and most carry no stiffness (77% of the entries of
//   the 250-fibre yarn's first tangents are exact zeros); dropping them costs one pass over K
//   and changes no product, but A_c's LU, formed on the padded pattern, cost 0.63 s against
//   0.05 s on 13 500 unknowns (docs/RESULTS.md "Explicit zeros").
// Without the coarse level nothing converges on dense bundles (the contact couples the fibres at
// every wavelength along them); 8 segments on fibres of 15 elements took 150-171 GMRES
// iterations where 15 took 69-70.
// Threading (tbb::parallel_for in the caller's arena), bitwise the same for any thread count:
// the fibre blocks are factorised and applied in parallel, each writing only its own fibre's
// equations; A_c and K Phi are formed fibre by fibre, each fibre's columns summed in a fixed
// order by one thread (its accumulator's, whichever thread that is). The coarse LU, its solves and the products K v
// are sequential. A parallel product was measured twice and lost: by rows from a copy of K made
// at each build (bundle37, docs/RESULTS.md "Inexact Newton"), and by ranges of rows of K's own
// columns on the 480-fibre fabric (0.074 s per product on 2 threads against 0.039 s for the
// sequential one: the product is bound by memory, and each thread reads every column's indices).
// Errors: build() returns false with a message when a fibre block is singular or MUMPS fails on
// A_c (singular, out of memory).
#pragma once

#include "components/fibres.h"
#include "components/linear_system.h"
#include "components/solver_settings.h"

#include <memory>
#include <string>

namespace fibra {

// Auto's rule for the coarse rotations (header): kept while MUMPS estimates A_c's factorisation
// at no more than this many flops per non-zero of K (the 250-fibre yarn: kept, A_c at 3e8-1e9
// flops; the 480-fibre fabric: 1 200, left out).
inline constexpr double kRotationsUpToFlopsPerNonzero = 600;

// Seconds spent by the preconditioner, accumulated until taken (takeTimes).
struct SchwarzTimes {
  double local = 0, coarse = 0;  // builds: the fibre blocks, the coarse level
  double coarseMatrix = 0, coarseAnalyse = 0;  // of `coarse`: Phi and A_c; A_c's pattern analysis
  // apply() calls: their count and the s spent in the coarse solve (Phi^T v, A_c^-1, Phi z),
  // the product K y_c and the fibre blocks' solves; product(): the operator's K v
  int applications = 0;
  double coarseSolve = 0, product = 0, blockSolve = 0;
  double operatorProduct = 0;
  int builds = 0, withoutRotations = 0;  // builds, and those whose coarse level had no rotations
  SchwarzTimes& operator+=(const SchwarzTimes& o) {
    builds += o.builds, withoutRotations += o.withoutRotations;
    local += o.local, coarse += o.coarse, coarseMatrix += o.coarseMatrix;
    coarseAnalyse += o.coarseAnalyse, applications += o.applications;
    coarseSolve += o.coarseSolve, product += o.product, blockSolve += o.blockSolve;
    operatorProduct += o.operatorProduct;
    return *this;
  }
};

class SchwarzPreconditioner {
 public:
  SchwarzPreconditioner();
  ~SchwarzPreconditioner();
  SchwarzPreconditioner(const SchwarzPreconditioner&) = delete;
  SchwarzPreconditioner& operator=(const SchwarzPreconditioner&) = delete;

  // Builds both levels from ls.K and the fibres' current state; segments >= 1. Keeps a pointer
  // to ls (its K is used by apply()): it must stay alive and unchanged until the next build.
  // rotations: the coarse rotations (Auto: by the rule of the header).
  bool build(const LinearSystem& ls, const FibreStore& fibres, int segments, std::string& message,
             CoarseRotations rotations = CoarseRotations::On);
  // Forgets Auto's choice of the coarse rotations: the next build makes it again.
  void forgetChoice();
  // Whether the last build's coarse level carried the rotations, and MUMPS's estimate of the
  // flops of A_c's factorisation at its last analysis (with the rotations, where Auto chose).
  bool rotations() const;
  double coarseFlops() const;
  // y = M^-1 v (free equations).
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;
  // y = K v with the K of the last build (full or upper-triangle storage).
  void product(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;
  // The times accumulated since the last call (by build, apply and product), which restart at 0.
  SchwarzTimes takeTimes();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fibra
