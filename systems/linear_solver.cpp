#include "systems/linear_solver.h"

#include "systems/krylov.h"
#include "systems/mumps_solver.h"
#include "systems/nonzero_pattern.h"
#include "systems/schwarz_preconditioner.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <chrono>

// OpenBLAS's thread count: a process-wide setting (cblas.h of the OpenBLAS package).
extern "C" void openblas_set_num_threads(int);

namespace fibra {
namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

enum class Active { None, Llt, Ldlt, Lu, Umfpack, Krylov, Mumps, MumpsBlr, Schwarz };

// The upper triangle of S = (K + K^T) / 2 (K full, CSC); for a symmetric ls, K itself.
void symmetricPart(const LinearSystem& ls, SparseMatrix& S) {
  if (ls.symmetric) {
    S = ls.K;
    return;
  }
  const SparseMatrix Kt = ls.K.transpose();
  S = (0.5 * (ls.K + Kt)).triangularView<Eigen::Upper>();
}

// The full matrix of a symmetric ls (K stores the upper triangle), else K.
SparseMatrix fullMatrix(const LinearSystem& ls) {
  if (!ls.symmetric) return ls.K;
  return SparseMatrix(ls.K.selfadjointView<Eigen::Upper>());
}

// The factor of the shifted symmetric part, kept across Newton iterations (Krylov strategy).
struct Preconditioner {
  bool lu = false;                // KrylovLu: UMFPACK LU of the full K instead
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  Eigen::UmfPackLU<SparseMatrix> umf;
  SparseMatrix S;                 // upper triangle of the symmetric part, shifted
  Eigen::VectorXd diagonal;       // |S_ii| before the shift
  std::vector<Index> diagonalAt;  // index of S_ii in S.valuePtr()
  Index revision = -1;            // pattern revision analysed
  bool valid = false;             // a factor exists
  bool fresh = false;             // factorised from the K of the current call
  bool stale = false;             // the last solve asks for a refactorisation
  double shift = 0;               // sigma of the factor
};

// Positions of the diagonal entries of an upper-triangular CSC matrix (last of each column).
std::vector<Index> diagonalPositions(const SparseMatrix& S) {
  std::vector<Index> at(S.cols());
  for (Index j = 0; j < S.cols(); ++j) at[j] = S.outerIndexPtr()[j + 1] - 1;
  return at;
}

// CHOLMOD's orderings: its default (nmethods 0: AMD, and METIS too when AMD's fill is heavy)
// for Auto, else that one method.
void orderCholmod(cholmod_common& c, Ordering o) {
  if (o == Ordering::Auto) {
    c.nmethods = 0;
    return;
  }
  c.nmethods = 1;
  c.method[0].ordering = o == Ordering::Metis ? CHOLMOD_METIS : CHOLMOD_AMD;
}

}  // namespace

const char* strategyName(LinearStrategy s) {
  switch (s) {
    case LinearStrategy::Auto: return "auto";
    case LinearStrategy::Direct: return "direct";
    case LinearStrategy::Umfpack: return "umfpack";
    case LinearStrategy::Krylov: return "krylov";
    case LinearStrategy::KrylovLu: return "krylov-lu";
    case LinearStrategy::Mumps: return "mumps";
    case LinearStrategy::Schwarz: return "schwarz";
  }
  return "?";
}

bool parseStrategy(const std::string& name, LinearStrategy& s) {
  for (LinearStrategy c : {LinearStrategy::Auto, LinearStrategy::Direct, LinearStrategy::Umfpack,
                           LinearStrategy::Krylov, LinearStrategy::KrylovLu, LinearStrategy::Mumps,
                           LinearStrategy::Schwarz})
    if (name == strategyName(c)) {
      s = c;
      return true;
    }
  return false;
}

