// Prescribed rigid motions (components/motion.h) evaluated at a pseudo-time: the map
//   x -> c + R(t) (x - c) + d(t)
// of held DOFs and rigid tools. Header-only, pure functions.
#pragma once

#include "components/motion.h"

#include <Eigen/Geometry>

namespace fibra {

struct RigidMotion {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vec3 centre = Vec3::Zero(), shift = Vec3::Zero();  // mm
  Vec3 operator()(const Vec3& x) const { return centre + R * (x - centre) + shift; }
};

// The motion at time t; `defaultCentre` stands in for a NaN centre (mm).
inline RigidMotion motionAt(const PrescribedMotion& m, const Vec3& defaultCentre, double time) {
  RigidMotion out;
  out.centre = m.centre.allFinite() ? m.centre : defaultCentre;
  if (m.rotates)
    out.R = Eigen::AngleAxisd(tableValue(m.angle, time), m.axis.normalized()).toRotationMatrix();
  out.shift = m.displacement * tableValue(m.displacementTable, time);
  return out;
}

}  // namespace fibra
