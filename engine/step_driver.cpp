// Step driver: one increment of pseudo-time, as a list of stages.
//   1. target time of the next increment of the current scene step;
//   2. attempt: trial contact state = committed; held DOFs moved to their targets, the free ones
//      by the secant predictor (startAttempt); Newton on the free DOFs (with contact: the nested
//      loops of engine/contact_loops.h);
//   3. converged: commit (swap trial and committed, keep q, r, f_ext) and go on to the target;
//      failed: discard the trial (back to the last converged q, r, f_ext); with contact
//      normal_update "auto" an attempt with loop B's normals is tried again at its size with
//      every fibre normal linearised, and back (retryNormals); an attempt that
//      started from the predictor is tried again at its size without it, any other cuts the
//      attempt's size (bounded by the step's maxCutbacks) and retry; never accept a non-converged
//      state. Where nothing the scene prescribes changes over the failed attempt and the step
//      has no damping, a smaller attempt would repeat it exactly (a forced allowance changes
//      with time: nothingPrescribedChanges): the step fails at once; with damping_from
//      "failure", there and after the last cutback, the viscous continuation comes on instead,
//      for the rest of the step (dampingOn), and takes the increment again. The
//      attempt size adapts (nextIncrement): it grows back after easy attempts, up to the
//      nominal increment, and carries over to the next increment of the step, whose end is
//      always reached exactly (frames and history rows stay on the nominal times);
//   4. at the target: time, increment and step counters.
// After a failure or a cancellation the world is at its last converged state: the start of the
// increment, or the last sub-increment that converged after a cutback.
#include "core/format.h"
#include "engine/contact_loops.h"
#include "engine/world_state.h"
#include "systems/beam_evaluation.h"
#include "systems/boundary.h"
#include "systems/contact_queries.h"
#include "systems/element_stretch.h"
#include "systems/energy_balance.h"
#include "systems/newton.h"
#include "systems/stabilisation.h"

#include <chrono>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

