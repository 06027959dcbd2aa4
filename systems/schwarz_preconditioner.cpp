#include "systems/schwarz_preconditioner.h"

#include "core/sparse_room.h"
#include "systems/mumps_solver.h"

#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

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

// out = A without the entries that are exactly 0 (one pass, the order of the rest kept).
void withoutZeros(const SparseMatrix& A, SparseMatrix& out) {
  Index nnz = 0;
  for (Index k = 0; k < A.nonZeros(); ++k) nnz += A.valuePtr()[k] != 0;
  roomFor(out, A.rows(), A.cols(), nnz);
  Index at = 0;
  for (Index j = 0; j < A.outerSize(); ++j) {
    out.outerIndexPtr()[j] = int(at);
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.value() != 0) out.innerIndexPtr()[at] = int(it.row()), out.valuePtr()[at++] = it.value();
  }
  out.outerIndexPtr()[A.outerSize()] = int(at);
}

// out = the full matrix whose upper triangle U holds (upper storage, as LinearSystem keeps a
// symmetric K), without its zeros; rows ascending in each column. `cursor`: scratch.
void fullWithoutZeros(const SparseMatrix& U, SparseMatrix& out, std::vector<int>& cursor) {
  const Index n = U.cols();
  cursor.assign(size_t(n) + 1, 0);  // first: the entries of each column
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(U, j); it; ++it)
      if (it.value() != 0 && it.row() <= j) ++cursor[size_t(j)], cursor[size_t(it.row())] += it.row() < j;
  Index nnz = 0;
  for (Index j = 0; j < n; ++j) nnz += cursor[size_t(j)];
  roomFor(out, n, n, nnz);
  int* outer = out.outerIndexPtr();
  outer[0] = 0;
  for (Index j = 0; j < n; ++j) outer[j + 1] = outer[j] + cursor[size_t(j)];
  // column j: its upper part (rows <= j, ascending), then the mirrored rows > j in column order
  for (Index j = 0; j < n; ++j) {
    int at = outer[j];
    for (SparseMatrix::InnerIterator it(U, j); it; ++it)
      if (it.value() != 0 && it.row() <= j) out.innerIndexPtr()[at] = int(it.row()), out.valuePtr()[at++] = it.value();
    cursor[size_t(j)] = at;
  }
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(U, j); it; ++it)
      if (it.value() != 0 && it.row() < j) {
        int& at = cursor[size_t(it.row())];
        out.innerIndexPtr()[at] = int(j), out.valuePtr()[at++] = it.value();
      }
}

// One fibre's coarse columns, compressed: per column l (of `per`) its rows and values in
// rows/values[start[l] .. start[l + 1]). Kept per fibre from build to build.
struct Columns {
  std::vector<int> start, rows;
  std::vector<double> values;
};

// A sparse accumulator of rows, each `width` wide: the slot of row i, the rows in use and
// their sums (slot-major). Kept per thread.
struct Accumulator {
  std::vector<int> slot;       // per row: its slot, -1 when unused
  std::vector<int> used;       // rows in use, in the order they came
  std::vector<double> sums;    // width per slot
  int width = 0;

  void prepare(Index rows, int w) {
    if (Index(slot.size()) != rows) slot.assign(size_t(rows), -1);
    width = w;
  }
  double* row(int i) {
    int& s = slot[size_t(i)];
    if (s < 0) {
      s = int(used.size());
      used.push_back(i);
      if (sums.size() < used.size() * size_t(width)) sums.resize(2 * used.size() * size_t(width));
      std::fill_n(sums.begin() + std::ptrdiff_t(s) * width, width, 0.0);
    }
    return sums.data() + std::ptrdiff_t(s) * width;
  }
  // The used rows in ascending order (their sums keep their slots).
  void sortUsed() { std::sort(used.begin(), used.end()); }
  // out's columns l = 0..width-1: the non-zero sums of the used rows, ascending; then empty.
  void emit(Columns& out) {
    out.start.assign(size_t(width) + 1, 0);
    out.rows.clear(), out.values.clear();
    for (int l = 0; l < width; ++l) {
      for (int i : used) {
        const double v = sums[size_t(slot[size_t(i)]) * size_t(width) + size_t(l)];
        if (v != 0) out.rows.push_back(i), out.values.push_back(v);
      }
      out.start[size_t(l) + 1] = int(out.rows.size());
    }
    for (int i : used) slot[size_t(i)] = -1;
    used.clear();
  }
};

