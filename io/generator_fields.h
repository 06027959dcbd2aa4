// Field checks shared by the scene generators (io/yarn_generator.cpp, io/fabric_generator.cpp):
// each fails with a SceneError "PATH.key: what is wrong" (json_reader). Internal to io/.
#pragma once

#include "io/json_reader.h"

#include <cctype>
#include <cmath>
#include <sstream>
#include <string>

namespace fibra::generator_fields {

using json_reader::Fields;
using json_reader::Json;

[[noreturn]] inline void bad(const Fields& f, const char* key, const std::string& what) {
  json_reader::fail(f.path(key), what);
}

// A number as a message shows it (shortest default formatting).
inline std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A required finite number > 0.
inline double positive(const Fields& f, const char* key) {
  const double v = f.number(key);
  if (!(v > 0 && std::isfinite(v))) bad(f, key, "must be > 0, got " + num(v));
  return v;
}

// An integer in [min, max], `fallback` when absent.
inline int integerIn(const Fields& f, const char* key, int fallback, int min, int max) {
  const int v = f.integer(key, fallback);
  if (v < min || v > max)
    bad(f, key, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                    std::to_string(v));
  return v;
}

// A generator's name: the prefix of the fibres and groups it makes, so a valid scene name.
inline void checkName(const Fields& f, const std::string& name) {
  if (name.empty()) bad(f, "name", "must not be empty");
  for (char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') continue;
    std::string what(1, '\'');
    what.append(json_reader::shown(name)).append("' contains '").push_back(c);
    bad(f, "name", what.append("'; names use letters, digits, '_', '-' and '.'"));
  }
}

// A generator makes at most this many beam elements (the paper's largest scene, the woven
// fabric, has 480 x 40 = 19 200): a size error before anything is allocated.
constexpr double kMaxGeneratedElements = 1e6;

// `elements` (the key that sets the count per fibre) when fibres x elements exceeds the limit.
inline void checkElementCount(const Fields& f, double fibres, int elements) {
  if (fibres * elements > kMaxGeneratedElements)
    bad(f, "elements",
        num(fibres) + " fibres x " + std::to_string(elements) + " elements = " +
            num(fibres * elements) + " beam elements, more than a generator makes (" +
            num(kMaxGeneratedElements) + ")");
}

}  // namespace fibra::generator_fields
