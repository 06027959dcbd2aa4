#include "engine/contact_loops.h"

#include "engine/fibre_contact.h"
#include "engine/tool_stages.h"
#include "systems/boundary.h"
#include "systems/friction_history.h"


#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

double minRadius(const FibreStore& fs) {
  double r = fs.fibres() ? fs.radius[0] : 1;
  for (double x : fs.radius) r = std::min(r, x);
  return r;
}

// --- the stages of both kinds of contact element, fibre-fibre and fibre-tool ---

void detect(WorldState& w, double t) {
  if (w.contact.fibres) {
    detectFibreContacts(w);
    rebaseFibreContacts(w);
  }
  if (w.contact.tools) detectToolStage(w, t);
}

// Friction reference of the current elements at the current state (time t).
void rebase(WorldState& w, double t) {
  if (w.contact.fibres) rebaseFibreContacts(w);
  if (w.contact.tools) rebaseToolContacts(w, t);
}

double deepestDetected(const WorldState& w) {
  return std::max(w.contact.fibres ? deepestFibreContact(w) : 0.0,
                  w.contact.tools ? deepestToolContact(w) : 0.0);
}

// Largest angle any normal turned by, rad.
double updateNormals(WorldState& w, double t) {
  return std::max(w.contact.fibres ? updateFibreNormals(w) : 0.0,
                  w.contact.tools ? updateToolStageNormals(w, t) : 0.0);
}

// Eq. 13 per zone; the largest relative change of a penalty.
double adaptPenalties(WorldState& w) {
  return std::max(w.contact.fibres ? adaptZonePenalties(w) : 0.0,
                  w.contact.tools ? adaptToolPenalties(w) : 0.0);
}

void recordFrictionHistory(WorldState& w) {
  std::vector<HistoryEntry> entries;
  if (w.contact.fibres) fibreHistoryEntries(w, entries);
  if (w.contact.tools) toolHistoryEntries(w, entries);
  recordHistory(entries, w.history);
}

// Largest step along dq that closes no element deeper than stepPenetration p_max.
double stepLimit(const WorldState& w, const Eigen::VectorXd& dq) {
  return std::min(w.contact.fibres ? fibreStepLimit(w, dq) : 1.0,
                  w.contact.tools ? toolStepLimit(w, dq) : 1.0);
}

void fillReport(const WorldState& w, ContactReport& r) {
  r.active = r.sliding = 0;
  r.maxPenetration = r.maxPenetrationRatio = 0;
  if (w.contact.fibres) fibreContactReport(w, r);
  if (w.contact.tools) toolContactReport(w, r);
}

// Largest centreline displacement since the state q0, mm.
double largestMotion(const Eigen::VectorXd& q, const Eigen::VectorXd& q0) {
  double m = 0;
  for (Index n = 0; n < Index(q.size() / kNodeDofs); ++n) m = std::max(m, (x0Of(q, n) - x0Of(q0, n)).norm());
  return m;
}

}  // namespace

void buildContact(WorldState& w) {
  const ContactDef& def = w.scene.contact;
  ContactSettings& s = w.contact;
  const double R = minRadius(w.fibres);
  s.tools = !w.scene.tools.empty();
  s.fibres = def.enabled;
  s.maxDetectionLoops = def.maxDetectionLoops;
  s.maxNormalLoops = def.maxNormalLoops;
  s.pRegRatio = def.regularisation;
  s.penaltyChange = def.penaltyChange;
  s.gMax = std::isfinite(def.maxReversibleSlip) ? def.maxReversibleSlip : 0.005 * R;
  s.toolProximity = def.proximityDistance;  // NaN: per fibre, systems/tool_contact.h
  s.symmetrised = def.frictionTangent == FrictionTangent::Symmetrised;
  const double pMax = std::isfinite(def.maxPenetration) ? def.maxPenetration : 0.005 * R;
  s.pMax = pMax;
  buildFibreContact(w);

  for (const ToolDef& t : w.scene.tools) {
    w.tools.name.push_back(t.name);
    w.tools.kind.push_back(t.kind);
    w.tools.point.push_back(t.point);
    w.tools.direction.push_back(t.direction);
    w.tools.radius.push_back(t.radius);
    w.tools.inside.push_back(t.inside);
    w.tools.motion.push_back(motionOf(t));
    w.tools.friction.push_back(t.friction);
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
  Eigen::VectorXd qDetected = w.fibres.q;
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
    // The elements of this pass were detected at qDetected: if the fibres have hardly moved
    // since, a new detection would find the same set.
    if (a == s.maxDetectionLoops ||
        (largestMotion(w.fibres.q, qDetected) <= s.particleTolerance * minRadius(w.fibres) &&
         change <= s.penaltyTolerance))
      break;
    qDetected = w.fibres.q;
    detect(w, tTry);
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

ContactCheckpoint contactCheckpoint(const WorldState& w) {
  return {w.history,      w.tools.penalty,   w.tools.reaction, w.zonePenalty,
          w.zones,        w.cache.zones.previous, w.cache.zones.nextId, w.elements,
          w.mechanics,    w.toolContacts,    w.system.r,       w.system.fext};
}

void restoreContact(WorldState& w, const ContactCheckpoint& c) {
  w.history = c.history;
  w.tools.penalty = c.toolPenalty;
  w.tools.reaction = c.toolReaction;
  w.zonePenalty = c.zonePenalty;
  w.zones = c.zones;
  w.cache.zones.previous = c.previousZones;
  w.cache.zones.nextId = c.nextZoneId;
  w.elements = c.elements;
  w.mechanics = c.mechanics;
  w.toolContacts = c.toolContacts;
  w.system.r = c.r;
  w.system.fext = c.fext;
  // The failed attempt may have changed the tangent's pattern: bind the restored elements to it.
  if (w.contact.fibres) registerFibreCliques(w);
}

}  // namespace fibra
