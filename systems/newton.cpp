#include "systems/newton.h"

#include "core/format.h"

#include <chrono>
#include <cmath>

namespace fibra {
namespace {

// Residuals that repeat to this relative tolerance are a cycle that stops the attempt; to
// kCycleDamping, over at least kCycleDampingRecords of them and within the reference force,
// one that arms the cycle damping (newton.h).
constexpr double kCycleRepeats = 1e-6;
constexpr double kCycleDamping = 1e-2;
constexpr int kCycleDampingRecords = 4;

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Context {
  Eigen::VectorXd& q;
  LinearSystem& ls;
  LinearSolver& solver;
  const NewtonSettings& settings;
  const NewtonCallbacks& cb;
  StepTimings& timings;
  Eigen::VectorXd rf, dq, dqBar;

  // Assembles at the current q; returns |r_f| / F_ref.
  double assemble(bool withTangent) {
    const auto t0 = Clock::now();
    cb.assemble(withTangent);
    timings.assemble += since(t0);
    rf.resize(ls.freeCount);
    for (Index i = 0; i < ls.freeCount; ++i) rf(i) = ls.r(ls.dofOf[i]);
    return relativeToReference(ls, ls.r, settings.lengthScale, settings.forceFloor);
  }

  // max |v_i| over free DOFs, positions divided by the length scale.
  double scaledMax(const Eigen::VectorXd& v) const {
    double m = 0;
    for (Index i = 0; i < v.size(); ++i)
      m = std::max(m, std::abs(v(i)) * (ls.dofOf[i] % kNodeDofs < 3 ? 1 / settings.lengthScale : 1.0));
    return m;
  }

  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double forcing) {
    const auto t0 = Clock::now();
    solver.solve(b, x, forcing);
    timings.solve += since(t0);
  }

  double moveTo(const Eigen::VectorXd& q0, double a, bool withTangent) {
    q = q0;
    for (Index i = 0; i < ls.freeCount; ++i) q(ls.dofOf[i]) += a * dq(i);
    return assemble(withTangent);
  }

  // The step direction on every DOF (zero on the held ones).
  Eigen::VectorXd fullStep() const {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(q.size());
    for (Index i = 0; i < ls.freeCount; ++i) d(ls.dofOf[i]) = dq(i);
    return d;
  }

  // Step length a and the relative residual at q0 + a dq: the full Newton step (within the
  // contact step limit), halved while the residual is not finite. With a bound `accept` (the
  // line search's, or the cycle damping's: see newton.h; infinite when neither applies):
  // halved while the residual exceeds it, at most maxHalvings times, keeping the trial with
  // the smallest residual. Leaves ls assembled with the tangent at the chosen q.
  struct Step {
    double a, residual;
    bool halved;  // the full step missed the bound
  };
  Step step(double accept) {
    const Eigen::VectorXd q0 = q;
    double a = cb.stepLimit ? std::clamp(cb.stepLimit(fullStep()), 1e-6, 1.0) : 1.0;
    double res = moveTo(q0, a, true);
    for (int k = 0; k < settings.maxHalvings && !std::isfinite(res); ++k) res = moveTo(q0, a *= 0.5, true);
    if (!std::isfinite(res) || res <= accept) return {a, res, false};
    double best = res, bestA = a;
    for (int k = 0; k < settings.maxHalvings && !(res <= accept); ++k) {
      res = moveTo(q0, a *= 0.5, false);
      if (res < best) best = res, bestA = a;
    }
    return {bestA, moveTo(q0, bestA, true), true};
  }
};

// Smallest residual of the records [from, to).
double smallest(const std::vector<NewtonRecord>& h, int from, int to) {
  double m = INFINITY;
  for (int i = from; i < to; ++i) m = std::min(m, h[i].residual);
  return m;
}

// The last max(2p, least) residuals (of the records from `from` on) repeat with period p (to
// `tol` relative), for some p <= maxPeriod; returns p, or 0.
int cyclePeriod(const std::vector<NewtonRecord>& h, int maxPeriod, double tol, int from = 0,
                int least = 0) {
  const int n = int(h.size());
  for (int p = 1; p <= maxPeriod && std::max(2 * p, least) <= n - from; ++p) {
    bool repeats = true;
    for (int i = 1; i <= std::max(p, least - p) && repeats; ++i) {
      const double a = h[n - i].residual, b = h[n - i - p].residual;
      repeats = std::abs(a - b) <= tol * std::max(std::abs(a), std::abs(b));
    }
    if (repeats) return p;
  }
  return 0;
}

// Whether the residuals after `fresh` circle close to the solution (cycle damping); least:
// the smallest residual of the pass.
bool circling(const std::vector<NewtonRecord>& h, double least, const NewtonSettings& s,
              int fresh) {
  return least < 1 &&
         cyclePeriod(h, s.maxCyclePeriod, kCycleDamping, fresh, kCycleDampingRecords) > 0;
}

// No new smallest residual in the last w records.
bool stuck(const std::vector<NewtonRecord>& h, int w) {
  const int n = int(h.size());
  return w > 0 && n > w && smallest(h, n - w, n) >= smallest(h, 0, n - w);
}

// The line search's acceptance bound for the next step: kappa times the largest of the last
// `window` relative residuals (the current one included); none for the first step of a pass.
double acceptance(const std::vector<NewtonRecord>& h, double current, const NewtonSettings& s) {
  if (h.empty()) return INFINITY;
  double m = current;
  for (int k = 1; k < s.lineSearchWindow && k <= int(h.size()); ++k) m = std::max(m, h[h.size() - k].residual);
  return s.lineSearchFactor * m;
}

// The bound the next step must meet: the line search's (kappa times the last residuals), and
// for a damped step a residual below the smallest so far (least) by a relative 1e-4;
// INFINITY: none.
double stepBound(const std::vector<NewtonRecord>& h, double current, double least,
                 const NewtonSettings& s, bool damped) {
  double bound = s.lineSearch ? acceptance(h, current, s) : INFINITY;
  if (damped) bound = std::min(bound, (1 - 1e-4) * least);
  return bound;
}

// Why the attempt stagnates, or "" when it does not.
std::string stagnation(const std::vector<NewtonRecord>& h, const NewtonSettings& s) {
  char m[200];
  const int n = int(h.size());
  const double last = n ? h.back().residual : 0;
  if (const int p = cyclePeriod(h, s.maxCyclePeriod, kCycleRepeats); p > 0) {
    std::snprintf(m, sizeof m, "stagnation: the residual repeats a cycle of %d iteration%s (last %.3g)",
                  p, p > 1 ? "s" : "", last);
    return m;
  }
  const bool far = n && smallest(h, 0, n) > 1;
  const int w = far ? s.farStagnationWindow : s.stagnationWindow;
  if (!stuck(h, w)) return "";
  std::snprintf(m, sizeof m, "stagnation: no smaller residual in %d iterations (smallest %.3g%s, last %.3g)",
                w, smallest(h, 0, n), far ? ", above the reference force" : "", last);
  return m;
}

}  // namespace

