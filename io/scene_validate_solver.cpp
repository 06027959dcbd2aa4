// Scene validation of the solver section (docs/SCENE.md "Solver"): ranges, and the settings
// that apply only to some linear strategies (systems/linear_solver.h).
#include "io/validate_checks.h"

#include "systems/linear_solver.h"

namespace fibra::validate_checks {

void validateSolver(const SolverDef& s) {
  if (!(s.krylov.tolerance > 0 && s.krylov.tolerance < 1))
    fail("solver.krylov_tolerance", "must be in (0, 1), got " + num(s.krylov.tolerance));
  atLeast(s.krylov.restart, 1, "solver.krylov_restart");
  atLeast(s.krylov.maxIterations, 1, "solver.krylov_max_iterations");
  atLeast(s.krylov.refactorAbove, 1, "solver.refactor_above");
  if (!(s.krylov.blrTolerance >= 0 && s.krylov.blrTolerance < 1))
    fail("solver.blr_tolerance", "must be in [0, 1), got " + num(s.krylov.blrTolerance));
  // Only MUMPS builds a block low-rank factor: anywhere else the setting would be ignored.
  if (s.krylov.blrTolerance > 0 && s.strategy != LinearStrategy::Mumps &&
      s.strategy != LinearStrategy::Auto)
    fail("solver.blr_tolerance",
         "applies to the strategies mumps and auto (mumps from " +
             std::to_string(kMumpsFromEquations) + " equations), not to '" +
             strategyName(s.strategy) + "'");
  inRange(s.krylov.coarseSegments, 1, 1000, "solver.coarse_segments");
  // Only the Schwarz strategy has a coarse level (auto takes it on a heavy fill).
  if (s.krylov.coarseSegments != KrylovSettings{}.coarseSegments &&
      s.strategy != LinearStrategy::Schwarz && s.strategy != LinearStrategy::Auto)
    fail("solver.coarse_segments", std::string("applies to the strategies schwarz and auto, not to '") +
                                       strategyName(s.strategy) + "'");
  if (s.krylov.coarseRotations != KrylovSettings{}.coarseRotations &&
      s.strategy != LinearStrategy::Schwarz && s.strategy != LinearStrategy::Auto)
    fail("solver.coarse_rotations", std::string("applies to the strategies schwarz and auto, not to '") +
                                         strategyName(s.strategy) + "'");
  const double slack = s.krylov.patternSlack;
  if (!(slack == 0 || (slack >= 1 && slack <= 100)))
    fail("solver.pattern_slack", "must be 0 (off) or in [1, 100], got " + num(slack));
  if (!(s.krylov.forcingMax >= 0 && s.krylov.forcingMax < 1))
    fail("solver.forcing_max", "must be in [0, 1), got " + num(s.krylov.forcingMax));
  // Only a GMRES solve can stop early; the direct strategies would ignore it.
  const LinearStrategy st = s.strategy;
  if (s.krylov.forcingMax > 0 && (st == LinearStrategy::Direct || st == LinearStrategy::Umfpack ||
                                  (st == LinearStrategy::Mumps && !(s.krylov.blrTolerance > 0))))
    fail("solver.forcing_max", std::string("applies to the GMRES strategies (schwarz, krylov, "
                                           "krylov-lu, mumps with blr_tolerance, auto), not to '") +
                                   strategyName(st) + "'");
}

}  // namespace fibra::validate_checks
