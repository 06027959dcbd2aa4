#include "systems/schwarz_preconditioner.h"

#include <Eigen/Geometry>
#include <Eigen/UmfPackSupport>
#include <tbb/parallel_for.h>

#include <chrono>
#include <utility>

// LAPACK's banded LU (OpenBLAS ships LAPACK): factor and solve, Fortran calling convention.
extern "C" {
void dgbtrf_(const int* m, const int* n, const int* kl, const int* ku, double* ab, const int* ldab,
             int* ipiv, int* info);
void dgbtrs_(const char* trans, const int* n, const int* kl, const int* ku, const int* nrhs,
             const double* ab, const int* ldab, const int* ipiv, double* b, const int* ldb,
             int* info, std::size_t transLength);
}

namespace fibra {
namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One fibre's diagonal block in LAPACK band storage (kl = ku = band; ldab = 3 band + 1;
// A(i, j) at ab[(2 band + i - j) + j ldab]), with its LU and pivots after dgbtrf.
struct FibreBlock {
  Index first = 0;  // first equation
  int n = 0;        // equations of the fibre (0: all held)
  int band = 0;
  std::vector<double> ab;
  std::vector<int> pivots;
};

// The column blocks `parts` (each `rows` rows, compressed) side by side as one matrix.
void joinColumns(const std::vector<SparseMatrix>& parts, Index rows, SparseMatrix& out) {
  Index nnz = 0, cols = 0;
  for (const SparseMatrix& p : parts) nnz += p.nonZeros(), cols += p.cols();
  out.resize(rows, cols);
  out.resizeNonZeros(nnz);
  Index at = 0, column = 0;
  for (const SparseMatrix& p : parts)
    for (Index j = 0; j < p.cols(); ++j, ++column) {
      out.outerIndexPtr()[column] = int(at);
      for (SparseMatrix::InnerIterator it(p, j); it; ++it, ++at)
        out.innerIndexPtr()[at] = int(it.row()), out.valuePtr()[at] = it.value();
    }
  out.outerIndexPtr()[cols] = int(at);
}

// The prune predicate: keep the entries that are not exactly 0.
bool nonZero(Index, Index, double v) { return v != 0; }

// out = A without the entries that are exactly 0 (one pass, the order of the rest kept).
void withoutZeros(const SparseMatrix& A, SparseMatrix& out) {
  Index nnz = 0;
  for (Index k = 0; k < A.nonZeros(); ++k) nnz += A.valuePtr()[k] != 0;
  out.resize(A.rows(), A.cols());
  out.resizeNonZeros(nnz);
  Index at = 0;
  for (Index j = 0; j < A.outerSize(); ++j) {
    out.outerIndexPtr()[j] = int(at);
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.value() != 0) out.innerIndexPtr()[at] = int(it.row()), out.valuePtr()[at++] = it.value();
  }
  out.outerIndexPtr()[A.outerSize()] = int(at);
}

}  // namespace

struct SchwarzPreconditioner::Impl {
  const LinearSystem* ls = nullptr;
  // K in full storage without its explicit zeros: the pattern keeps every candidate contact
  // element, and most of them carry no stiffness (77% of the entries of the 250-fibre yarn's
  // first tangents are exact zeros); dropping them changes no product
  SparseMatrix Kn;
  std::vector<FibreBlock> blocks;    // per fibre
  SparseMatrix Phi, Ac;              // coarse basis (equations x coarse unknowns), Phi^T K Phi
  SparseMatrix KPhi;                 // K Phi (equations x coarse unknowns), kept for apply()
  Index perFibre = 0;                // coarse unknowns per fibre (Phi's columns of a fibre)
  Eigen::UmfPackLU<SparseMatrix> coarse;
  std::vector<int> acOuter, acInner;  // the pattern of Ac that `coarse` analysed
  mutable SchwarzTimes times;  // apply() adds its own

  const SparseMatrix& K() const { return Kn; }
  bool factoriseBlocks(const FibreStore& fibres, std::string& message);
  void basis(const FibreStore& fibres, int segments);
  void coarseMatrix();
  bool factoriseCoarse(std::string& message);
  void applyBlocks(Eigen::VectorXd& y) const;
};

