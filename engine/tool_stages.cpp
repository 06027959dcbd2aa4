#include "engine/tool_stages.h"

#include "systems/friction_history.h"
#include "systems/interpolation.h"
#include "systems/particle.h"
#include "systems/tool_contact.h"

#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

ParticleWeights weightsOf(const WorldState& w, Index i) {
  const ToolContactStore& c = w.toolContacts;
  return particleWeights(w.fibres, c.element[i], c.z[i], c.xi1[i], c.xi2[i]);
}

}  // namespace

void detectToolStage(WorldState& w, double t) {
  detectToolContacts(w.fibres, w.fibres.q, w.tools, t, w.contact.toolProximity, w.toolContacts);
  rebaseToolContacts(w, t);
}

void rebaseToolContacts(WorldState& w, double t) {
  ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i) {
    const Index e = c.element[i], f = w.fibres.elementFibre[e];
    c.d0[i] = particlePosition(w.fibres.q, weightsOf(w, i)) - toolMotion(w.tools, c.tool[i], t)(c.toolPoint[i]);
    const Vec3 h = lookupHistory(w.history, f, -1 - c.tool[i], arcLength(w.fibres, e, c.z[i]),
                                 elementLength(w.fibres, f));
    c.gRev0[i] = projectOnPlane(h, c.normal[i]);
  }
}

double updateToolStageNormals(WorldState& w, double t) {
  ToolContactStore& c = w.toolContacts;
  const std::vector<Vec3> before = c.normal;
  updateToolNormals(w.fibres, w.fibres.q, w.tools, t, c);
  double turned = 0;
  for (Index i = 0; i < c.size(); ++i) {
    turned = std::max(turned, std::acos(std::clamp(before[i].dot(c.normal[i]), -1.0, 1.0)));
    c.gRev0[i] = projectOnPlane(c.gRev0[i], c.normal[i]);
  }
  return turned;
}

double adaptToolPenalties(WorldState& w) {
  const Index nf = w.fibres.fibres();
  std::vector<double> deepest(w.tools.penalty.size(), 0.0);
  const ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i) {
    const Index z = c.tool[i] * nf + w.fibres.elementFibre[c.element[i]];
    deepest[z] = std::max(deepest[z], -c.gap[i]);
  }
  const double beta = w.contact.penaltyChange;
  double change = 0;
  for (size_t z = 0; z < deepest.size(); ++z) {
    if (deepest[z] <= 0) continue;
    const double factor = std::clamp(deepest[z] / (w.contact.penaltyTarget * w.tools.pMax[z / nf]), 1 / beta, beta);
    w.tools.penalty[z] *= factor;
    change = std::max(change, std::abs(factor - 1));
  }
  return change;
}

void toolHistoryEntries(const WorldState& w, std::vector<HistoryEntry>& out) {
  const ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i)
    if (c.normalForce[i] > 0)
      out.push_back({w.fibres.elementFibre[c.element[i]], -1 - c.tool[i],
                     arcLength(w.fibres, c.element[i], c.z[i]), c.gRev[i]});
}

double toolStepLimit(const WorldState& w, const Eigen::VectorXd& dq) {
  const ToolContactStore& c = w.toolContacts;
  double a = 1;
  for (Index i = 0; i < c.size(); ++i) {
    const double allowed = w.contact.stepPenetration * w.tools.pMax[c.tool[i]];
    const double dg = c.normal[i].dot(particlePosition(dq, weightsOf(w, i)));
    if (dg < 0 && c.gap[i] > -allowed) a = std::min(a, (c.gap[i] + allowed) / -dg);
  }
  return a;
}

double deepestToolContact(const WorldState& w) {
  double d = 0;
  const ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i) d = std::max(d, -c.gap[i] / w.tools.pMax[c.tool[i]]);
  return d;
}

void toolContactReport(const WorldState& w, ContactReport& r) {
  const ToolContactStore& c = w.toolContacts;
  r.toolElements = c.size();
  for (Index i = 0; i < c.size(); ++i) {
    r.active += c.normalForce[i] > 0;
    r.sliding += sliding(c.normalForce[i], c.gRev[i], w.contact.gMax);
    r.maxPenetration = std::max(r.maxPenetration, -c.gap[i]);
    r.maxPenetrationRatio = std::max(r.maxPenetrationRatio, -c.gap[i] / w.tools.pMax[c.tool[i]]);
  }
}

}  // namespace fibra
