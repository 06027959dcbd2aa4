// A prescribed rigid motion of pseudo-time t, shared by held DOFs and rigid tools:
//   x -> c + R(t) (x - c) + d(t),   R(t) the rotation by angle(t) about `axis` through c,
//   d(t) = displacement * displacementTable(t).
// Resolved from the scene; no logic here (systems/motion.h evaluates it).
#pragma once

#include "core/table.h"
#include "core/types.h"

#include <limits>

namespace fibra {

struct PrescribedMotion {
  Vec3 displacement = Vec3::Zero();                 // mm, scaled by displacementTable
  Table displacementTable{{0.0, 1.0}, {0.0, 1.0}};  // -
  bool rotates = false;
  Vec3 axis = Vec3::UnitZ();                        // rotation axis (normalised when used)
  Vec3 centre = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // mm; NaN: the
                                                    // owner's default (a node's X0, a tool's point)
  Table angle;                                      // rad
};

}  // namespace fibra
