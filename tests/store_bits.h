// Determinism helpers: bitwise equality and a hash of every column of a store, reached by
// reflection (core/columns.h), so that a column added to a store is compared and hashed without
// a list kept by hand. Structs are compared member by member (never their padding bytes);
// doubles by their bits (so -0.0 differs from 0.0 and NaNs compare by payload).
#pragma once

#include "core/columns.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace fibra::test {

template <class T>
struct IsStdArray : std::false_type {};
template <class T, std::size_t N>
struct IsStdArray<std::array<T, N>> : std::true_type {};

template <class T>
concept EigenDense = requires(const T& m) {
  m.data();
  m.rows();
  m.cols();
  typename T::Scalar;
};

template <class T>
concept EigenSparse = requires(const T& m) {
  m.valuePtr();
  m.innerIndexPtr();
  m.outerIndexPtr();
  m.nonZeros();
};

// FNV-1a over bytes.
inline void hashBytes(const void* data, std::size_t n, std::uint64_t& h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
}

// Calls f(pointer, bytes) on every padding-free run of bits of v, in a fixed order.
template <class T, class F>
void visitBits(const T& v, F&& f) {
  if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
    f(&v, sizeof(T));
  } else if constexpr (std::is_same_v<T, std::string>) {
    const std::size_t n = v.size();
    f(&n, sizeof n);
    f(v.data(), n);
  } else if constexpr (IsStdVector<T>::value || IsStdArray<T>::value) {
    const std::size_t n = v.size();
    f(&n, sizeof n);
    using E = typename T::value_type;
    if constexpr (std::is_arithmetic_v<E> && !std::is_same_v<E, bool>)
      f(v.data(), n * sizeof(E));
    else
      for (const auto& e : v) visitBits(static_cast<const E&>(e), f);
  } else if constexpr (EigenSparse<T>) {
    const std::int64_t shape[3] = {v.rows(), v.cols(), v.nonZeros()};
    f(shape, sizeof shape);
    f(v.outerIndexPtr(), (v.outerSize() + 1) * sizeof(*v.outerIndexPtr()));
    f(v.innerIndexPtr(), v.nonZeros() * sizeof(*v.innerIndexPtr()));
    f(v.valuePtr(), v.nonZeros() * sizeof(*v.valuePtr()));
  } else if constexpr (EigenDense<T>) {
    const std::int64_t shape[2] = {v.rows(), v.cols()};
    f(shape, sizeof shape);
    f(v.data(), v.size() * sizeof(typename T::Scalar));
  } else {
    static_assert(std::is_aggregate_v<T>, "a store or a column type the helpers can reach");
    forEachColumn(v, [&](const auto& column) { visitBits(column, f); });
  }
}

template <class T>
std::uint64_t hashBits(const T& v, std::uint64_t h = 1469598103934665603ull) {
  visitBits(v, [&](const void* p, std::size_t n) { hashBytes(p, n, h); });
  return h;
}

// Bitwise equality of every column (and every member of every struct in it).
template <class T>
bool sameBits(const T& a, const T& b) {
  std::vector<unsigned char> x, y;
  const auto collect = [](std::vector<unsigned char>& out) {
    return [&out](const void* p, std::size_t n) {
      const auto* c = static_cast<const unsigned char*>(p);
      out.insert(out.end(), c, c + n);
    };
  };
  visitBits(a, collect(x));
  visitBits(b, collect(y));
  return x == y;
}

}  // namespace fibra::test
