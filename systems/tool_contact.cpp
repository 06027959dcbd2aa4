#include "systems/tool_contact.h"

#include "systems/contact_law.h"
#include "systems/friction_status.h"
#include "systems/particle.h"
#include "systems/tool_geometry.h"

#include <tbb/parallel_for.h>

namespace fibra {

void evaluateToolContacts(const FibreStore& fs, const ToolStore& tools, const ToolZoneStore& zones,
                          const ContactParams& p, const ToolContactStore& c,
                          const IterationInput& input, FrictionStatusStore& status,
                          ContactForceStore& out) {
  std::vector<RigidMotion> motion;
  for (Index t = 0; t < tools.size(); ++t) motion.push_back(toolMotion(tools, t, input.time));
  resizeContactForces(out, c.size());
  sizeFrictionStatus(status, c.size());
  tbb::parallel_for(Index(0), c.size(), [&](Index i) {
    const Index t = c.tool[i], z = c.zone[i];
    const Vec3 d = particlePosition(fs.q, c.side[i]) - motion[t](c.toolPoint[i]);
    const ContactLawParams law{zones.penalty[z] * c.weight[i], p.pRegRatio * zones.pMax[z],
                               tools.friction[t] * p.frictionFactor, p.gMax};
    const ContactLawResult r =
        contactLaw(d, {c.normal[i], c.d0[i], c.gRev0[i]}, law, p.symmetrised, status.held[i]);
    storeContactLaw(r, i, out);
    trackFrictionStatus(status, i, r, input.withTangent, p.frictionFlips);
  });
}

}  // namespace fibra