namespace fibra {
namespace {

double stepStart(const WorldState& w, int step) {
  return step == 0 ? 0.0 : w.scene.steps[step - 1].endTime;
}

// Whether a table takes one value over [a, b] (at both ends and at its breakpoints between).
bool constantOver(const Table& table, double a, double b) {
  const double v = tableValue(table, a);
  if (tableValue(table, b) != v) return false;
  for (double t : table.t)
    if (t > a && t < b && tableValue(table, t) != v) return false;
  return true;
}

// Whether the loads, the held DOFs' motion, the tools' motion and the step's forced allowance
// (released with t) are all constant over [a, b]: then, without damping, an attempt from a to
// any time in (a, b] solves the same equations from the same state (the friction history and
// the stabilisation's anchor are those of the converged state at a).
bool nothingPrescribedChanges(const SceneDef& s, const StepDef& st, double a, double b) {
  if (st.forcedAllowance > 0) return false;
  // A table scales a vector: a zero vector's table changes nothing.
  const auto moves = [&](const Vec3& v, const Table& t) {
    return !v.isZero(0) && !constantOver(t, a, b);
  };
  const auto turns = [&](bool rotates, const Table& t) {
    return rotates && !constantOver(t, a, b);
  };
  for (const LoadDef& l : s.loads)
    if (moves(l.vector, l.table)) return false;
  for (const BcDef& c : s.bcs)
    if (moves(c.displacement, c.displacementTable) || turns(c.rotates, c.angle)) return false;
  for (const ToolDef& t : s.tools)
    if (moves(t.displacement, t.displacementTable) || turns(t.rotates, t.angle)) return false;
  return true;
}

// What a step that failed after all its cutbacks can change, with the values it ran with, split
// into what a `--resume` takes and what needs a fresh run (engine/checkpoint.cpp's fingerprint
// refuses the rest); `size` is its last attempt's increment (t units).
std::string cutbackAdvice(const SceneDef& scene, const StepDef& st, double size) {
  const bool damped = anyStepDamped(scene);  // a resume takes a new damping only then
  const std::string damping = st.damping > 0 ? "a larger `damping` (now " + number(st.damping) + ")"
                                             : std::string("a `damping`");
  std::string resume = "a larger `max_iterations` (now " + std::to_string(st.maxIterations) +
                       ") or `max_cutbacks` (now " + std::to_string(st.maxCutbacks) + ")";
  std::string fresh = "more `increments` (now " + std::to_string(st.increments) + ")";
  (damped ? resume : fresh) += ", " + damping;
  if (st.forcedNormal.squaredNorm() > 0)
    fresh += st.forcedAllowance > 0 ? ", a larger `forced_normals.allowance` (now " +
                                          number(st.forcedAllowance) + " mm)"
                                    : ", a `forced_normals.allowance`";
  return " (the last attempt was an increment of " + number(size) + "; to go on, with `--resume`: " +
         resume + "; in a fresh run, also: " + fresh + ")";
}

// |f on the free DOFs| / F_ref at the converged state, as in Newton's test.
double relativeFree(const WorldState& w, const Eigen::VectorXd& f) {
  return relativeToReference(w.system, f, w.lengthScale, w.forceFloor);
}

// The secant predictor is dropped where it raises |r_free| at the attempt's start more than
// this factor over the start without it: on load-controlled bending (the roll-up, the
// cantilever) the extrapolated state is 1e5-1e6 x further out and Newton takes 15-20% more
// iterations from it; on prescribed motion (twist, squeeze, drag) it is 0.01-1.9 x and saves
// 20-60% (docs/METHOD.md "Secant predictor").
constexpr double kPredictorRise = 10;

// |r_free|, the weighted 2-norm of systems/newton.cpp (director rows over the length scale), N.
double freeResidual(const WorldState& w) {
  double r2 = 0;
  for (Index d = 0; d < Index(w.system.r.size()); ++d)
    if (w.system.equation[d] >= 0)
      r2 += std::pow(w.system.r(d) * (d % kNodeDofs < 3 ? 1.0 : 1 / w.lengthScale), 2);
  return std::sqrt(r2);
}

NewtonSettings newtonSettings(const WorldState& w, const StepDef& st) {
  NewtonSettings settings;
  settings.maxIterations = st.maxIterations;
  settings.forceTolerance = st.forceTolerance;
  settings.incrementTolerance = st.incrementTolerance;
  settings.forceFloor = w.forceFloor;
  settings.lengthScale = w.lengthScale;
  settings.lineSearch = st.lineSearch;
  settings.cycleDamping = w.scene.solver.cycleDamping;
  return settings;
}

// The failed attempts listed by noteFailure ("<what followed> at t = <t>: <why>; ..."), counted,
// the first two and the last three in full and the count of those between.
std::string earlierAttempts(const std::string& list) {
  static const std::regex next("; (?=(cutback|predictor off|every fibre normal linearised|loop B's "
                               "normals again|damping on) at t = )");
  const std::vector<std::string> items(
      std::sregex_token_iterator(list.begin(), list.end(), next, -1), {});
  std::string out = counted(int(items.size()), "failed attempt") +
                    " of the increment (what followed at t: why): ";
  for (size_t i = 0; i < items.size(); ++i) {
    if (items.size() > 5 && i == 2)
      out += "... " + std::to_string(items.size() - 5) + " more ...; ";
    if (items.size() > 5 && i >= 2 && i + 3 < items.size()) continue;
    out += items[i] + (i + 1 < items.size() ? "; " : "");
  }
  return out;
}

// Appends a failed attempt to the increment's list: what followed it, at its end tTry, and why.
void noteFailure(StepReport& rep, const std::string& followed, double tTry,
                 const NewtonResult& nr) {
  rep.message += (rep.message.empty() ? "" : "; ") + followed + " at t = " + number(tTry) + ": " +
                 nr.message;
}

// Contact normal_update "auto": an attempt that failed with the loop's normals (the fixed point
// of loop B, the frictionless parallel ones linearised where it diverged) is tried again, from
// the same start and at the same size, with every fibre normal linearised (as "newton");
// converged, the step keeps them (linearisedStep); failed, the step retries no more
// (escalationFailedStep). A kept attempt (after a retry or a switch, slowNormalLoop) that fails
// is retried with the loop's normals at the same size, and the step keeps those for good
// (linearisedFailedStep). A failed retry leaves the step where the attempt before it was: what
// follows (predictor off, or the cutback's size) is judged by that attempt.
// A retry needs a fibre normal that linearising changes (`linearisable`: the failed attempt's
// last detection has one that is neither forced nor an end face's); without one it would repeat
// the attempt exactly. Returns whether the attempt at tTry is to be tried again; `escalating`
// says whether that retry linearises every normal. Each change goes into rep.normalChanges.
bool retryNormals(WorldState& w, const NewtonResult& nr, double tTry, bool linearisable,
                  bool& escalating, StepReport& rep) {
  escalating = false;
  if (!w.contact.escalateNormals || !w.contact.fibres || nr.outcome != NewtonOutcome::Failed)
    return false;
  std::string retry;
  if (!w.contact.allNormals) {
    if (w.escalationFailedStep == w.step || w.linearisedFailedStep == w.step || !linearisable)
      return false;
    escalating = true;
    retry = "every fibre normal linearised";
  } else {
    const bool kept = w.linearisedStep == w.step;
    (kept ? w.linearisedFailedStep : w.escalationFailedStep) = w.step;
    w.linearisedStep = -1;
    rep.normalChanges.push_back(kept ? NormalChange::BackToLoop : NormalChange::RetryFailed);
    if (!kept) return false;
    retry = "loop B's normals again";
  }
  ++rep.normalRetries;
  noteFailure(rep, retry, tTry, nr);
  return true;
}

// Whether the attempt's last detection (w.trial) has a fibre-fibre element whose normal "auto"
// would linearise: not forced (constant) and not an end face's (systems/normal_linearisation.h).
bool anyLinearisable(const WorldState& w) {
  const ContactElementStore& el = w.trial.elements;
  for (Index e = 0; e < el.size(); ++e)
    if (!(el.fallback[e] & (kEndFaceI | kEndFaceJ)) && !el.forced[e]) return true;
  return false;
}

// Contact normal_update "auto", without a failure: an accepted attempt with loop B's normals that
// took more than max_iterations Newton iterations over its passes, and more Newton passes than
// detections (loop B updated the normals and solved again), has paid for the normals' fixed
// point; the step's next attempts linearise every fibre normal (linearisedStep), unless a kept
// linearised attempt of the step has failed already (a failed retry does not stop it: the
// first contact increment's retry may fail from its start where later ones converge). A
// linearised attempt that then fails is retried with loop B's normals at its size
// (retryNormals), and the step keeps those. Nothing switches where no attempt of the step follows
// (`stepGoesOn` false: the step's last increment has reached its end).
bool slowNormalLoop(const WorldState& w, const StepDef& st, const NewtonResult& nr,
                    const ContactReport& c, bool stepGoesOn) {
  return stepGoesOn && w.contact.escalateNormals && w.contact.fibres && !w.contact.allNormals &&
         w.linearisedFailedStep != w.step && nr.iterations > st.maxIterations &&
         c.normalLoops > c.detectionLoops;
}

// Size of the next attempt after this one (pseudo-time): doubled after an attempt whose longest
// Newton pass converged in at most half the iteration limit (with contact an attempt is up to
// n_A x n_B passes), up to the nominal increment; halved after a
// failure, quartered when no iteration came within the reference force (smallest relative
// residual above 1: far outside Newton's basin). Factors of 2 keep every size a power-of-two
// fraction of the nominal increment.
double nextIncrement(double dt, double nominal, const StepDef& st, const NewtonResult& nr) {
  if (nr.outcome == NewtonOutcome::Converged)
    return 2 * nr.longestPass <= st.maxIterations ? std::min(2 * dt, nominal) : dt;
  if (nr.outcome == NewtonOutcome::Cancelled) return dt;
  return dt * (nr.smallest > 1 ? 0.25 : 0.5);
}

// Whether the step's viscous continuation acts on its attempts now: from the step's start, or,
// with damping_from "failure", once an increment of the step has failed without it.
bool dampingOn(const WorldState& w, const StepDef& st) {
  return st.damping > 0 && (st.dampingFrom == DampingFrom::Start || w.dampedStep == w.step);
}

// The trial starts from the last converged state; the continuation's c/dt for its size; the
// step's forced normals (zero: the normal rules) for the detections and normal updates, the
// overlap they allow at the attempt's end time tTry, A (t_end - tTry) / (t_end - t_start), and
// its factor on the friction coefficients.
void beginAttempt(WorldState& w, const StepDef& st, double tTry, double tStart) {
  const double size = tTry - w.time;
  if (hasContact(w)) w.trial = w.committed;
  w.contact.forcedNormal = st.forcedNormal;
  w.contact.forcedAllowance =
      st.forcedAllowance * std::max(0.0, st.endTime - tTry) / (st.endTime - tStart);
  w.contact.frictionFactor = st.frictionFactor;
  w.contact.unstableNormals = false;
  setSymmetric(w, symmetricTangent(w));
  w.stabilisation.qStart = w.fibres.q;
  w.stabilisation.viscous = dampingOn(w, st) ? st.damping / size : 0;
}

// The work of every force over the attempt that converged (systems/energy_balance.h), before
// its start state is overwritten.
void balanceEnergy(WorldState& w) {
  EnergyForces now;
  energyForces(w.fibres, w.constraints, w.system, hasContact(w) ? &w.committed : nullptr, now);
  Eigen::VectorXd springs;
  if (w.stabilisation.active)
    springs = springForce(w.fibres, w.stabilisation) + viscousForce(w.fibres, w.stabilisation);
  const double strain = beamEnergy(w.fibres, w.beams, w.fibres.q) - w.energy.strainAtStart;
  accumulateEnergy(w.energy.last, now, w.converged.q, w.fibres.q, springs, strain,
                   w.energy.balance);
  w.energy.last = std::move(now);
}

// The attempt converged: its state becomes the last converged one.
void commit(WorldState& w, double time) {
  if (hasContact(w)) std::swap(w.committed, w.trial);
  balanceEnergy(w);
  w.rate = (w.fibres.q - w.converged.q) / (time - w.time);  // per unit pseudo-time, per DOF
  w.rateStep = w.step;
  w.converged.q = w.fibres.q;
  w.converged.r = w.system.r;
  w.converged.fext = w.system.fext;
  w.time = time;
}

// The attempt failed or was cancelled: back to the last converged state.
void discard(WorldState& w) {
  w.fibres.q = w.converged.q;
  w.system.r = w.converged.r;
  w.system.fext = w.converged.fext;
}

// Why fibre f's element could fold, and what to change (docs/METHOD.md "Folded elements").
std::string foldCause(const WorldState& w, Index f) {
  if (w.materials.law[w.fibres.material[f]] == MaterialLaw::SaintVenantKirchhoff)
    return "a spurious state of the Saint Venant-Kirchhoff energy, which softens beyond 42% "
           "compression; a fibre bent this tightly needs the material law \"neo_hookean\" and "
           "axial integration \"full\"";
  if (w.scene.fibres[f].integration.axial == AxialRule::Reduced)
    return "the element is distorted between its axial integration points; axial integration "
           "\"full\" leaves it no such mode";
  return "the fibre is bent or twisted more tightly than its elements resolve; more elements";
}

// A converged state with a folded element is a spurious equilibrium of the material law
// (systems/element_stretch.h): the attempt fails, and is cut.
void rejectFolded(const WorldState& w, NewtonResult& r) {
  const StretchCheck c = smallestStretch(w.fibres, w.fibres.q);
  if (c.element < 0 || c.smallest >= kFoldedStretch) return;
  const Index f = w.fibres.elementFibre[c.element];
  r.outcome = NewtonOutcome::Failed;
  r.message = std::string("an element folded: ") +
              (c.volume ? "section volume ratio " : "axial stretch ") + number(c.smallest) +
              " in element " + std::to_string(c.element - w.fibres.firstElement[f]) +
              " of fibre '" + w.fibres.name[f] + "' (below " + number(kFoldedStretch) + ": " +
              foldCause(w, f) + ")";
}

// Where the free residual is largest (Progress::largest).
std::string largestResidual(const WorldState& w) {
  static const char* const component[kNodeDofs] = {"x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z"};
  Index best = -1;
  double m = -1;
  for (Index d = 0; d < w.system.r.size(); ++d) {
    if (w.system.equation[d] < 0) continue;
    const double v = std::abs(w.system.r(d)) * (d % kNodeDofs < 3 ? 1.0 : 1 / w.lengthScale);
    if (v > m) m = v, best = d;
  }
  if (best < 0) return "";
  const Index node = best / kNodeDofs, f = w.fibres.nodeFibre[node];
  return "fibre '" + w.fibres.name[f] + "' node " + std::to_string(node - w.fibres.firstNode[f]) + " " +
         component[best % kNodeDofs];
}

// What the progress callback is told after Newton iteration `it` of the attempt at tTry.
Progress progressOf(const WorldState& w, const NewtonRecord& rec, int it, double tTry, double load) {
  const LinearSolveStats& ls = w.solver.stats();
  Progress p{w.step, tTry, load, it, rec.residual, rec.lineSearch, ls.lastTolerance, ls.lastReached,
             ls.lastKrylovIterations, 0, 0, 0, {}};
  if (hasContact(w)) {
    ContactReport c;
    fillContactReport(w.contact, w.trial, c);
    p.activeElements = c.active, p.slidingElements = c.sliding, p.deepest = c.maxPenetrationRatio;
  }
  p.largest = largestResidual(w);
  return p;
}

NewtonResult attempt(WorldState& w, const StepDef& st, double tTry, double tStart,
                     StepReport& rep) {
  StepTimings& timings = rep.timings;
  ContactReport& contact = rep.contact;
  beginAttempt(w, st, tTry, tStart);
  NewtonCallbacks cb;
  cb.assemble = [&w, tTry](bool withTangent) { runStage(w, w.pipeline.assemble, tTry, withTangent); };
  cb.cancel = [&w] { return w.cancel(); };
  if (w.def.progress) {
    const double span = st.endTime - tStart;
    cb.progress = [&w, tTry, tStart, span](int it, const NewtonRecord& rec) {
      w.def.progress(progressOf(w, rec, it, tTry, (tTry - tStart) / span));
    };
  }
  const NewtonSettings settings = newtonSettings(w, st);
  NewtonResult r;
  w.arena->execute([&] {
    if (hasContact(w)) {
      r = solveContactIncrement(w, tTry, settings, cb, timings, contact);
    } else {
      startAttempt(w, tTry);
      r = solveNewton(w.fibres.q, w.system, w.solver, settings, cb, timings);
    }
  });
  if (r.outcome == NewtonOutcome::Converged) rejectFolded(w, r);
  if (r.outcome == NewtonOutcome::Converged && w.stabilisation.active) {
    contact.stabilisation = relativeFree(w, springForce(w.fibres, w.stabilisation));
    rep.viscousForce = relativeFree(w, viscousForce(w.fibres, w.stabilisation));
  }
  return r;
}

}  // namespace

// The attempt from q_n (converged at t_n = w.time) to tTry starts, where w.predict, from the
// secant predictor q_n + (tTry - t_n) v_n, v_n = (q_n - q_{n-1}) / (t_n - t_{n-1}) the rate of
// the step's last converged attempt (commit), on the free DOFs; the held DOFs go to their
// targets either way. The predictor is kept unless it raises |r_free| above kPredictorRise times
// that of the start without it (then w.predict is cleared).
void startAttempt(WorldState& w, double tTry) {
  applyConstraints(w.fibres, w.constraints, w.groups, tTry, w.fibres.q);
  if (!w.predict) return;
  assembleResidual(w, tTry);
  const double held = freeResidual(w);
  const Eigen::VectorXd q0 = w.fibres.q;
  w.fibres.q += (tTry - w.time) * w.rate;
  applyConstraints(w.fibres, w.constraints, w.groups, tTry, w.fibres.q);
  assembleResidual(w, tTry);
  if (!(freeResidual(w) <= kPredictorRise * held)) {
    w.fibres.q = q0;
    w.predict = false;
  }
}

void runStage(WorldState& w, TaskGraph& stage, double t, bool withTangent) {
  w.input.time = t;
  w.input.withTangent = withTangent;
  w.arena->execute([&] { stage.run(w.def.trace); });
}

void assembleResidual(WorldState& w, double t) { runStage(w, w.pipeline.assemble, t, false); }

// The solver's counts since the increment began (its stats are reset then).
LinearReport linearReport(const LinearSolveStats& s) {
  return {s.analyses, s.factorisations, s.solves, s.fallbacks, s.krylovIterations,
          s.maxKrylovIterations, s.krylovFailures};
}

StepReport advance(WorldState& w) {
  StepReport rep;
  if (w.step >= int(w.scene.steps.size())) return rep;
  w.solver.resetStats();
  w.solver.forgetPattern();  // a run resumed at this increment factorises on the same patterns
  const auto clock0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  };
  const StepDef& st = w.scene.steps[w.step];
  const double tStart = stepStart(w, w.step);
  const double t1 = tStart + (w.increment + 1) * (st.endTime - tStart) / st.increments;
  rep.step = w.step;
  rep.increment = w.increment + 1;
  w.cancel.arm(w.def.cancel);

