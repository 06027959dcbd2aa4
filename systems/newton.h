// Newton system: Newton-Raphson with line search on the free DOFs, for a fixed set of contact
// elements and normals (paper section 4.4, third loop).
//
// Reads/writes the state q (free DOFs), LinearSystem (through the assemble callback, which
// fills r, fext and, when asked, K at the current q), and the LinearSolver.
//
// Iteration: K dq = -r_f; q += alpha dq with alpha = 1 (within the contact step limit), halved
// while the residual is not finite. Damping by the energy slope or the residual norm is
// measured to hurt here: the straight Newton line leaves the rotation manifold to second
// order, and the stiff axial and director-stretch modes then dominate both merits although the
// full step is right; plain Newton's residual routinely jumps by 10-1000x every other
// iteration on large rotations and still converges. So the optional line search is
// non-monotone (after Grippo, Lampariello and Lucidi, SIAM J. Numer. Anal. 23, 1986, on the
// relative residual): the step is accepted when |r_f(q + a dq)| <= kappa * max of the last M
// relative residuals (kappa = lineSearchFactor, M = lineSearchWindow), the first step of a
// pass always (after a load increment the predictor's residual is small and the first full
// step multiplies it by 1e3-1e6); otherwise a is halved, at most maxHalvings times, and the
// trial with the smallest residual is taken. Cutbacks of the increment remain the
// globalisation.
// Cycle damping (cycleDamping): Newton circling, as in the late crush of the 250-fibre yarn,
// where full steps swap two states of nearly the same residual (8.58e-3 and 8.88e-3 for 20
// iterations) while a dozen contact elements switch. When the last 2p residuals (at least 4)
// repeat with a period p <= maxCyclePeriod to 1e-2 relative, and the pass has come within the
// reference force (smallest residual below 1; further out Newton's residuals are erratic and
// cutbacks serve), the steps must bring the residual below the smallest so far by a relative
// 1e-4: the first that does not is halved, at most maxHalvings times, until it does, else the
// trial with the smallest residual is taken; then full steps again, and a repetition is sought
// only among the residuals after that step. Residuals falling by more than 1% an iteration do
// not repeat and are never damped (a steady fall slower than that counts as period 1); an
// exact repetition (1e-6) still stops the attempt.
// Norms: director forces (N mm) are divided by lengthScale, position increments too, so every
// component reads as a force (N) or a dimensionless increment.
// Converged when, after an iteration,
//   |r_f| <= forceTolerance * F_ref, F_ref = max(|f_ext|, |reactions|, forceFloor), and
//   max |dq_bar| <= incrementTolerance, dq_bar = -K^-1 r_f the correction the state still
//   needs, by one back-substitution with the factorisation at hand (no extra factorisation).
// forceFloor keeps F_ref above the residual's roundoff (the world uses 1e-4 E A).
// Inexact Newton: every solve is passed a forcing term eta_k (the GMRES strategies stop at
// |K dq + r_f| <= eta_k |r_f| when the solver's KrylovSettings::forcingMax is set; the exact ones
// ignore it), Eisenstat and Walker's choice 2 (SIAM J. Sci. Comput. 17, 1996, eq. 2.6 with
// gamma = 0.9, alpha = 2, and their safeguard): eta_1 = 1, eta_k = 0.9 (rho_k / rho_{k-1})^2,
// rho the relative residual, at least 0.9 eta_{k-1}^2 when that exceeds 0.1, and at least
// 0.5 forceTolerance / rho_k (no solve more accurate than the residual test can see), and 0
// (the solver's own tolerance) once rho_k passes the residual test and only the increment test
// is left, which wants exact directions; the solver clamps it to [tolerance, forcingMax]. The
// convergence check's correction dq_bar is solved to the solver's own tolerance (its error, not
// only its residual, must be small). The safeguard takes the unclamped eta_{k-1}.
// Fails (never silently): non-finite residual, singular tangent, relative residual beyond
// `divergence` times max(its first value, 1), stagnation, iteration limit, or cancellation.
// Stagnation, when a cutback serves better than more iterations: Newton cycles (the last 2p
// residuals repeat with a period p <= maxCyclePeriod to 1e-6 relative: stick/slip in dense
// frictional contact repeats exact cycles of up to 8 iterations), or it is stuck (no new
// smallest residual in the last stagnationWindow iterations, farStagnationWindow while no
// residual has come below 1, i.e. the attempt is still off by more than the reference force).
// A spike followed by a steady decrease, or a slow steady decrease, is neither. (Growth
// relative to the first value alone is normal here: after a small, accurate predictor the
// first full step routinely multiplies the residual by 1e3-1e6 on slender fibres and still
// converges quadratically.)
#pragma once

