// Step driver: one increment of pseudo-time, as a list of stages.
//   1. target time of the next increment of the current scene step;
//   2. attempt: held DOFs moved to their targets, Newton on the free DOFs;
//   3. on failure, bisect the remaining interval (bounded by the step's maxCutbacks) and retry
//      from the last converged sub-state; never accept a non-converged state;
//   4. commit: time, increment and step counters.
#include "engine/contact_loops.h"
#include "engine/world_state.h"
#include "systems/boundary.h"
#include "systems/newton.h"
#include "systems/stabilisation.h"

#include <chrono>
#include <cmath>

namespace fibra {
namespace {

double stepStart(const WorldState& w, int step) {
  return step == 0 ? 0.0 : w.scene.steps[step - 1].endTime;
}

// |stabilisation force on the free DOFs| / F_ref at the converged state.
double stabilisationEffect(const WorldState& w) {
  const Eigen::VectorXd f = stabilisationForce(w.fibres, w.fibres.q, w.qStart, w.stabilisation);
  double free2 = 0;
  for (Index i = 0; i < w.system.freeCount; ++i) free2 += std::pow(f(w.system.dofOf[i]), 2);
  const double ref = std::max(w.system.fext.norm(), w.forceFloor);
  return std::sqrt(free2) / ref;
}

NewtonResult attempt(WorldState& w, const StepDef& st, double tTry, double tStart,
                     StepTimings& timings, ContactReport& contact) {
  w.solveTime = tTry;
  w.qStart = w.fibres.q;
  NewtonSettings settings;
  settings.maxIterations = st.maxIterations;
  settings.forceTolerance = st.forceTolerance;
  settings.incrementTolerance = st.incrementTolerance;
  settings.forceFloor = w.forceFloor;
  settings.lengthScale = w.lengthScale;
  settings.lineSearch = st.lineSearch;
  NewtonCallbacks cb;
  cb.assemble = [&w](bool withTangent) {
    w.withTangent = withTangent;
    w.iteration.run(w.def.trace);
  };
  cb.cancel = w.def.cancel;
  if (w.def.progress) {
    const double span = st.endTime - tStart;
    cb.progress = [&w, tTry, tStart, span](int it, double residual) {
      w.def.progress({w.step, tTry, (tTry - tStart) / span, it, residual});
    };
  }
  NewtonResult r;
  w.arena->execute([&] {
    if (hasContact(w)) {
      r = solveContactIncrement(w, tTry, settings, cb, timings, contact);
    } else {
      applyConstraints(w.fibres, w.constraints, w.groups, tTry, w.fibres.q);
      r = solveNewton(w.fibres.q, w.system, w.solver, settings, cb, timings);
    }
  });
  if (r.outcome == NewtonOutcome::Converged) contact.stabilisation = stabilisationEffect(w);
  return r;
}

}  // namespace

void assembleResidual(WorldState& w, double t) {
  w.solveTime = t;
  w.withTangent = false;
  w.arena->execute([&] { w.iteration.run(w.def.trace); });
}

StepReport advance(WorldState& w) {
  StepReport rep;
  if (w.step >= int(w.scene.steps.size())) return rep;
  const auto clock0 = std::chrono::steady_clock::now();
  const StepDef& st = w.scene.steps[w.step];
  const double tStart = stepStart(w, w.step);
  const double t1 = tStart + (w.increment + 1) * (st.endTime - tStart) / st.increments;
  rep.step = w.step;
  rep.increment = w.increment + 1;

  // The world always holds the last converged (sub-)state: q, its time, its contact state and
  // the residual assembled there.
  const Eigen::VectorXd qStart = w.fibres.q;
  const double timeStart = w.time;
  Eigen::VectorXd qGood = qStart;
  const ContactCheckpoint contactStart = contactCheckpoint(w);
  ContactCheckpoint contactGood = contactStart;
  double dt = t1 - w.time;
  while (w.time < t1) {
    const double tTry = w.time + dt >= t1 - 1e-12 * std::abs(t1) ? t1 : w.time + dt;
    const NewtonResult nr = attempt(w, st, tTry, tStart, rep.timings, rep.contact);
    rep.totalIterations += nr.iterations;
    rep.history = nr.history;
    if (nr.outcome == NewtonOutcome::Converged) {
      contactGood = contactCheckpoint(w);
      qGood = w.fibres.q;
      w.time = tTry;
      rep.iterations = nr.iterations;
      rep.residual = nr.residual;
      continue;
    }
    const bool cancelled = nr.outcome == NewtonOutcome::Cancelled;
    if (cancelled || ++rep.cutbacks > st.maxCutbacks) {
      w.fibres.q = qStart;
      w.time = timeStart;
      restoreContact(w, contactStart);
      rep.status = cancelled ? StepStatus::Cancelled : StepStatus::Failed;
      rep.message = cancelled ? "cancelled" : "increment to t = " + std::to_string(t1) +
                    " failed after " + std::to_string(st.maxCutbacks) + " cutbacks: " + nr.message;
      rep.time = w.time;
      rep.timings.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
      return rep;
    }
    rep.message += (rep.message.empty() ? "" : "; ") + std::string("cutback at t = ") +
                   std::to_string(tTry) + ": " + nr.message;
    w.fibres.q = qGood;
    restoreContact(w, contactGood);
    dt *= 0.5;
  }

  if (++w.increment == st.increments) {
    ++w.step;
    w.increment = 0;
  }
  rep.status = StepStatus::Converged;
  rep.time = t1;
  rep.loadFactor = (t1 - tStart) / (st.endTime - tStart);
  rep.timings.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  return rep;
}

}  // namespace fibra
