#include "engine/contact_loops.h"

#include "systems/boundary.h"
#include "systems/friction_history.h"
#include "systems/interpolation.h"
#include "systems/particle.h"
#include "systems/tool_contact.h"

#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

double minRadius(const FibreStore& fs) {
  double r = fs.fibres() ? fs.radius[0] : 1;
  for (double x : fs.radius) r = std::min(r, x);
  return r;
}

// --- detection: elements at the current state, friction reference and history ---

// Friction reference of the current elements: their relative positions in the state q at time
// tRef, and the reversible slip the history holds for their particles.
void rebase(WorldState& w, double tRef) {
  ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i) {
    const Index e = c.element[i], f = w.fibres.elementFibre[e];
    const Vec3 x = particlePosition(w.fibres.q, particleWeights(w.fibres, e, c.z[i], c.xi1[i], c.xi2[i]));
    c.d0[i] = x - toolMotion(w.tools.def[c.tool[i]], tRef)(c.toolPoint[i]);
    const Vec3 h = lookupHistory(w.history, f, -1 - c.tool[i], arcLength(w.fibres, e, c.z[i]),
                                 elementLength(w.fibres, f));
    c.gRev0[i] = projectOnPlane(h, c.normal[i]);
  }
}

void detect(WorldState& w, double t) {
  if (!w.contact.tools) return;
  detectToolContacts(w.fibres, w.fibres.q, w.tools, t, w.contact.toolProximity, w.toolContacts);
  rebase(w, t);
}

// Deepest penetration of the freshly detected elements, in units of their p_max.
double deepestDetected(const WorldState& w) {
  double d = 0;
  const ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i) d = std::max(d, -c.gap[i] / w.tools.pMax[c.tool[i]]);
  return d;
}

// Largest angle any normal turned by, rad; the reversible slips follow to the new planes.
double updateNormals(WorldState& w, double t) {
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

// Eq. 13 per zone: k <- k * clamp(g_max / p_max, 1 / beta, beta). Returns the largest relative
// change of a penalty.
double adaptPenalties(WorldState& w) {
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
    const double factor = std::clamp(deepest[z] / w.tools.pMax[z / nf], 1 / beta, beta);
    w.tools.penalty[z] *= factor;
    change = std::max(change, std::abs(factor - 1));
  }
  return change;
}

void recordFrictionHistory(WorldState& w) {
  std::vector<HistoryEntry> entries;
  const ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i)
    if (c.normalForce[i] > 0)
      entries.push_back({w.fibres.elementFibre[c.element[i]], -1 - c.tool[i],
                         arcLength(w.fibres, c.element[i], c.z[i]), c.gRev[i]});
  recordHistory(entries, w.history);
}

// The contact set as (tool, element, z, xi) records, to tell whether detection changed it.
struct SetSignature {
  std::vector<std::array<double, 5>> records;
};

SetSignature signature(const WorldState& w) {
  SetSignature s;
  const ToolContactStore& c = w.toolContacts;
  for (Index i = 0; i < c.size(); ++i)
    s.records.push_back({double(c.tool[i]), double(c.element[i]), c.z[i], c.xi1[i], c.xi2[i]});
  return s;
}

bool sameSet(const SetSignature& a, const SetSignature& b, double tolerance) {
  if (a.records.size() != b.records.size()) return false;
  for (size_t i = 0; i < a.records.size(); ++i)
    for (int k = 0; k < 5; ++k)
      if (std::abs(a.records[i][k] - b.records[i][k]) > (k < 3 ? 0.0 : tolerance)) return false;
  return true;
}

// Largest step along dq that closes no contact element deeper than `depth` p_max. Gaps are
// linear in the DOFs for fixed elements and normals, so g(a) = g + a N . (D dq) exactly.
double stepLimit(const WorldState& w, const Eigen::VectorXd& dq) {
  const ToolContactStore& c = w.toolContacts;
  double a = 1;
  for (Index i = 0; i < c.size(); ++i) {
    const double allowed = w.contact.stepPenetration * w.tools.pMax[c.tool[i]];
    const double dg = c.normal[i].dot(particlePosition(dq, particleWeights(w.fibres, c.element[i], c.z[i], c.xi1[i], c.xi2[i])));
    if (dg < 0 && c.gap[i] > -allowed) a = std::min(a, (c.gap[i] + allowed) / -dg);
  }
  return a;
}

void fillReport(const WorldState& w, ContactReport& r) {
  const ToolContactStore& c = w.toolContacts;
  r.toolElements = c.size();
  r.active = r.sliding = 0;
  r.maxPenetration = r.maxPenetrationRatio = 0;
  for (Index i = 0; i < c.size(); ++i) {
    r.active += c.normalForce[i] > 0;
    r.sliding += c.slip[i];
    r.maxPenetration = std::max(r.maxPenetration, -c.gap[i]);
    r.maxPenetrationRatio = std::max(r.maxPenetrationRatio, -c.gap[i] / w.tools.pMax[c.tool[i]]);
  }
}

}  // namespace