struct Scratch {
  Accumulator kphi, coarse;  // rows of K Phi (equations); rows of A_c (coarse unknowns)
};

// The blocks `parts` (each `per` columns of `rows` rows) side by side as one compressed matrix
// `out` (rows x parts * per); a column l of part f with `unit[f * per + l]` gets 1 on its diagonal.
void joinColumns(const std::vector<Columns>& parts, Index rows, Index per,
                 const std::vector<char>* unit, SparseMatrix& out) {
  Index nnz = 0;
  for (const Columns& p : parts) nnz += Index(p.rows.size());
  if (unit) nnz += std::count(unit->begin(), unit->end(), char(1));
  roomFor(out, rows, Index(parts.size()) * per, nnz);
  Index at = 0, column = 0;
  for (const Columns& p : parts)
    for (Index l = 0; l < per; ++l, ++column) {
      out.outerIndexPtr()[column] = int(at);
      if (unit && (*unit)[size_t(column)]) {
        out.innerIndexPtr()[at] = int(column), out.valuePtr()[at++] = 1;
        continue;
      }
      for (int k = p.start[size_t(l)]; k < p.start[size_t(l) + 1]; ++k, ++at)
        out.innerIndexPtr()[at] = p.rows[size_t(k)], out.valuePtr()[at] = p.values[size_t(k)];
    }
  out.outerIndexPtr()[column] = int(at);
}

}  // namespace

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

struct SchwarzPreconditioner::Impl {
  const LinearSystem* ls = nullptr;
  // K in full storage without its explicit zeros: the pattern keeps every candidate contact
  // element, and most of them carry no stiffness (77% of the entries of the 250-fibre yarn's
  // first tangents are exact zeros); dropping them changes no product
  SparseMatrix Kn;
  std::vector<FibreBlock> blocks;    // per fibre
  RowMajorMatrix Phi;                // coarse basis (equations x coarse unknowns), by rows
  std::vector<char> emptyColumn;     // per coarse unknown: Phi's column is empty (DOFs held)
  SparseMatrix Ac;                   // Phi^T K Phi
  SparseMatrix KPhi;                 // K Phi (equations x coarse unknowns), kept for apply()
  Index perFibre = 0;                // coarse unknowns per fibre (Phi's columns of a fibre)
  std::vector<Columns> kphiParts, acParts;  // per fibre: its columns of K Phi and of A_c
  tbb::enumerable_thread_specific<Scratch> scratch;
  mutable MumpsFactor coarse;        // A_c's LU (its solve is not const)
  Index coarseRevision = 0;          // A_c's pattern revision, for MumpsAnalysis
  double coarseFlops = 0;            // MUMPS's estimate at the last analysis
  std::vector<int> acOuter, acInner;  // the pattern of Ac that `coarse` analysed
  int rotationsChosen = -1;          // Auto's choice: -1 not made, 0 off, 1 on
  bool rotations = true;             // the last build's
  std::vector<int> cursor;           // scratch of copyOperator
  mutable SchwarzTimes times;  // apply() adds its own