// Equation ranges and band LUs of every fibre's block.
bool SchwarzPreconditioner::Impl::factoriseBlocks(const FibreStore& fibres, std::string& message) {
  const Index nf = fibres.fibres();
  blocks.assign(size_t(nf), {});
  for (Index f = 0; f < nf; ++f) {
    FibreBlock& b = blocks[size_t(f)];
    const Index d0 = kNodeDofs * fibres.firstNode[f], d1 = d0 + kNodeDofs * fibres.nodeCount[f];
    Index first = -1, last = -1;
    for (Index d = d0; d < d1; ++d)
      if (ls->equation[d] >= 0) last = ls->equation[d], first = first < 0 ? last : first;
    b.first = std::max<Index>(first, 0);
    b.n = first < 0 ? 0 : int(last - first + 1);
    b.band = std::min(b.n - 1, kNodeDofs * (fibres.order[f] + 1) - 1);
  }
  const SparseMatrix& A = K();
  std::vector<int> failed(size_t(nf), 0);
  tbb::parallel_for(Index(0), nf, [&](Index f) {
    FibreBlock& b = blocks[size_t(f)];
    if (b.n == 0) return;
    const int ld = 3 * b.band + 1;
    b.ab.assign(size_t(ld) * size_t(b.n), 0.0);
    b.pivots.resize(size_t(b.n));
    for (int j = 0; j < b.n; ++j)
      for (SparseMatrix::InnerIterator it(A, b.first + j); it; ++it) {
        const Index i = it.row() - b.first;
        if (i >= 0 && i < b.n && std::abs(i - j) <= b.band)
          b.ab[size_t(2 * b.band + i - j) + size_t(j) * size_t(ld)] = it.value();
      }
    int info = 0;
    dgbtrf_(&b.n, &b.n, &b.band, &b.band, b.ab.data(), &ld, b.pivots.data(), &info);
    failed[size_t(f)] = info != 0;
  });
  for (Index f = 0; f < nf; ++f)
    if (failed[size_t(f)]) {
      message = "Schwarz: the block of fibre " + fibres.name[size_t(f)] + " is singular";
      return false;
    }
  return true;
}

// Phi of the header: per fibre, hats over `segments` pieces of its node index, times the three
// translations of x0 and the three rotations of the directors, without explicit zeros (A_c's
// pattern follows K's non-zero values anyway, and is analysed again when it changes).
void SchwarzPreconditioner::Impl::basis(const FibreStore& fibres, int segments) {
  std::vector<Eigen::Triplet<double>> t;
  const Index columnsPerFibre = perFibre = Index(segments + 1) * 6;
  for (Index f = 0; f < fibres.fibres(); ++f) {
    const Index nodes = fibres.nodeCount[f];
    for (Index k = 0; k < nodes; ++k) {
      const Index node = fibres.firstNode[f] + k;
      const double at = double(k) * segments / double(nodes - 1);
      const Vec3 g[2] = {g1Of(fibres.q, node), g2Of(fibres.q, node)};
      for (int c = std::max(0, int(at)); c <= std::min(segments, int(at) + 1); ++c) {
        const double phi = 1 - std::abs(at - c);
        if (!(phi > 0)) continue;
        const Index column = f * columnsPerFibre + Index(c) * 6;
        auto add = [&](int dof, Index col, double v) {
          const Index e = ls->equation[kNodeDofs * node + dof];
          if (e >= 0) t.emplace_back(e, col, v);
        };
        for (int i = 0; i < 3; ++i) {
          add(i, column + i, phi);
          for (int a = 0; a < 2; ++a) {
            const Vec3 dg = Vec3::Unit(i).cross(g[a]) * phi;
            for (int r = 0; r < 3; ++r) add(3 + 3 * a + r, column + 3 + i, dg(r));
          }
        }
      }
    }
  }
  Phi.resize(ls->freeCount, fibres.fibres() * columnsPerFibre);
  Phi.setFromTriplets(t.begin(), t.end());
  Phi.prune(nonZero);
}

// A_c = Phi^T K Phi, one fibre's coarse columns at a time (tbb over the fibres: Phi's columns
// of fibre f are contiguous, so A_c's columns are the blocks Phi^T (K Phi_f) side by side, each
// computed on its own: bitwise the same for any thread count). A coarse unknown whose column of
// Phi is empty (all its DOFs held) gets 1 on the diagonal.
void SchwarzPreconditioner::Impl::coarseMatrix() {
  const SparseMatrix& A = K();
  const SparseMatrix PhiT = Phi.transpose();
  const Index nc = Phi.cols(), per = perFibre;
  std::vector<SparseMatrix> parts(size_t(nc / per)), kphi(parts.size());
  tbb::parallel_for(size_t(0), parts.size(), [&](size_t f) {
    kphi[f] = A * Phi.middleCols(Index(f) * per, per);
    parts[f] = PhiT * kphi[f];
  });
  joinColumns(kphi, A.rows(), KPhi);
  joinColumns(parts, nc, Ac);
  Ac.prune(nonZero);  // Phi's explicit zeros give zeros
  for (Index j = 0; j < nc; ++j)
    if (Phi.outerIndexPtr()[j + 1] == Phi.outerIndexPtr()[j]) Ac.coeffRef(j, j) = 1;
  Ac.makeCompressed();
}

