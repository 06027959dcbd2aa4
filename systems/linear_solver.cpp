#include "systems/linear_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <chrono>

// OpenBLAS's thread count: a process-wide setting (cblas.h of the OpenBLAS package).
extern "C" void openblas_set_num_threads(int);

namespace fibra {
namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

enum class Active { None, Llt, Ldlt, Lu };

}  // namespace

struct LinearSolver::Impl {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt;
  Eigen::UmfPackLU<SparseMatrix> umfpack;
  Eigen::SparseLU<SparseMatrix> sparseLu;
  LuSolver luKind = LuSolver::EigenSparseLu;
  int blasThreads = 0;
  Index lltRevision = -1, ldltRevision = -1, luRevision = -1;
  Active active = Active::None;
  LinearSolveStats stats;

  Impl() {
    llt.cholmod().print = 0;
    ldlt.cholmod().print = 0;
  }

  template <class Solver>
  bool run(Solver& s, Index& revision, const SparseMatrix& K, Index current) {
    if (revision != current) {
      const auto t0 = std::chrono::steady_clock::now();
      s.analyzePattern(K);
      stats.analyse += seconds(t0);
      ++stats.analyses;
      revision = current;
    }
    const auto t0 = std::chrono::steady_clock::now();
    s.factorize(K);
    stats.factorise += seconds(t0);
    ++stats.factorisations;
    return s.info() == Eigen::Success;
  }
};

LinearSolver::LinearSolver() : impl_(std::make_unique<Impl>()) {}
LinearSolver::~LinearSolver() = default;

void LinearSolver::setLuSolver(LuSolver lu) {
  if (impl_->luKind != lu) impl_->luRevision = -1;
  impl_->luKind = lu;
}

void LinearSolver::setBlasThreads(int threads) { impl_->blasThreads = threads; }

bool LinearSolver::factorise(const LinearSystem& ls, std::string& message) {
  Impl& m = *impl_;
  if (m.blasThreads > 0) openblas_set_num_threads(m.blasThreads);
  m.active = Active::None;
  if (!ls.symmetric) {
    const bool umfpack = m.luKind == LuSolver::Umfpack;
    if (umfpack ? !m.run(m.umfpack, m.luRevision, ls.K, ls.revision)
                : !m.run(m.sparseLu, m.luRevision, ls.K, ls.revision)) {
      message = umfpack ? "UMFPACK: singular tangent" : "SparseLU: singular tangent";
      return false;
    }
    m.active = Active::Lu;
    return true;
  }
  if (m.run(m.llt, m.lltRevision, ls.K, ls.revision)) {
    m.active = Active::Llt;
    return true;
  }
  ++m.stats.fallbacks;
  if (!m.run(m.ldlt, m.ldltRevision, ls.K, ls.revision)) {
    message = "CHOLMOD: tangent not positive definite and LDL^T failed (singular)";
    return false;
  }
  message = "tangent not positive definite: solved by LDL^T";
  m.active = Active::Ldlt;
  return true;
}

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& m = *impl_;
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
    case Active::None: x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN()); break;
  }
  m.stats.solve += seconds(t0);
}

const LinearSolveStats& LinearSolver::stats() const { return impl_->stats; }

}  // namespace fibra
