// Stabilisation system: a spring from the free DOFs of the selected fibres to their values at
// the start of the attempt, for fibres held only by contact (DESIGN.md 1.4), and the step's
// viscous continuation on every free DOF.
//
// Reads  FibreStore (q, radius), StabilisationStore (per-node stiffness k_n, the attempt's c/dt,
//        its start state q_n), IterationInput (withTangent).
// Writes LinearSystem r (+= (k_n + c/dt) (q - q_n)) and K (+= k_n + c/dt on the diagonal).
//        Parallel over nodes (each node writes its own entries).
//   Pi_s = 1/2 sum_n (k_n + c/dt) (|x0 - x0_n|^2 + R^2 |g1 - g1_n|^2 + R^2 |g2 - g2_n|^2)
// The continuation is implicit Euler on the viscous flow c dq/dt = -r(q) in pseudo-time
// (pseudo-transient continuation): its force c (q - q_n)/dt vanishes only where the state stops
// moving, and it grows as cutbacks shrink dt, so that an attempt past a limit point of the
// static path becomes easier, not harder. The driver reports both forces at convergence,
// relative to the reference force (springForce, viscousForce).
#pragma once

#include "components/iteration.h"
#include "components/linear_system.h"
#include "components/stabilisation.h"

namespace fibra {

void assembleStabilisation(const FibreStore& fibres, const StabilisationStore& stabilisation,
                           const IterationInput& input, LinearSystem& ls);

// The spring forces k_n (q - q_n) of the state fibres.q (one entry per DOF, N or N mm).
Eigen::VectorXd springForce(const FibreStore& fibres, const StabilisationStore& stabilisation);
// The viscous forces (c/dt) (q - q_n) (one entry per DOF, N or N mm).
Eigen::VectorXd viscousForce(const FibreStore& fibres, const StabilisationStore& stabilisation);

}  // namespace fibra
