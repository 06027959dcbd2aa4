#include "systems/tool_geometry.h"

namespace fibra {

RigidMotion toolMotion(const ToolStore& tools, Index tool, double time) {
  return motionAt(tools.motion[tool], tools.point[tool], time);
}

SurfacePoint closestSurfacePoint(const ToolStore& tools, Index tool, const RigidMotion& m,
                                  const Vec3& x) {
  const Vec3 p = m(tools.point[tool]), dir = (m.R * tools.direction[tool]).normalized();
  if (tools.kind[tool] == ToolKind::Plane) {
    const double dist = (x - p).dot(dir);
    return {x - dist * dir, dir, dist};
  }
  Vec3 radial = (x - p) - (x - p).dot(dir) * dir;
  const double rho = radial.norm();
  // On the axis the radial direction is undefined: any normal to the axis will do.
  radial = rho > 0 ? Vec3(radial / rho) : Vec3(dir.unitOrthogonal());
  const bool inside = tools.inside[tool];
  const Vec3 normal = inside ? Vec3(-radial) : radial;
  const double dist = inside ? tools.radius[tool] - rho : rho - tools.radius[tool];
  return {x - dist * normal, normal, dist};
}

}  // namespace fibra