struct LinearSolver::Impl {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt;
  Eigen::UmfPackLU<SparseMatrix> umfpack, umfpackFull;  // Direct's LU; the Umfpack strategy's
  Eigen::SparseLU<SparseMatrix> sparseLu;
  Preconditioner pre;
  MumpsFactor mumps;
  NonzeroPattern pattern;                // the non-zero pattern the factorisations see
  SchwarzPreconditioner schwarz;
  const FibreStore* fibres = nullptr;    // Schwarz: the fibres it follows
  double fill = 0;                       // MUMPS's estimated flops per non-zero of K, last analysis
  int autoChoice = -1;                   // Auto from kMumpsFromEquations, this increment: -1 not
                                         // decided yet, 0 MUMPS, 1 Schwarz (forgetPattern resets)
  GmresWorkspace workspace;
  KrylovSettings krylov;
  double forcing = 0;                    // the solve's forcing term (0: krylov.tolerance)
  LuSolver luKind = LuSolver::EigenSparseLu;
  LinearStrategy strategy = LinearStrategy::Auto;
  Ordering ordering = Ordering::Auto;
  int blasThreads = 0;
  Trace* trace = nullptr;
  Index lltRevision = -1, ldltRevision = -1, luRevision = -1, umfRevision = -1;
  Active active = Active::None;
  const LinearSystem* system = nullptr;  // Krylov: the system whose K the products use
  SparseMatrix full;                     // Umfpack strategy on a symmetric K
  LinearSolveStats stats;

  Impl() {
    pattern.slack = krylov.patternSlack;
    llt.cholmod().print = 0;
    ldlt.cholmod().print = 0;
    pre.llt.cholmod().print = 0;
  }

  template <class Solver>
  bool run(Solver& s, Index& revision, const SparseMatrix& K, Index current) {
    if (revision != current) {
      order(s, K.cols());
      const auto t0 = std::chrono::steady_clock::now();
      s.analyzePattern(K);
      stats.analyse += seconds(t0);
      ++stats.analyses;
      revision = current;
    }
    Span span(trace, "factorise", "solver");
    span.items(K.cols());
    const auto t0 = std::chrono::steady_clock::now();
    s.factorize(K);
    stats.factorise += seconds(t0);
    ++stats.factorisations;
    return s.info() == Eigen::Success;
  }

  // The fill-reducing ordering of the next analysis of s, for n equations.
  void order(Eigen::UmfPackLU<SparseMatrix>& s, Index n) const {
    const bool metis =
        ordering == Ordering::Metis || (ordering == Ordering::Auto && n >= kMetisFromEquations);
    s.umfpackControl()(UMFPACK_ORDERING) = metis ? UMFPACK_ORDERING_METIS : UMFPACK_ORDERING_AMD;
  }
  template <class Cholmod>
  void order(Cholmod& s, Index) const { orderCholmod(s.cholmod(), ordering); }
  void order(Eigen::SparseLU<SparseMatrix>&, Index) const {}  // COLAMD, its own

  bool direct(const LinearSystem& ls, std::string& message);
  bool umfpackLu(const LinearSystem& ls, std::string& message);
  bool factorisePreconditioner(const LinearSystem& ls, std::string& message);
  int reuseLimit() const;
  bool krylovFactorise(const LinearSystem& ls, std::string& message, bool lu);
  void krylovSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  GmresResult gmresOnce(const Eigen::VectorXd& b, Eigen::VectorXd& x, int limit,
                        const LinearOperator& M);
  bool mumpsFactorise(const LinearSystem& ls, std::string& message);
  void mumpsSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  bool schwarzFactorise(const LinearSystem& ls, const LinearSystem& exact, std::string& message);
  void schwarzSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  bool exactMumps(const LinearSystem& ls, std::string& message);
  bool mumpsAnalyse(const LinearSystem& ls, std::string& message);
  bool schwarzPays(const LinearSystem& ls);
  // The GMRES tolerance of the current solve: krylov.tolerance, or the forcing term within
  // [tolerance, forcingMax] when inexact Newton is on.
  double gmresTolerance() const {
    if (!(krylov.forcingMax > 0) || !(forcing > 0)) return krylov.tolerance;
    return std::clamp(forcing, krylov.tolerance, std::max(krylov.tolerance, krylov.forcingMax));
  }
};

bool LinearSolver::Impl::direct(const LinearSystem& ls, std::string& message) {
  if (!ls.symmetric) {
    const bool umf = luKind == LuSolver::Umfpack;
    if (umf ? !run(umfpack, luRevision, ls.K, ls.revision)
            : !run(sparseLu, luRevision, ls.K, ls.revision)) {
      message = umf ? "UMFPACK: singular tangent" : "SparseLU: singular tangent";
      return false;
    }
    active = Active::Lu;
    return true;
  }
  if (run(llt, lltRevision, ls.K, ls.revision)) {
    active = Active::Llt;
    return true;
  }
  ++stats.fallbacks;
  if (!run(ldlt, ldltRevision, ls.K, ls.revision)) {
    message = "CHOLMOD: tangent not positive definite and LDL^T failed (singular)";
    return false;
  }
  message = "tangent not positive definite: solved by LDL^T";
  active = Active::Ldlt;
  return true;
}

