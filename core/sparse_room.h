// Storage of a compressed sparse matrix rebuilt again and again (every detection, every Newton
// iteration), kept from call to call.
//
// A block of more than glibc's mmap threshold (then fixed at 128 KiB by core/allocator.h) is
// mapped fresh at every allocation and faulted in page by page as it is first written: on a
// 37-fibre bundle with the Schwarz strategy such system time was 28% of the wall time
// (docs/RESULTS.md "Storage kept between Newton iterations"). Kept storage is reallocated only
// when it grows, whatever the allocator does.
#pragma once

#include <Eigen/SparseCore>

namespace fibra {

// m becomes rows x cols, compressed, with nnz entries whose indices and values the caller
// writes (outer index included); its storage is reallocated only when nnz exceeds it, then with
// a quarter more room.
template <class Matrix>
void roomFor(Matrix& m, Eigen::Index rows, Eigen::Index cols, Eigen::Index nnz) {
  m.resize(rows, cols);
  if (m.data().allocatedSize() < nnz) m.reserve(nnz + nnz / 4);
  m.resizeNonZeros(nnz);
}

}  // namespace fibra
