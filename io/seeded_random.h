// A seeded pseudo-random sequence that is the same on every machine and compiler: xoshiro256**
// (Blackman and Vigna) seeded through splitmix64, with its own uniform double. The standard
// library's engines are portable but its distributions are not (their algorithms are left to
// each implementation), so the scene generators draw only through this class.
#pragma once

#include <cstdint>

namespace fibra {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) {
    for (std::uint64_t& s : state_) s = splitmix64(seed);
  }

  // The next 64 random bits.
  std::uint64_t next() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1): the top 53 bits as a multiple of 2^-53 (exact in a double).
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }

  // Uniform integer in [0, n), n >= 1 (by the uniform double: the bias is below 2^-40 for the
  // small n the generators use).
  int below(int n) {
    const int k = int(uniform() * n);
    return k < n ? k : n - 1;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static std::uint64_t splitmix64(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  std::uint64_t state_[4];
};

}  // namespace fibra