bool LinearSolver::Impl::umfpackLu(const LinearSystem& ls, std::string& message) {
  if (ls.symmetric) full = fullMatrix(ls);
  if (!run(umfpackFull, umfRevision, ls.symmetric ? full : ls.K, ls.revision)) {
    message = "UMFPACK: singular tangent";
    return false;
  }
  active = Active::Umfpack;
  return true;
}

// Factorises S + sigma diag(|S_ii|) for sigma = 0 (or a tenth of the last shift), growing by
// 100x up to 1 while CHOLMOD reports it not positive definite.
bool LinearSolver::Impl::factorisePreconditioner(const LinearSystem& ls, std::string& message) {
  if (pre.lu) {
    if (ls.symmetric) full = fullMatrix(ls);
    if (!run(pre.umf, pre.revision, ls.symmetric ? full : ls.K, ls.revision)) {
      pre.valid = false;
      message = "Krylov: UMFPACK preconditioner singular";
      return false;
    }
    pre.valid = pre.fresh = true;
    pre.stale = false;
    return true;
  }
  symmetricPart(ls, pre.S);
  if (pre.revision != ls.revision) {
    pre.diagonalAt = diagonalPositions(pre.S);
    const auto t0 = std::chrono::steady_clock::now();
    orderCholmod(pre.llt.cholmod(), ordering);
    pre.llt.analyzePattern(pre.S);
    stats.analyse += seconds(t0);
    ++stats.analyses;
    pre.revision = ls.revision;
  }
  const Index n = pre.S.cols();
  pre.diagonal.resize(n);
  for (Index i = 0; i < n; ++i) pre.diagonal(i) = std::abs(pre.S.valuePtr()[pre.diagonalAt[i]]);
  double sigma = pre.shift > 0 ? pre.shift / 10 : 0, applied = 0;
  for (;;) {
    for (Index i = 0; i < n; ++i) pre.S.valuePtr()[pre.diagonalAt[i]] += (sigma - applied) * pre.diagonal(i);
    applied = sigma;
    Span span(trace, "factorise", "solver");
    span.items(n);
    const auto t0 = std::chrono::steady_clock::now();
    pre.llt.factorize(pre.S);
    stats.factorise += seconds(t0);
    ++stats.factorisations;
    if (pre.llt.info() == Eigen::Success) break;
    if (sigma >= 1) {
      pre.valid = false;
      message = "Krylov: symmetric part not positive definite even with a shift of 1 diag";
      return false;
    }
    sigma = sigma > 0 ? std::min(1.0, sigma * 100) : 1e-8;
  }
  stats.shifted += sigma > 0;
  stats.shift = pre.shift = sigma;
  pre.valid = pre.fresh = true;
  pre.stale = false;
  return true;
}

bool LinearSolver::Impl::krylovFactorise(const LinearSystem& ls, std::string& message, bool lu) {
  system = &ls;
  if (pre.lu != lu) pre.valid = false, pre.revision = -1, pre.shift = 0, pre.lu = lu;
  if (pre.valid && pre.revision == ls.revision && !pre.stale) {
    pre.fresh = false;
    ++stats.reuses;
    active = Active::Krylov;
    return true;
  }
  if (pre.valid && pre.revision == ls.revision) ++stats.refactorisations;
  if (!factorisePreconditioner(ls, message)) return false;
  active = Active::Krylov;
  return true;
}

// GMRES on the true K of `system`, right-preconditioned by M, at most `limit` iterations.
GmresResult LinearSolver::Impl::gmresOnce(const Eigen::VectorXd& b, Eigen::VectorXd& x, int limit,
                                          const LinearOperator& M) {
  const LinearSystem& ls = *system;
  const LinearOperator A = [&ls](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    if (ls.symmetric)
      y.noalias() = ls.K.selfadjointView<Eigen::Upper>() * v;
    else
      y.noalias() = ls.K * v;
  };
  GmresSettings g;
  g.tolerance = gmresTolerance();
  g.restart = krylov.restart;
  g.maxIterations = limit;
  x.setZero(b.size());
  Span span(trace, "krylov", "solver");
  const GmresResult r = gmres(A, M, b, x, g, workspace);
  span.items(r.iterations);
  stats.krylovIterations += r.iterations;
  stats.maxKrylovIterations = std::max(stats.maxKrylovIterations, r.iterations);
  stats.lastKrylovIterations += r.iterations;
  stats.lastTolerance = g.tolerance;
  stats.lastReached = r.residual;
  return r;
}