// A_c's LU; UMFPACK's pattern analysis is redone only when A_c's pattern changes.
bool SchwarzPreconditioner::Impl::factoriseCoarse(std::string& message) {
  auto t0 = std::chrono::steady_clock::now();
  coarseMatrix();
  times.coarseMatrix += since(t0);
  const std::vector<int> outer(Ac.outerIndexPtr(), Ac.outerIndexPtr() + Ac.cols() + 1),
      inner(Ac.innerIndexPtr(), Ac.innerIndexPtr() + Ac.nonZeros());
  if (outer != acOuter || inner != acInner) {
    coarse.umfpackControl()(UMFPACK_IRSTEP) = 0;  // a preconditioner: no iterative refinement
    t0 = std::chrono::steady_clock::now();
    coarse.analyzePattern(Ac);
    times.coarseAnalyse += since(t0);
    acOuter = outer, acInner = inner;
  }
  coarse.factorize(Ac);
  if (coarse.info() != Eigen::Success) {
    message = "Schwarz: the coarse matrix is singular";
    return false;
  }
  return true;
}

// y = B^-1 y, fibre by fibre.
void SchwarzPreconditioner::Impl::applyBlocks(Eigen::VectorXd& y) const {
  tbb::parallel_for(size_t(0), blocks.size(), [&](size_t f) {
    const FibreBlock& b = blocks[f];
    if (b.n == 0) return;
    const int ld = 3 * b.band + 1, one = 1;
    int info = 0;
    dgbtrs_("N", &b.n, &b.band, &b.band, &one, b.ab.data(), &ld, b.pivots.data(),
            y.data() + b.first, &b.n, &info, 1);
  });
}

SchwarzPreconditioner::SchwarzPreconditioner() : impl_(std::make_unique<Impl>()) {}
SchwarzPreconditioner::~SchwarzPreconditioner() = default;

bool SchwarzPreconditioner::build(const LinearSystem& ls, const FibreStore& fibres, int segments,
                                  std::string& message) {
  Impl& m = *impl_;
  m.ls = &ls;
  if (ls.symmetric) {
    m.Kn = ls.K.selfadjointView<Eigen::Upper>();
    m.Kn.prune(nonZero);
  } else {
    withoutZeros(ls.K, m.Kn);
  }
  auto t0 = std::chrono::steady_clock::now();
  const bool blocks = m.factoriseBlocks(fibres, message);
  m.times.local += since(t0);
  if (!blocks) return false;
  t0 = std::chrono::steady_clock::now();
  m.basis(fibres, std::max(1, segments));
  m.times.coarseMatrix += since(t0);
  const bool coarse = m.factoriseCoarse(message);
  m.times.coarse += since(t0);
  return coarse;
}

void SchwarzPreconditioner::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  const Impl& m = *impl_;
  auto t0 = std::chrono::steady_clock::now();
  const Eigen::VectorXd z = m.coarse.solve(Eigen::VectorXd(m.Phi.transpose() * v));
  auto t1 = std::chrono::steady_clock::now();
  y.noalias() = v - m.KPhi * z;  // K y_c with y_c = Phi z
  auto t2 = std::chrono::steady_clock::now();
  m.applyBlocks(y);
  auto t3 = std::chrono::steady_clock::now();
  y.noalias() += m.Phi * z;
  using S = std::chrono::duration<double>;
  ++m.times.applications;
  m.times.coarseSolve += S(t1 - t0).count(), m.times.product += S(t2 - t1).count();
  m.times.blockSolve += S(t3 - t2).count();
}

void SchwarzPreconditioner::product(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  const auto t0 = std::chrono::steady_clock::now();
  y.noalias() = impl_->K() * v;
  impl_->times.operatorProduct += since(t0);
}

SchwarzTimes SchwarzPreconditioner::takeTimes() { return std::exchange(impl_->times, {}); }

}  // namespace fibra
