// Rigid tool geometry: a tool's motion at a pseudo-time and the closest point of its surface.
//
// Motion: a tool's point x (at t = 0) is at M(t) x = c + R(t)(x - c) + d(t), c its centre (the
// tool's point unless given). Surface: a plane through M(t) point with normal R(t) direction
// (towards the fibres), or a cylinder of that axis and radius, the fibres outside it or inside
// it. Pure functions, used by the tool detection, normal and law systems.
#pragma once

#include "components/tools.h"
#include "systems/motion.h"

namespace fibra {

RigidMotion toolMotion(const ToolStore& tools, Index tool, double time);

// Closest point of the tool's surface to x, the unit normal there pointing to the fibres' side,
// and the signed distance of x from the surface along it (mm).
struct SurfacePoint {
  Vec3 point, normal;
  double distance;
};
SurfacePoint closestSurfacePoint(const ToolStore& tools, Index tool, const RigidMotion& m,
                                  const Vec3& x);

}  // namespace fibra