  void copyOperator(const LinearSystem& system);
  const SparseMatrix& K() const { return Kn; }
  bool factoriseBlocks(const FibreStore& fibres, std::string& message);
  void basis(const FibreStore& fibres, int segments, bool withRotations);
  void coarseColumns(Index f, Index first, Index n, Scratch& s);
  void coarseMatrix();
  bool analyseCoarse(std::string& message);
  bool coarseLevel(const FibreStore& fibres, int segments, CoarseRotations wanted,
                   std::string& message);
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

// Phi of the header, row by row (an equation's row: per hat c over its node, the translation
// column of its x0 component, or the two rotation columns whose e_i x g_a has its component),
// without zeros; per fibre, hats over `segments` pieces of its node index (at most its nodes
// less one), times the three translations of x0 and (withRotations) the three rotations of the
// directors.
void SchwarzPreconditioner::Impl::basis(const FibreStore& fibres, int segments,
                                        bool withRotations) {
  const Index per = perFibre = Index(segments + 1) * 6, n = ls->freeCount;
  const Index nc = fibres.fibres() * per;
  // Per node at most 2 hats x (3 translation + 6 x 2 rotation entries).
  Index most = 0;
  for (Index f = 0; f < fibres.fibres(); ++f) most += 30 * fibres.nodeCount[f];
  roomFor(Phi, n, nc, most);
  emptyColumn.assign(size_t(nc), 1);
  std::pair<int, double> entries[3];  // of one hat in one equation's row
  Index at = 0;
  for (Index e = 0; e < n; ++e) {  // rows in equation order (numberEquations: DOF order)
    const Index dof = ls->dofOf[size_t(e)], node = dof / kNodeDofs;
    const Index f = fibres.nodeFibre[size_t(node)], k = node - fibres.firstNode[f];
    const int d = int(dof % kNodeDofs);
    // at most one piece per element interval of nodes: with more, two hats could share their
    // only node and A_c would be singular; the fibre's hats beyond stay empty (unit diagonal)
    const int pieces = int(std::min<Index>(segments, fibres.nodeCount[f] - 1));
    const double s = double(k) * pieces / double(fibres.nodeCount[f] - 1);
    Phi.outerIndexPtr()[e] = int(at);
    for (int c = std::max(0, int(s)); c <= std::min(pieces, int(s) + 1); ++c) {
      const double phi = 1 - std::abs(s - c);
      if (!(phi > 0)) continue;
      const Index column = f * per + Index(c) * 6;
      int count = 0;
      if (d < 3) {
        entries[count++] = {int(column + d), phi};
      } else if (withRotations) {  // component r of director a: (e_i x g_a)_r for the rotations i != r
        const Vec3 g = d < 6 ? g1Of(fibres.q, node) : g2Of(fibres.q, node);
        const int r = (d - 3) % 3;
        for (int i = 0; i < 3; ++i) {
          const double v = Vec3::Unit(i).cross(g)(r) * phi;
          if (v != 0) entries[count++] = {int(column + 3 + i), v};
        }
      }
      for (int m = 0; m < count; ++m) {
        Phi.innerIndexPtr()[at] = entries[m].first, Phi.valuePtr()[at++] = entries[m].second;
        emptyColumn[size_t(entries[m].first)] = 0;
      }
    }
  }
  Phi.outerIndexPtr()[n] = int(at);
  Phi.resizeNonZeros(at);
}

// Fibre f's columns of K Phi and A_c = Phi^T K Phi (its equations first .. first + n - 1, which
// are the rows of its columns of Phi): (K Phi)(i, l) = sum_j K(i, j) Phi(j, l) over its
// equations j in order, then A_c(a, l) = sum_i Phi(i, a) (K Phi)(i, l) over the rows i of K Phi
// in ascending order. Sequential within the fibre: the same sums for any thread count.
void SchwarzPreconditioner::Impl::coarseColumns(Index f, Index first, Index n, Scratch& s) {
  const int per = int(perFibre);
  const Index base = f * perFibre;
  s.kphi.prepare(Kn.rows(), per);
  s.coarse.prepare(Phi.cols(), per);
  for (Index j = first; j < first + n; ++j)
    for (RowMajorMatrix::InnerIterator p(Phi, j); p; ++p) {
      const int l = int(p.col() - base);
      for (SparseMatrix::InnerIterator k(Kn, j); k; ++k) s.kphi.row(int(k.row()))[l] += k.value() * p.value();
    }
  s.kphi.sortUsed();
  for (int i : s.kphi.used) {
    const double* kp = s.kphi.sums.data() + size_t(s.kphi.slot[size_t(i)]) * size_t(per);
    for (RowMajorMatrix::InnerIterator p(Phi, i); p; ++p) {
      double* a = s.coarse.row(int(p.col()));
      for (int l = 0; l < per; ++l) a[l] += p.value() * kp[l];
    }
  }
  s.coarse.sortUsed();
  s.kphi.emit(kphiParts[size_t(f)]);
  s.coarse.emit(acParts[size_t(f)]);
}

// A_c and K Phi, fibre by fibre (tbb over the fibres: each computes its own columns,
// coarseColumns), then joined. A coarse unknown whose column of Phi is empty (all its DOFs held)
// gets 1 on the diagonal.
void SchwarzPreconditioner::Impl::coarseMatrix() {
  const Index nf = Index(blocks.size());
  kphiParts.resize(size_t(nf)), acParts.resize(size_t(nf));
  tbb::parallel_for(Index(0), nf, [&](Index f) {
    const FibreBlock& b = blocks[size_t(f)];
    coarseColumns(f, b.first, b.n, scratch.local());
  });
  joinColumns(kphiParts, Kn.rows(), perFibre, nullptr, KPhi);
  joinColumns(acParts, Phi.cols(), perFibre, &emptyColumn, Ac);
}

// A_c's pattern analysis by MUMPS, redone only when A_c's pattern changes.
bool SchwarzPreconditioner::Impl::analyseCoarse(std::string& message) {
  const int* outer = Ac.outerIndexPtr();
  const int* inner = Ac.innerIndexPtr();
  const size_t cols = size_t(Ac.cols()), nnz = size_t(Ac.nonZeros());
  if (acOuter.size() == cols + 1 && acInner.size() == nnz &&
      std::equal(outer, outer + cols + 1, acOuter.begin()) &&
      std::equal(inner, inner + nnz, acInner.begin()))
    return true;
  const auto t0 = std::chrono::steady_clock::now();
  MumpsAnalysis how;
  how.ordering = Ordering::Metis;
  how.revision = ++coarseRevision;
  acOuter.clear();  // analysed nothing, should MUMPS fail
  if (!coarse.analyse(Ac, how, message)) return false;
  times.coarseAnalyse += since(t0);
  coarseFlops = coarse.estimatedFlops();
  acOuter.assign(outer, outer + cols + 1), acInner.assign(inner, inner + nnz);
  return true;
}

// Phi, A_c and A_c's LU, with the rotations as `wanted` (Auto: the header's rule, the choice
// made at the first build after forgetChoice).
bool SchwarzPreconditioner::Impl::coarseLevel(const FibreStore& fibres, int segments,
                                              CoarseRotations wanted, std::string& message) {
  using enum CoarseRotations;
  const auto form = [&](bool withRotations) {
    const auto t0 = std::chrono::steady_clock::now();
    rotations = withRotations;
    basis(fibres, segments, withRotations);
    coarseMatrix();
    times.coarseMatrix += since(t0);
    return analyseCoarse(message);
  };
  if (!form(wanted == On || (wanted == Auto && rotationsChosen != 0))) return false;
  if (wanted == Auto && rotationsChosen < 0) {
    rotationsChosen = coarseFlops <= kRotationsUpToFlopsPerNonzero * double(Kn.nonZeros());
    if (!rotationsChosen && !form(false)) return false;
  }
  if (!coarse.factorise(Ac, message)) {
    message = "Schwarz: the coarse matrix: " + message;
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

// Kn = the full K of `system` without its explicit zeros; `ls` points to it.
void SchwarzPreconditioner::Impl::copyOperator(const LinearSystem& system) {
  ls = &system;
  if (system.symmetric) {
    fullWithoutZeros(system.K, Kn, cursor);
  } else {
    withoutZeros(system.K, Kn);
  }
}

bool SchwarzPreconditioner::build(const LinearSystem& ls, const FibreStore& fibres, int segments,
                                  std::string& message, CoarseRotations rotations) {
  Impl& m = *impl_;
  m.copyOperator(ls);
  auto t0 = std::chrono::steady_clock::now();
  const bool blocks = m.factoriseBlocks(fibres, message);
  m.times.local += since(t0);
  if (!blocks) return false;
  t0 = std::chrono::steady_clock::now();
  // hats beyond every fibre's node intervals would be empty columns, unit rows of A_c only
  Index intervals = 1;
  for (Index f = 0; f < fibres.fibres(); ++f) intervals = std::max(intervals, fibres.nodeCount[f] - 1);
  const int pieces = int(std::clamp<Index>(segments, 1, intervals));
  const bool coarse = m.coarseLevel(fibres, pieces, rotations, message);
  m.times.coarse += since(t0);
  ++m.times.builds, m.times.withoutRotations += !m.rotations;
  return coarse;
}

void SchwarzPreconditioner::forgetChoice() { impl_->rotationsChosen = -1; }
bool SchwarzPreconditioner::rotations() const { return impl_->rotations; }
double SchwarzPreconditioner::coarseFlops() const { return impl_->coarseFlops; }

void SchwarzPreconditioner::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  const Impl& m = *impl_;
  auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd z = m.Phi.transpose() * v;
  m.coarse.solve(z);
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
