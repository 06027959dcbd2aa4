// The process's allocator setting for long runs, called by fibra's programs (app/main.cpp, the
// benches) at start, never by the library: it is process-wide, and a host program that embeds
// fibra decides its own (docs/EMBEDDING.md).
//
// glibc's malloc raises its mmap threshold to the size of every large block freed (up to 32 MiB
// on 64-bit), after which blocks of that size come from the heaps of the threads that asked for
// them and are never given back when they free out of order. A Newton iteration builds and
// frees matrices of varying size on every thread (the Schwarz preconditioner's K without zeros,
// K Phi, A_c, the per-fibre products), and on the 250-fibre yarn the resident memory then grew
// by about 40 MB per iteration (0.70 -> 1.20 GiB over 13 iterations, 13.6 GB at the end of a
// 4 547-iteration run); with the threshold fixed at 128 KiB it stays at 0.62-0.64 GiB with
// the same time per iteration (docs/RESULTS.md "Explicit zeros").
// Since the Schwarz preconditioner and K's pattern keep their storage (core/sparse_room.h), what
// is still allocated per Newton iteration is mostly UMFPACK's factor of the coarse matrix and
// the contact stores, allocated and freed by one thread at a time; a block above the threshold
// is mapped fresh and faulted in page by page at each allocation, and the heap's top above the
// trim threshold is given back and faulted in again. So the thresholds are now fixed higher: on
// the mid-crush Table 2 yarn (6 increments, 157 Newton iterations, 2 threads) 0.476 s per
// iteration against 0.612 s with 128 KiB, resident memory flat at 0.88 GiB against 0.77 GiB
// (docs/RESULTS.md "Storage kept between Newton iterations").
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fibra {

// Fixes glibc's mmap threshold at 32 MiB (setting it turns off its growth) and its trim
// threshold at 256 MiB. Elsewhere: nothing.
inline void fixAllocatorThreshold() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 256 * 1024 * 1024);
#endif
}

}  // namespace fibra
