// Checks shared by the scene validation's files (io/scene_validate.cpp and the sections split
// from it): each throws SceneError "PATH: what is wrong" for a value out of its range. Internal
// to io/; validateScene (io/scene_validate.h) is the entry point.
#pragma once

#include "core/errors.h"
#include "core/types.h"
#include "engine/scene.h"

#include <cmath>
#include <sstream>
#include <string>

namespace fibra::validate_checks {

inline std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

inline std::string at(const std::string& list, size_t i) { return list + "[" + std::to_string(i) + "]"; }

[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
  throw SceneError(path + ": " + what);
}

inline void positive(double v, const std::string& path) {
  if (!(v > 0 && std::isfinite(v))) fail(path, "must be > 0, got " + num(v));
}
inline void nonNegative(double v, const std::string& path) {
  if (!(v >= 0 && std::isfinite(v))) fail(path, "must be >= 0, got " + num(v));
}
inline void finite(double v, const std::string& path) {
  if (!std::isfinite(v)) fail(path, "must be a finite number, got " + num(v));
}
inline void finite(const Vec3& v, const std::string& path) {
  if (!v.allFinite()) fail(path, "must be a finite vector");
}
// Lengths and coordinates beyond this (mm) are beyond any scene, and their products overflow.
inline constexpr double kLongest = 1e6;
// A position or length in mm: finite and at most kLongest in size.
inline void withinScene(double v, const std::string& path) {
  finite(v, path);
  if (std::abs(v) > kLongest)
    fail(path, "must be at most " + num(kLongest) + " mm in size, got " + num(v));
}
inline void withinScene(const Vec3& v, const std::string& path) {
  finite(v, path);
  if (v.cwiseAbs().maxCoeff() > kLongest)
    fail(path, "coordinates must be at most " + num(kLongest) + " mm in size");
}
inline void nonZero(const Vec3& v, const std::string& path) {
  if (!(v.allFinite() && v.norm() > 0)) fail(path, "must be a finite, non-zero vector");
  if (!std::isfinite(v.norm())) fail(path, "is too long: its length overflows a double");
}
// NaN means "the default"; any other value must be positive.
inline void positiveOrDefault(double v, const std::string& path) {
  if (!std::isnan(v)) positive(v, path);
}
inline void atLeast(int v, int min, const std::string& path) {
  if (v < min) fail(path, "must be >= " + std::to_string(min) + ", got " + std::to_string(v));
}
inline void inRange(int v, int min, int max, const std::string& path) {
  if (v < min || v > max)
    fail(path, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                   std::to_string(v));
}

// The solver section (io/scene_validate_solver.cpp).
void validateSolver(const SolverDef& s);

}  // namespace fibra::validate_checks