#include "components/linear_system.h"
#include "core/report.h"
#include "systems/linear_solver.h"

#include <functional>

namespace fibra {

struct NewtonSettings {
  int maxIterations = 30;
  double forceTolerance = 1e-8;       // relative to F_ref
  double incrementTolerance = 1e-10;  // relative to lengthScale (positions) or absolute (directors)
  double forceFloor = 1e-12;          // N: F_ref floor for unloaded states
  double lengthScale = 1;             // mm
  bool lineSearch = false;            // non-monotone residual line search (see above)
  int lineSearchWindow = 5;           // M: residuals the acceptance bound looks back on
  double lineSearchFactor = 3;        // kappa: accepted growth over their largest
  int maxHalvings = 5;                // halvings of a step (non-finite residual, line search)
  bool cycleDamping = false;          // damped steps once the residuals repeat (see above); off
                                      // here, on from a scene (solver.cycle_damping)
  double divergence = 1e6;            // relative residual that aborts the attempt
  int stagnationWindow = 20;          // iterations without a new smallest residual: stuck
  int farStagnationWindow = 10;       // the same while every residual is above 1 (F_ref)
  int maxCyclePeriod = 8;             // longest cycle of residuals detected
};

enum class NewtonOutcome { Converged, Failed, Cancelled };

struct NewtonResult {
  NewtonOutcome outcome = NewtonOutcome::Failed;
  int iterations = 0;
  double residual = 0;  // final relative residual
  double smallest = INFINITY;  // smallest relative residual after an iteration
  int dampedSteps = 0;  // steps the cycle damping halved
  int longestPass = 0;  // iterations of the longest Newton pass (contact: of the nested loops)
  std::vector<NewtonRecord> history;
  std::string message;
};

struct NewtonCallbacks {
  std::function<void(bool withTangent)> assemble;  // fill ls at the current q
  // Largest step length in (0, 1] along the full-DOF direction dq from the current q (contact:
  // no element may close deeper than a few p_max in one step); none: 1.
  std::function<double(const Eigen::VectorXd& dq)> stepLimit;
  std::function<void(int iteration, const NewtonRecord& record)> progress;  // after each iteration
  std::function<bool()> cancel;
};

// |f on the free DOFs| / F_ref, F_ref = max(|f_ext|, |r on the held DOFs| (the reactions),
// forceFloor), director components divided by lengthScale (N). f: one entry per DOF (N, N mm);
// f = ls.r gives Newton's relative residual.
double relativeToReference(const LinearSystem& ls, const Eigen::VectorXd& f, double lengthScale,
                           double forceFloor);

// Eisenstat-Walker's forcing term eta_k for the solve after relative residual rho (see above);
// previous: the relative residual before the last step (<= 0 at a pass's first solve), eta: the
// last forcing term. Dimensionless, in [0, 1] (0: the solver's tolerance).
double forcingTerm(double rho, double previous, double eta, double forceTolerance);

NewtonResult solveNewton(Eigen::VectorXd& q, LinearSystem& ls, LinearSolver& solver,
                         const NewtonSettings& settings, const NewtonCallbacks& callbacks,
                         StepTimings& timings);

}  // namespace fibra