// Iterations allowed with a re-used factor: refactorAbove. A count, not a time budget: a
// decision on measured times would make the results depend on the machine's load.
int LinearSolver::Impl::reuseLimit() const { return std::min(krylov.refactorAbove, krylov.maxIterations); }

// With a re-used factor GMRES stops at reuseLimit(): a factor that stale costs more in
// iterations than a new one; the solve is then redone with a fresh factor, up to
// maxIterations.
void LinearSolver::Impl::krylovSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const LinearOperator M = [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    if (pre.lu)
      y = pre.umf.solve(v);
    else
      y = pre.llt.solve(v);
  };
  GmresResult r = gmresOnce(b, x, pre.fresh ? krylov.maxIterations : reuseLimit(), M);
  if (!r.converged && !pre.fresh) {
    std::string message;
    ++stats.refactorisations;
    if (factorisePreconditioner(*system, message)) r = gmresOnce(b, x, krylov.maxIterations, M);
  }
  if (!r.converged) ++stats.krylovFailures;
  if (!r.converged || r.iterations > krylov.refactorAbove) pre.stale = true;
}

// MUMPS: analysis when the pattern revision (or symmetry, ordering, BLR) changes, numeric
// factorisation every call (a factor does not survive a Newton iteration on the contact
// tangents: docs/RESULTS.md "PETSc", re-used factor).
bool LinearSolver::Impl::mumpsFactorise(const LinearSystem& ls, std::string& message) {
  system = &ls;
  const Index n = ls.freeCount;
  if (!mumpsAnalyse(ls, message)) return false;
  Span span(trace, "factorise", "solver");
  span.items(n);
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = mumps.factorise(ls.K, message);
  stats.factorise += seconds(t0);
  ++stats.factorisations;
  if (!ok) return false;
  active = krylov.blrTolerance > 0 ? Active::MumpsBlr : Active::Mumps;
  return true;
}

// MUMPS's analysis of ls.K's pattern, when the pattern revision (or symmetry, ordering, BLR)
// changed since the last one; false with MUMPS's message.
bool LinearSolver::Impl::mumpsAnalyse(const LinearSystem& ls, std::string& message) {
  const Index n = ls.freeCount;
  const MumpsAnalysis how{.symmetric = ls.symmetric, .ordering = ordering,
                          .metisAuto = ordering == Ordering::Auto && n >= kMumpsMetisFromEquations,
                          .blrTolerance = krylov.blrTolerance, .revision = ls.revision,
                          .compact = &ls == &pattern.compact};
  if (mumps.needsAnalysis(how)) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = mumps.analyse(ls.K, how, message);
    stats.analyse += seconds(t0);
    ++stats.analyses;
    fill = ok ? mumps.estimatedFlops() / double(std::max<Index>(ls.K.nonZeros(), 1)) : 0;
    if (!ok) return false;
  }
  stats.flopsPerEntry = fill;
  return true;
}

// Auto's choice between MUMPS and Schwarz (from kMumpsFromEquations equations) by MUMPS's
// analysis of the increment's first pattern (autoTakesSchwarz), kept for the increment's other
// patterns (the analysis would cost Schwarz ~1 s per pattern on bundle37); false also when the
// analysis fails (mumpsFactorise then reports it).
bool LinearSolver::Impl::schwarzPays(const LinearSystem& ls) {
  if (autoChoice >= 0) return autoChoice == 1;
  std::string message;
  if (!fibres || !mumpsAnalyse(ls, message)) return false;
  autoChoice = autoTakesSchwarz(fill, true) ? 1 : 0;
  return autoChoice == 1;
}

// Exact factor: x = (LU)^-1 b. BLR factor: GMRES on the true K to krylov.tolerance, the factor
// as its right preconditioner.
void LinearSolver::Impl::mumpsSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (active == Active::Mumps) {
    x = b;
    mumps.solve(x);
    return;
  }
  const LinearOperator M = [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
    y = v;
    mumps.solve(y);
  };
  if (!gmresOnce(b, x, krylov.maxIterations, M).converged) ++stats.krylovFailures;
}