void buildContact(WorldState& w) {
  const ContactDef& def = w.scene.contact;
  ContactSettings& s = w.contact;
  const double R = minRadius(w.fibres);
  s.tools = !w.scene.tools.empty();
  s.maxDetectionLoops = def.maxDetectionLoops;
  s.maxNormalLoops = def.maxNormalLoops;
  s.pRegRatio = def.regularisation;
  s.penaltyChange = def.penaltyChange;
  s.gMax = std::isfinite(def.maxReversibleSlip) ? def.maxReversibleSlip : 0.005 * R;
  s.toolProximity = def.proximityDistance;  // NaN: per fibre, systems/tool_contact.h
  s.symmetrised = def.frictionTangent == FrictionTangent::Symmetrised;
  const double pMax = std::isfinite(def.maxPenetration) ? def.maxPenetration : 0.005 * R;

  for (const ToolDef& t : w.scene.tools) {
    w.tools.def.push_back(t);
    w.tools.pMax.push_back(std::isfinite(t.maxPenetration) ? t.maxPenetration : pMax);
    w.tools.reaction.push_back(Vec3::Zero());
    for (Index f = 0; f < w.fibres.fibres(); ++f) {
      const double k0 = std::isfinite(def.initialPenalty)
                            ? def.initialPenalty
                            : w.materials.youngModulus[w.fibres.material[f]] * w.fibres.radius[f];
      w.tools.penalty.push_back(k0);
    }
  }

  w.stabilisation.assign(w.fibres.nodes(), 0.0);
  const StabilisationDef& st = w.scene.stabilisation;
  for (Index f = 0; f < w.fibres.fibres(); ++f) {
    const bool listed = st.fibres.empty() ||
                        std::find(st.fibres.begin(), st.fibres.end(), w.fibres.name[f]) != st.fibres.end();
    if (!listed) continue;
    for (Index n = 0; n < w.fibres.nodeCount[f]; ++n) w.stabilisation[w.fibres.firstNode[f] + n] = st.stiffness;
  }
}

NewtonResult solveContactIncrement(WorldState& w, double tTry, const NewtonSettings& settings,
                                   const NewtonCallbacks& cb, StepTimings& timings,
                                   ContactReport& report) {
  const ContactSettings& s = w.contact;
  NewtonCallbacks callbacks = cb;
  callbacks.stepLimit = [&w](const Eigen::VectorXd& dq) { return stepLimit(w, dq); };
  NewtonResult nr;
  report = ContactReport{};
  const Eigen::VectorXd qEntry = w.fibres.q;
  const FrictionHistoryStore historyEntry = w.history;
  detect(w, w.time);
  applyConstraints(w.fibres, w.constraints, w.groups, tTry, w.fibres.q);
  for (int a = 1; a <= s.maxDetectionLoops; ++a) {
    report.detectionLoops = a;
    for (int b = 1; b <= s.maxNormalLoops; ++b) {
      ++report.normalLoops;
      const int before = nr.iterations;
      nr = solveNewton(w.fibres.q, w.system, w.solver, settings, callbacks, timings);
      nr.iterations += before;
      if (nr.outcome != NewtonOutcome::Converged) return nr;
      if (b == s.maxNormalLoops || updateNormals(w, tTry) < s.normalTolerance) break;
    }
    const double change = adaptPenalties(w);
    recordFrictionHistory(w);
    fillReport(w, report);
    if (a == s.maxDetectionLoops) break;
    const SetSignature previous = signature(w);
    detect(w, tTry);
    if (sameSet(previous, signature(w), s.particleTolerance * minRadius(w.fibres)) &&
        change <= s.penaltyTolerance)
      break;
    if (deepestDetected(w) > s.stepPenetration) {
      // The last pass went deep where it had no elements: redo the increment from its start
      // with the new elements, so that the step limit can bring them into contact gently.
      w.fibres.q = qEntry;
      w.history = historyEntry;
      rebase(w, w.time);
      applyConstraints(w.fibres, w.constraints, w.groups, tTry, w.fibres.q);
      ++report.restarts;
    }
  }
  return nr;
}

ContactCheckpoint contactCheckpoint(const WorldState& w) { return {w.history, w.tools.penalty}; }

void restoreContact(WorldState& w, const ContactCheckpoint& c) {
  w.history = c.history;
  w.tools.penalty = c.toolPenalty;
}

}  // namespace fibra
