#include "systems/nonzero_pattern.h"

#include <algorithm>

namespace fibra {
namespace {

// Whether stored entry k of K (row i, column j) must be in P: not exactly 0, or diagonal.
inline bool needed(double v, int i, Index j) { return v != 0 || i == j; }

// Counts, over K's stored entries, those needed (nz(K) ∪ diag) and those needed outside P.
void countNeeded(const SparseMatrix& K, const std::vector<std::uint8_t>& in, Index& need,
                 Index& escapes) {
  need = escapes = 0;
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* value = K.valuePtr();
  for (Index j = 0; j < K.outerSize(); ++j)
    for (Index k = outer[j]; k < outer[j + 1]; ++k)
      if (needed(value[k], inner[k], j)) ++need, escapes += !in[k];
}

// P := P ∪ needed (keep) or P := needed (!keep); returns |P|.
Index remask(const SparseMatrix& K, std::vector<std::uint8_t>& in, bool keep) {
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* value = K.valuePtr();
  Index entries = 0;
  for (Index j = 0; j < K.outerSize(); ++j)
    for (Index k = outer[j]; k < outer[j + 1]; ++k) {
      in[k] = (keep && in[k]) || needed(value[k], inner[k], j);
      entries += in[k];
    }
  return entries;
}

// The compact matrix's structure from the mask (rows in K's order within each column).
void structure(const SparseMatrix& K, const std::vector<std::uint8_t>& in, Index entries,
               SparseMatrix& C) {
  C.resize(K.rows(), K.cols());
  C.resizeNonZeros(entries);
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  Index at = 0;
  for (Index j = 0; j < K.outerSize(); ++j) {
    C.outerIndexPtr()[j] = int(at);
    for (Index k = outer[j]; k < outer[j + 1]; ++k)
      if (in[k]) C.innerIndexPtr()[at++] = inner[k];
  }
  C.outerIndexPtr()[K.outerSize()] = int(at);
}

// C's values: K's on P, in the same order as structure().
void gather(const SparseMatrix& K, const std::vector<std::uint8_t>& in, SparseMatrix& C) {
  const double* value = K.valuePtr();
  double* out = C.valuePtr();
  const Index n = K.nonZeros();
  for (Index k = 0, at = 0; k < n; ++k)
    if (in[k]) out[at++] = value[k];
}

// in[k] = 1 where K's stored entry k (row i, column j) is an entry of the previous pattern C
// (a new stored pattern of the same size: P carried over by coordinates); returns their count.
// mark: scratch of one int per row.
Index carry(const SparseMatrix& C, const SparseMatrix& K, std::vector<std::uint8_t>& in,
            std::vector<Index>& mark) {
  mark.assign(size_t(K.rows()), -1);
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  Index entries = 0;
  for (Index j = 0; j < K.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(C, j); it; ++it) mark[it.row()] = j;
    for (Index k = outer[j]; k < outer[j + 1]; ++k) entries += in[k] = mark[inner[k]] == j;
  }
  return entries;
}

// Whether A and B have the same CSC arrays (sizes, column starts, row indices in order).
bool sameStructure(const SparseMatrix& A, const SparseMatrix& B) {
  const Index nnz = A.nonZeros();
  return A.rows() == B.rows() && A.cols() == B.cols() && nnz == B.nonZeros() &&
         std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1, B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + nnz, B.innerIndexPtr());
}

}  // namespace

const LinearSystem& updateNonzeroPattern(const LinearSystem& ls, NonzeroPattern& p) {
  if (!(p.slack > 0)) return ls;
  ++p.passes;
  LinearSystem& c = p.compact;
  const SparseMatrix& K = ls.K;
  const bool fresh = p.storedRevision < 0 || c.K.cols() != K.cols() || c.K.rows() != K.rows();
  const bool moved = !fresh && (p.storedRevision != ls.revision || Index(p.in.size()) != K.nonZeros());
  if (fresh || moved) {
    p.in.assign(size_t(K.nonZeros()), 0);
    if (moved) p.entries = carry(c.K, K, p.in, p.mark);
    p.storedRevision = ls.revision;
  }
  Index need = 0, escapes = 0;
  countNeeded(K, p.in, need, escapes);
  const double limit = p.slack * double(need);
  const bool keep = !fresh && escapes == 0 && double(p.entries) <= limit;
  if (keep && moved) {
    // the same revision only for the same arrays: a factorisation's analysis holds their order
    SparseMatrix next;
    structure(K, p.in, p.entries, next);
    if (!sameStructure(next, c.K)) ++c.revision, ++p.patterns;
    c.K.swap(next);
  } else if (!keep) {
    const bool unite = !fresh && double(p.entries + escapes) <= limit;
    p.entries = remask(K, p.in, unite);
    structure(K, p.in, p.entries, c.K);
    ++c.revision;
    ++p.patterns;
  }
  gather(K, p.in, c.K);
  c.freeCount = ls.freeCount;
  c.symmetric = ls.symmetric;
  return c;
}

}  // namespace fibra