  // Stops at the last converged state with a status and a message.
  // A failure's message ends with the increment's failed attempts before it.
  const auto stop = [&](StepStatus status, const std::string& message) {
    rep.status = status;
    rep.message = status != StepStatus::Failed || rep.message.empty()
                      ? message
                      : message + ". Before it, " + earlierAttempts(rep.message);
    rep.time = w.time;
    rep.loadFactor = (w.time - tStart) / (st.endTime - tStart);
    rep.timings.total = elapsed();
    rep.energy = w.energy.balance;
    rep.linear = linearReport(w.solver.stats());
    return rep;
  };
  const double nominal = (st.endTime - tStart) / st.increments;
  if (w.increment == 0 || !(w.dt > 0)) w.dt = nominal;
  int spent = 0;  // cutbacks before the continuation came on (damping_from "failure")
  bool retried = false;  // a predicted attempt failed: the increment goes on without the predictor
  bool escalating = false;  // the attempt retries a failed one with every fibre normal linearised
  NewtonResult beforeRetry;  // the failed attempt that the retry repeats
  int refined = 0;  // zones refined by the acceptance of the increment's converged attempts
  while (w.time < t1) {
    const double tTry = w.time + w.dt >= t1 - 1e-9 * nominal ? t1 : w.time + w.dt;
    if (!(tTry - w.time > 1e-12 * std::max(std::abs(t1), nominal)))
      return stop(StepStatus::Failed, "increment to t = " + number(t1) +
                                          " failed: the attempt size fell to " +
                                          number(tTry - w.time) +
                                          ", the round-off of the pseudo-time");
    w.predict = st.predictor && !retried && w.rateStep == w.step;
    w.contact.allNormals = escalating || w.linearisedStep == w.step;
    const NewtonResult nr = attempt(w, st, tTry, tStart, rep);
    rep.totalIterations += nr.iterations;
    rep.dampedSteps += nr.dampedSteps;
    rep.history = nr.history;
    if (nr.outcome == NewtonOutcome::Converged) {
      const double size = tTry - w.time;
      rep.smallestIncrement = rep.subIncrements++ ? std::min(rep.smallestIncrement, size) : size;
      rep.predicted += w.predict;
      refined += rep.contact.newlyRefinedZones;
      rep.contact.newlyRefinedZones = refined;
      commit(w, tTry);
      const bool stepGoesOn = tTry < t1 || w.increment + 1 < st.increments;
      const bool slow = slowNormalLoop(w, st, nr, rep.contact, stepGoesOn);
      rep.normalsSwitched |= slow;
      if (escalating) rep.normalChanges.push_back(NormalChange::RetryConverged);
      if (slow) rep.normalChanges.push_back(NormalChange::Switched);
      if (w.contact.allNormals || slow) w.linearisedStep = w.step;
      rep.normalsLinearised = w.contact.allNormals;
      escalating = false;
      rep.iterations = nr.iterations;
      rep.residual = nr.residual;
      w.dt = nextIncrement(w.dt, nominal, st, nr);
      retried = false;
      continue;
    }
    const bool linearisable = anyLinearisable(w);
    discard(w);
    const bool wasRetry = escalating;
    if (retryNormals(w, nr, tTry, linearisable, escalating, rep)) {
      if (escalating) beforeRetry = nr;
      continue;
    }
    // A failed retry with every normal linearised: the step goes on as the attempt before it
    // would have, its size judged by that attempt (nextIncrement).
    const NewtonResult& judged = wasRetry ? beforeRetry : nr;
    if (w.predict && nr.outcome == NewtonOutcome::Failed) {
      retried = true;
      ++rep.predictorRetries;
      noteFailure(rep, "predictor off", tTry, nr);
      continue;
    }
    w.dt = nextIncrement(tTry - w.time, nominal, st, judged);
    const bool cancelled = nr.outcome == NewtonOutcome::Cancelled;
    if (cancelled) return stop(StepStatus::Cancelled, "cancelled");
    const bool stuck = !dampingOn(w, st) && nothingPrescribedChanges(w.scene, st, w.time, tTry);
    if ((stuck || rep.cutbacks - spent >= st.maxCutbacks) && st.damping > 0 && !dampingOn(w, st)) {
      // damping_from "failure": load control cannot go on; the continuation takes the
      // increment again from its last converged state, at the nominal size, and acts to the
      // step's end with cutbacks of its own
      w.dampedStep = w.step;
      rep.dampedFrom = w.time;
      spent = rep.cutbacks;
      w.dt = nominal;
      retried = false;
      noteFailure(rep, "damping on", tTry, nr);
      continue;
    }
    if (stuck)
      return stop(StepStatus::Failed,
                  "increment to t = " + number(t1) + " failed: " + nr.message +
                      "; a smaller increment would repeat this attempt exactly: nothing the "
                      "scene prescribes changes from t = " + number(w.time) + " to " +
                      number(tTry) + " and the step has no damping (ramp the loads or the "
                      "motion over the step with a table, or give the step a `damping`, the "
                      "viscous continuation, so that a smaller increment is a smaller change" +
                      std::string(st.forcedNormal.squaredNorm() > 0
                                      ? "; or `forced_normals.allowance`, the overlap the step "
                                        "removes in equal parts"
                                      : "") +
                      ")");
    if (++rep.cutbacks - spent > st.maxCutbacks)
      return stop(StepStatus::Failed, "increment to t = " + number(t1) + " failed after " +
                                          counted(st.maxCutbacks, "cutback") + ": " + nr.message +
                                          cutbackAdvice(w.scene, st, tTry - w.time));
    noteFailure(rep, "cutback", tTry, nr);
  }

  if (++w.increment == st.increments) {
    ++w.step;
    w.increment = 0;
  }
  rep.status = StepStatus::Converged;
  rep.time = t1;
  rep.loadFactor = (t1 - tStart) / (st.endTime - tStart);
  rep.timings.total = elapsed();
  rep.energy = w.energy.balance;
  rep.linear = linearReport(w.solver.stats());
  return rep;
}

}  // namespace fibra
