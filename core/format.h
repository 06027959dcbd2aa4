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

}  // namespace fibra
