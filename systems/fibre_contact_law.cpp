#include "systems/fibre_contact_law.h"

#include "systems/contact_law.h"
#include "systems/friction_status.h"
#include "systems/normal_linearisation.h"
#include "systems/particle.h"

#include <tbb/parallel_for.h>

namespace fibra {

void evaluateFibreContacts(const FibreStore& fs, const ContactParams& p, const ZoneStore& zones,
                           const ContactElementStore& el, const IterationInput& input,
                           FrictionStatusStore& status, ContactForceStore& out) {
  resizeContactForces(out, el.size());
  sizeFrictionStatus(status, el.size());
  if (p.newtonNormals) out.normalJacobian.resize(el.size());
  tbb::parallel_for(Index(0), el.size(), [&](Index e) {
    const Index z = el.zone[e];
    const ContactLawParams law{zones.penalty[z] * el.weight[e], p.pRegRatio * zones.pMax[z],
                               zones.friction[z] * p.frictionFactor, p.gMax};
    if (linearisedNormal(p, el, e)) {
      const LinearisedContact c =
          linearisedContact(fs, fs.q, el, e, law, p.thetaParallel, p.thetaCross);
      storeContactLaw(c.law, e, out);
      out.normalJacobian[e] = c.jacobian;
      return;
    }
    const Vec3 d = particlePosition(fs.q, el.sideI[e]) - particlePosition(fs.q, el.sideJ[e]);
    const ContactLawResult r =
        contactLaw(d, {el.normal[e], el.d0[e], el.gRev0[e]}, law, p.symmetrised, status.held[e]);
    storeContactLaw(r, e, out);
    trackFrictionStatus(status, e, r, input.withTangent, p.frictionFlips);
  });
}

}  // namespace fibra
