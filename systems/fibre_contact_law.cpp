#include "systems/fibre_contact_law.h"

#include "systems/contact_law.h"
#include "systems/contact_params.h"
#include "systems/facing_particles.h"
#include "systems/friction_status.h"
#include "systems/normal_linearisation.h"
#include "systems/particle.h"

#include <tbb/parallel_for.h>

namespace fibra {
namespace {

// With contact.facing_particles (the facing columns then sized): a fixed normal (the caller has
// taken the linearised ones), no end face. Frictional or not: the normal force on the facing
// particles, friction's on the material ones (systems/facing_particles.h).
bool facingElement(const ContactParams& p, const ContactElementStore& el, Index e) {
  return p.facingParticles && !(el.fallback[e] & (kEndFaceI | kEndFaceJ));
}

}  // namespace

void evaluateFibreContacts(const FibreStore& fs, const ContactParams& p, const ZoneStore& zones,
                           const ContactElementStore& el, const IterationInput& input,
                           FrictionStatusStore& status, ContactForceStore& out) {
  resizeContactForces(out, el.size());
  sizeFrictionStatus(status, el.size());
  if (normalsInNewton(p)) out.normalJacobian.resize(el.size());
  if (p.facingParticles) {  // only then: seven columns per element a scene without it skips
    out.facing.assign(el.size(), 0);
    for (auto* side : {&out.facingI, &out.facingJ, &out.rollingI, &out.rollingJ})
      side->resize(el.size());
    out.frictionStiffness.resize(el.size(), Eigen::Matrix3d::Zero());  // zero where not facing:
    out.coupling.resize(el.size(), Eigen::Matrix3d::Zero());           // hashed, checkpointed
  }
  tbb::parallel_for(Index(0), el.size(), [&](Index e) {
    const Index z = el.zone[e];
    const ContactLawParams law{zones.penalty[z] * el.weight[e], p.pRegRatio * zones.pMax[z],
                               zones.friction[z] * p.frictionFactor, p.gMax};
    if (linearisedNormal(p, el, e)) {
      const LinearisedContact c = linearisedContact(fs, fs.q, el, e, law, p.thetaParallel,
                                                    p.thetaCross, status.held[e],
                                                    p.facingParticles);
      storeContactLaw(c.law, e, out);
      out.normalJacobian[e] = c.jacobian;
      if (c.facing) {
        out.facing[e] = 1;
        out.facingI[e] = c.I.particle, out.facingJ[e] = c.J.particle;
        out.rollingI[e] = c.I.rolling, out.rollingJ[e] = c.J.rolling;
      }
      trackFrictionStatus(status, e, c.law, input.withTangent, p.frictionFlips);
      return;
    }
    // a forced element's allowance widens its gap: d shifted along N (a constant of q; N's
    // tangent plane, where the slip lives, is unchanged)
    const Vec3 widen = forcedAllowance(p, el.forced[e]) * el.normal[e];
    const Vec3 d =
        particlePosition(fs.q, el.sideI[e]) - particlePosition(fs.q, el.sideJ[e]) + widen;
    FacingSide I, J;
    if (facingElement(p, el, e) &&
        facingSide(fs.q, el.sideI[e], fs.radius[el.fibreI[e]], -el.normal[e], I) &&
        facingSide(fs.q, el.sideJ[e], fs.radius[el.fibreJ[e]], el.normal[e], J)) {
      const ContactLawResult r = contactLawSplit(I.position - J.position + widen, d,
                                                 {el.normal[e], el.d0[e], el.gRev0[e]}, law,
                                                 p.symmetrised, status.held[e]);
      storeContactLaw(r, e, out);
      out.facing[e] = 1;
      out.facingI[e] = I.particle, out.facingJ[e] = J.particle;
      out.rollingI[e] = I.rolling, out.rollingJ[e] = J.rolling;
      out.frictionStiffness[e] = r.frictionStiffness, out.coupling[e] = r.coupling;
      if (law.mu > 0) trackFrictionStatus(status, e, r, input.withTangent, p.frictionFlips);
      return;
    }
    const ContactLawResult r =
        contactLaw(d, {el.normal[e], el.d0[e], el.gRev0[e]}, law, p.symmetrised, status.held[e]);
    storeContactLaw(r, e, out);
    trackFrictionStatus(status, e, r, input.withTangent, p.frictionFlips);
  });
}

}  // namespace fibra
