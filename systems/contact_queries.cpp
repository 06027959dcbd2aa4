#include "systems/contact_queries.h"

#include "systems/particle.h"

#include <algorithm>

namespace fibra {

double stepLimit(const ContactParams& p, const ContactState& s, const Eigen::VectorXd& dq) {
  double a = 1;
  const auto limit = [&](double gap, double pMax, double dg) {
    const double allowed = p.stepPenetration * pMax;
    if (dg < 0 && gap > -allowed) a = std::min(a, (gap + allowed) / -dg);
  };
  const ContactElementStore& el = s.elements;
  for (Index e = 0; e < el.size(); ++e)
    limit(s.forces.gap[e], s.zones.pMax[el.zone[e]],
          el.normal[e].dot(particlePosition(dq, el.sideI[e]) - particlePosition(dq, el.sideJ[e])));
  const ToolContactStore& t = s.toolElements;
  for (Index i = 0; i < t.size(); ++i)
    limit(s.toolForces.gap[i], s.toolZones.pMax[t.zone[i]],
          t.normal[i].dot(particlePosition(dq, t.side[i])));
  return a;
}

double deepestDetected(const ContactState& s) {
  double d = 0;
  for (Index e = 0; e < s.elements.size(); ++e)
    d = std::max(d, -s.elements.gap[e] / s.zones.pMax[s.elements.zone[e]]);
  for (Index i = 0; i < s.toolElements.size(); ++i)
    d = std::max(d, -s.toolElements.gap[i] / s.toolZones.pMax[s.toolElements.zone[i]]);
  return d;
}

void fillContactReport(const ContactParams& p, const ContactState& s, ContactReport& r) {
  r.zones = s.zones.size();
  r.elements = s.elements.size();
  r.toolElements = s.toolElements.size();
  r.active = r.sliding = 0;
  r.maxPenetration = r.maxPenetrationRatio = 0;
  const auto add = [&](const ContactForceStore& f, Index e, double pMax) {
    r.active += f.normalForce[e] > 0;
    r.sliding += sliding(f.normalForce[e], f.gRev[e], p.gMax);
    r.maxPenetration = std::max(r.maxPenetration, -f.gap[e]);
    r.maxPenetrationRatio = std::max(r.maxPenetrationRatio, -f.gap[e] / pMax);
  };
  for (Index e = 0; e < s.elements.size(); ++e) add(s.forces, e, s.zones.pMax[s.elements.zone[e]]);
  for (Index i = 0; i < s.toolElements.size(); ++i)
    add(s.toolForces, i, s.toolZones.pMax[s.toolElements.zone[i]]);
}

}  // namespace fibra
