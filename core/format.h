// Numbers in messages: six significant digits (%g), so that 1e-9 and 7e-10 read as themselves
// and not as 0.000000 (std::to_string).
#pragma once

#include <cstdio>
#include <string>

namespace fibra {

inline std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

// A count with its noun, singular for one: counted(1, "cutback") is "1 cutback", counted(3, …)
// "3 cutbacks".
inline std::string counted(long n, const char* noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

}  // namespace fibra