// MUMPS's exact factor of ls whatever blrTolerance says: the Schwarz strategy's fallback.
bool LinearSolver::Impl::exactMumps(const LinearSystem& ls, std::string& message) {
  const double blr = krylov.blrTolerance;
  krylov.blrTolerance = 0;
  const bool ok = mumpsFactorise(ls, message);
  krylov.blrTolerance = blr;
  return ok;
}

// Builds the two-level preconditioner from ls.K (every call: docs/RESULTS.md "Fibre-block
// preconditioners"); one that cannot be built falls back to MUMPS's exact LU of `exact` (ls's K
// on the non-zero pattern, or ls) for this call, as does a solve that misses its tolerance.
bool LinearSolver::Impl::schwarzFactorise(const LinearSystem& ls, const LinearSystem& exact,
                                          std::string& message) {
  system = &exact;
  if (!fibres) {
    message = "Schwarz: no fibres given to the linear solver (setFibres)";
    return false;
  }
  Span span(trace, "factorise", "solver");
  span.items(ls.freeCount);
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  const bool built = schwarz.build(ls, *fibres, krylov.coarseSegments, why, krylov.coarseRotations);
  stats.factorise += seconds(t0);
  ++stats.factorisations;
  stats.schwarz += schwarz.takeTimes();
  if (built) {
    active = Active::Schwarz;
    return true;
  }
  ++stats.fallbacks;
  return exactMumps(exact, message);
}

// GMRES on the true K preconditioned by the Schwarz levels; a solve that misses the tolerance is
// redone by MUMPS's exact LU of the same K.
void LinearSolver::Impl::schwarzSolve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const LinearOperator A = [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) { schwarz.product(v, y); };
  const LinearOperator M = [this](const Eigen::VectorXd& v, Eigen::VectorXd& y) { schwarz.apply(v, y); };
  GmresSettings g;
  g.tolerance = gmresTolerance();
  g.restart = krylov.restart;
  g.maxIterations = krylov.maxIterations;
  x.setZero(b.size());
  GmresResult r;
  {
    Span span(trace, "krylov", "solver");
    r = gmres(A, M, b, x, g, workspace);
    span.items(r.iterations);
  }
  stats.schwarz += schwarz.takeTimes();
  stats.krylovIterations += r.iterations;
  stats.maxKrylovIterations = std::max(stats.maxKrylovIterations, r.iterations);
  stats.lastKrylovIterations += r.iterations;
  stats.lastTolerance = g.tolerance;
  stats.lastReached = r.residual;
  if (r.converged) return;
  ++stats.krylovFailures;
  if (keepsInexactMiss(g.tolerance, krylov.tolerance, r.residual)) return;
  ++stats.fallbacks;
  std::string message;
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = exactMumps(*system, message);
  stats.factorise += seconds(t0);
  if (!ok) {
    x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN());
    return;
  }
  x = b;
  mumps.solve(x);
}

bool keepsInexactMiss(double asked, double tolerance, double reached) {
  return asked > tolerance && reached <= std::min(kInexactMissBound, 10 * asked);
}

bool autoTakesSchwarz(double flopsPerEntry, bool haveFibres) {
  return haveFibres && flopsPerEntry >= kSchwarzFromFlopsPerEntry;
}

LinearSolver::LinearSolver() : impl_(std::make_unique<Impl>()) {}
LinearSolver::~LinearSolver() = default;

void LinearSolver::setLuSolver(LuSolver lu) {
  if (impl_->luKind != lu) impl_->luRevision = -1;
  impl_->luKind = lu;
}

void LinearSolver::setStrategy(LinearStrategy s) { impl_->strategy = s; }
void LinearSolver::setKrylov(const KrylovSettings& k) {
  Impl& m = *impl_;
  if (m.krylov.patternSlack != k.patternSlack)  // analyse again on the other pattern
    m.lltRevision = m.ldltRevision = m.luRevision = m.umfRevision = m.pre.revision = -1;
  m.krylov = k;
  m.pattern.slack = k.patternSlack;
}
void LinearSolver::setOrdering(Ordering o) {
  Impl& m = *impl_;
  if (m.ordering != o)  // analyse again with the new ordering
    m.lltRevision = m.ldltRevision = m.luRevision = m.umfRevision = m.pre.revision = -1;
  m.ordering = o;
}
void LinearSolver::setBlasThreads(int threads) { impl_->blasThreads = threads; }
void LinearSolver::setTrace(Trace* trace) { impl_->trace = trace; }
void LinearSolver::setFibres(const FibreStore* fibres) { impl_->fibres = fibres; }
LinearStrategy LinearSolver::strategy() const { return impl_->strategy; }