double forcingTerm(double rho, double previous, double eta, double forceTolerance) {
  if (rho <= forceTolerance) return 0;  // only the increment test is left: exact directions
  if (!(previous > 0)) return 1;
  double next = 0.9 * std::pow(rho / previous, 2);
  if (0.9 * eta * eta > 0.1) next = std::max(next, 0.9 * eta * eta);
  next = std::max(next, 0.5 * forceTolerance / rho);
  return std::min(next, 1.0);
}

double relativeToReference(const LinearSystem& ls, const Eigen::VectorXd& f, double lengthScale,
                           double forceFloor) {
  double fFree2 = 0, rFree2 = 0, rAll2 = 0, ext2 = 0;
  for (Index d = 0; d < ls.r.size(); ++d) {
    // director forces (N mm) divided by the length scale: every component reads as a force
    const double w2 = std::pow(d % kNodeDofs < 3 ? 1.0 : 1 / lengthScale, 2);
    rAll2 += w2 * ls.r(d) * ls.r(d);
    ext2 += w2 * ls.fext(d) * ls.fext(d);
    if (ls.equation[d] >= 0) rFree2 += w2 * ls.r(d) * ls.r(d), fFree2 += w2 * f(d) * f(d);
  }
  const double ref = std::max({std::sqrt(ext2), std::sqrt(std::max(rAll2 - rFree2, 0.0)), forceFloor});
  return std::sqrt(fFree2) / ref;
}

NewtonResult solveNewton(Eigen::VectorXd& q, LinearSystem& ls, LinearSolver& solver,
                         const NewtonSettings& settings, const NewtonCallbacks& cb,
                         StepTimings& timings) {
  Context c{q, ls, solver, settings, cb, timings, {}, {}, {}};
  NewtonResult res;
  res.residual = c.assemble(true);
  if (res.residual <= settings.forceTolerance) {
    res.outcome = NewtonOutcome::Converged;
    return res;
  }
  const double first = res.residual;
  double previous = 0, eta = 1;  // the residual before the last step, the last forcing term
  bool damped = false;  // cycle damping armed: the steps meet its bound until one is halved
  int fresh = 0;        // the first record after the last halved step: cycles are sought there
  for (int it = 1; it <= settings.maxIterations; ++it) {
    if (cb.cancel && cb.cancel()) {
      res.outcome = NewtonOutcome::Cancelled;
      res.message = "cancelled";
      return res;
    }
    const auto t0 = Clock::now();
    const bool ok = solver.factorise(ls, res.message);
    timings.factorise += since(t0);
    if (!ok) return res;
    eta = forcingTerm(res.residual, previous, eta, settings.forceTolerance);
    c.solve(-c.rf, c.dq, eta);
    previous = res.residual;

    const auto [alpha, residual, halved] =
        c.step(stepBound(res.history, res.residual, res.smallest, settings, damped));
    if (damped && halved) damped = false, fresh = int(res.history.size()) + 1, ++res.dampedSteps;
    res.iterations = res.longestPass = it;
    res.residual = residual;
    res.smallest = std::min(res.smallest, residual);
    res.history.push_back({residual, alpha * c.scaledMax(c.dq), alpha});
    if (cb.progress) cb.progress(it, res.history.back());
    if (!std::isfinite(residual)) {
      res.message = "non-finite residual at iteration " + std::to_string(it);
      return res;
    }
    if (residual <= settings.forceTolerance) {
      // the correction still needed, with the factorisation at hand
      c.solve(-c.rf, c.dqBar, 0);  // exact: a small residual need not mean a small error
      if (c.scaledMax(c.dqBar) <= settings.incrementTolerance) {
        res.outcome = NewtonOutcome::Converged;
        res.message.clear();
        return res;
      }
    }
    if (res.message = stagnation(res.history, settings); !res.message.empty()) return res;
    if (settings.cycleDamping && circling(res.history, res.smallest, settings, fresh))
      damped = true;
    if (residual > settings.divergence * std::max(first, 1.0)) {
      res.message = "diverging: residual grew from " + number(first) + " to " + number(residual);
      return res;
    }
  }
  res.message = "no convergence in " + counted(settings.maxIterations, "iteration") +
                " (residual " + number(res.residual) + ")";
  return res;
}

}  // namespace fibra
