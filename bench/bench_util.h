// Small helpers shared by the benches: wall-clock medians, BLAS thread control, CSV output.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

extern "C" void openblas_set_num_threads(int);

namespace fibra::bench {

inline double seconds(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median wall time of `repeats` runs of f, seconds.
inline double median(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) t.push_back(seconds(f));
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// OpenBLAS threads follow the bench's thread count (CHOLMOD's supernodal work is in BLAS).
inline void setBlasThreads(int n) { openblas_set_num_threads(n); }

inline std::FILE* openCsv(const std::string& path, const char* header) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f) std::fprintf(f, "%s\n", header);
  return f;
}

}  // namespace fibra::bench