LinearStrategy LinearSolver::resolved(Index n) const {
  if (impl_->strategy != LinearStrategy::Auto) return impl_->strategy;
  return n < kMumpsFromEquations ? LinearStrategy::Direct : LinearStrategy::Mumps;
}

bool LinearSolver::factorise(const LinearSystem& ls, std::string& message) {
  Impl& m = *impl_;
  if (m.blasThreads > 0) openblas_set_num_threads(m.blasThreads);
  m.active = Active::None;
  const bool automatic = m.strategy == LinearStrategy::Auto;
  const LinearStrategy s = resolved(ls.freeCount);
  // every strategy but Schwarz (which drops the zeros itself) factorises K on its non-zeros
  const int patterns = m.pattern.patterns;
  const auto t0 = std::chrono::steady_clock::now();
  const LinearSystem& kc = s == LinearStrategy::Schwarz ? ls : updateNonzeroPattern(ls, m.pattern);
  m.stats.pattern += seconds(t0);
  m.stats.patterns += m.pattern.patterns - patterns;
  m.stats.patternEntries = kc.K.nonZeros();
  switch (s) {
    case LinearStrategy::Umfpack: return m.umfpackLu(kc, message);
    case LinearStrategy::Mumps:
      // auto: a tangent MUMPS cannot factorise (reported singular, out of memory) falls back to
      // the direct path (as UMFPACK's singular reports on the 250-fibre yarn did,
      // docs/RESULTS.md). With a heavy fill auto takes Schwarz instead (schwarzPays).
      if (automatic && m.schwarzPays(kc)) {
        ++m.stats.schwarzChoices;
        return m.schwarzFactorise(ls, kc, message);
      }
      if (m.mumpsFactorise(kc, message) || !automatic) return m.active != Active::None;
      ++m.stats.fallbacks;
      message.clear();
      return m.direct(kc, message);
    case LinearStrategy::Krylov: return m.krylovFactorise(kc, message, false);
    case LinearStrategy::KrylovLu: return m.krylovFactorise(kc, message, true);
    case LinearStrategy::Schwarz: return m.schwarzFactorise(ls, ls, message);
    default: return m.direct(kc, message);
  }
}

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) { solve(b, x, 0.0); }

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double forcing) {
  Impl& m = *impl_;
  m.forcing = forcing;
  m.stats.lastKrylovIterations = 0;
  m.stats.lastTolerance = m.stats.lastReached = 0;
  if (m.blasThreads > 0) openblas_set_num_threads(m.blasThreads);
  Span span(m.trace, "solve", "solver");
  span.items(1);
  const auto t0 = std::chrono::steady_clock::now();
  switch (m.active) {
    case Active::Llt: x = m.llt.solve(b); break;
    case Active::Ldlt: x = m.ldlt.solve(b); break;
    case Active::Lu:
      if (m.luKind == LuSolver::Umfpack)
        x = m.umfpack.solve(b);
      else
        x = m.sparseLu.solve(b);
      break;
    case Active::Umfpack: x = m.umfpackFull.solve(b); break;
    case Active::Krylov: m.krylovSolve(b, x); break;
    case Active::Mumps:
    case Active::MumpsBlr: m.mumpsSolve(b, x); break;
    case Active::Schwarz: m.schwarzSolve(b, x); break;
    case Active::None: x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN()); break;
  }
  m.stats.solve += seconds(t0);
  ++m.stats.solves;
}

const LinearSolveStats& LinearSolver::stats() const { return impl_->stats; }
void LinearSolver::resetStats() { impl_->stats = LinearSolveStats{}; }
void LinearSolver::forgetPattern() {
  impl_->pattern.storedRevision = -1;
  impl_->autoChoice = -1;
  impl_->schwarz.forgetChoice();
}

}  // namespace fibra
