// MUMPS factor: one sequential MUMPS 5.5 instance (Debian's libmumps-seq, no MPI) holding the
// factor of a sparse n x n matrix A, for the `mumps` strategy of systems/linear_solver.h.
//
// Reads  A in CSC (free DOFs): the full matrix (LU, MUMPS sym = 0), or the upper triangle of a
//        symmetric one (LDL^T, sym = 2: general symmetric, indefinite allowed).
// Writes its own MUMPS state (DMUMPS_STRUC_C, created in the constructor with job = -1,
//        destroyed in the destructor with job = -2; no global state), the 1-based COO
//        triplets (irn, jcn, a) MUMPS reads: irn/jcn built once per pattern, a refilled every
//        factorisation.
// Computes
//   analyse:   the fill-reducing ordering and symbolic factorisation of A's pattern (job 1).
//              Orderings (ICNTL(7)): AMD (0), or METIS nested dissection of the pattern of
//              A + A^T computed by CHOLMOD (cholmod_metis; Debian's MUMPS is built without
//              METIS) and given to MUMPS as the pivot order (1). MUMPS's automatic choice is not
//              offered: it may pick Scotch, whose threads order differently from run to run.
//              With blrTolerance eps > 0 the factor is block low-rank (ICNTL(35) = 2,
//              CNTL(7) = eps: off-diagonal blocks of the fronts compressed to relative accuracy
//              eps), an approximate factor: A ~ L U with |A - L U| ~ eps |A|.
//   factorise: the numeric LU (or LDL^T) of A's values (job 2); out of workspace (INFOG(1) = -9)
//              is retried once with ICNTL(14), the workspace margin in percent, raised 4x.
//   solve:     x = (L U)^-1 b in place (job 3), one dense right-hand side.
// Errors (INFOG(1) < 0) return false with "MUMPS error <code>: <meaning>". MUMPS's printing is
// off (ICNTL(1..4)).
// Determinism: sequential MUMPS (no OpenMP in Debian's build) is deterministic for a given
// input once its one source of chance, Scotch's partition of the BLR clusters, runs on one
// thread with a fixed seed (the Scotch wrappers at the end of mumps_solver.cpp, which also
// initialise the graph MUMPS 5.5 leaves uninitialised); its dense kernels are OpenBLAS's,
// bitwise reproducible for a fixed OpenBLAS thread count. Across thread counts OpenBLAS may
// split sums differently (not guaranteed bitwise).
#pragma once

#include "components/linear_system.h"
#include "components/solver_settings.h"

#include <memory>
#include <string>

namespace fibra {

// How one MUMPS factor is analysed: these (and the pattern revision) decide re-analysis.
struct MumpsAnalysis {
  bool symmetric = false;     // A given as its upper triangle, factorised as LDL^T
  Ordering ordering = Ordering::Auto;
  bool metisAuto = false;     // Ordering::Auto resolved to METIS (else AMD)
  double blrTolerance = 0;    // 0: exact factor; > 0: BLR at that relative accuracy
  Index revision = -1;        // pattern revision of A
  bool compact = false;       // A is the non-zero pattern's matrix (systems/nonzero_pattern.h),
                              // `revision` that pattern's own
  bool operator==(const MumpsAnalysis&) const = default;
};

class MumpsFactor {
 public:
  MumpsFactor();
  ~MumpsFactor();
  MumpsFactor(const MumpsFactor&) = delete;
  MumpsFactor& operator=(const MumpsFactor&) = delete;

  // True when A's pattern must be (re-)analysed for `how`.
  bool needsAnalysis(const MumpsAnalysis& how) const;
  // Analyses A's pattern for `how`; false with a message on a MUMPS error.
  bool analyse(const SparseMatrix& A, const MumpsAnalysis& how, std::string& message);
  // Factorises A's values (A: the pattern last analysed); false with a message (singular, out
  // of memory after the retry, ...).
  bool factorise(const SparseMatrix& A, std::string& message);
  // x := A^-1 x with the factor (approximate with BLR); after a successful factorise.
  void solve(Eigen::VectorXd& x);
  // MUMPS's INFOG(7): the ordering it used in the last analysis (0 AMD, 1 given, 2 AMF,
  // 3 SCOTCH, 4 PORD, 5 METIS, 6 QAMD).
  int orderingUsed() const;
  // MUMPS's RINFOG(1): the floating-point operations its last analysis estimates the
  // elimination (the numeric factorisation) will take; 0 before any analysis.
  double estimatedFlops() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "MUMPS error <code>: <meaning>" for MUMPS's INFOG(1) = code < 0 (and INFOG(2) = detail).
std::string mumpsErrorMessage(int code, int detail);

}  // namespace fibra
