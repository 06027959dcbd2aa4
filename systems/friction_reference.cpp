#include "systems/friction_reference.h"

#include "systems/friction_history.h"
#include "systems/particle.h"
#include "systems/tool_geometry.h"

namespace fibra {

void setFrictionReference(const FibreStore& fs, const ToolStore& tools,
                          const FrictionHistoryStore& history, const IterationInput& input,
                          ContactElementStore& el, ToolContactStore& tel) {
  for (Index e = 0; e < el.size(); ++e) {
    el.d0[e] = particlePosition(fs.q, el.sideI[e]) - particlePosition(fs.q, el.sideJ[e]);
    const Index I = el.fibreI[e], J = el.fibreJ[e];
    const Vec3 hI = lookupHistory(history, I, J, el.sI[e], elementLength(fs, I));
    const Vec3 hJ = lookupHistory(history, J, I, el.sJ[e], elementLength(fs, J));
    el.gRev0[e] = projectOnPlane(0.5 * (hI - hJ), el.normal[e]);
  }
  for (Index i = 0; i < tel.size(); ++i) {
    const Index e = tel.element[i], f = fs.elementFibre[e];
    tel.d0[i] = particlePosition(fs.q, tel.side[i]) - toolMotion(tools, tel.tool[i], input.time)(tel.toolPoint[i]);
    const Vec3 h = lookupHistory(history, f, -1 - tel.tool[i], arcLength(fs, e, tel.z[i]),
                                 elementLength(fs, f));
    tel.gRev0[i] = projectOnPlane(h, tel.normal[i]);
  }
}

}  // namespace fibra
