#include "systems/tool_normals.h"

#include "systems/friction_history.h"
#include "systems/particle.h"
#include "systems/tool_geometry.h"

#include <algorithm>
#include <cmath>

namespace fibra {

void updateToolNormals(const FibreStore& fs, const ToolStore& tools, const IterationInput& input,
                       ToolContactStore& c, ContactLoopStats& stats) {
  double turned = 0;
  for (Index i = 0; i < c.size(); ++i) {
    const RigidMotion m = toolMotion(tools, c.tool[i], input.time);
    const SurfacePoint sp = closestSurfacePoint(tools, c.tool[i], m, particlePosition(fs.q, c.side[i]));
    turned = std::max(turned, std::acos(std::clamp(c.normal[i].dot(sp.normal), -1.0, 1.0)));
    c.normal[i] = sp.normal;
    c.gap[i] = sp.distance;
    c.gRev0[i] = projectOnPlane(c.gRev0[i], c.normal[i]);
  }
  stats.normalTurn = turned;
}

}  // namespace fibra
