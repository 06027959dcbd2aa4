// Stabilisation system: a spring from the free DOFs of the selected fibres to their values at
// the start of the increment, for fibres held only by contact (DESIGN.md 1.4).
//
// Reads  FibreStore (q, radius), StabilisationStore (per-node stiffness, the increment's start
//        state q_n), IterationInput (withTangent).
// Writes LinearSystem r (+= k (q - q_n)) and K (+= k on the diagonal). Parallel over nodes
// (each node writes its own entries). The driver measures the force left at convergence,
// |k (q - q_n)| (stabilisationForce), and reports it relative to the reference force.
//   Pi_s = 1/2 sum_n k_n (|x0 - x0_n|^2 + R^2 |g1 - g1_n|^2 + R^2 |g2 - g2_n|^2)
#pragma once

#include "components/iteration.h"
#include "components/linear_system.h"
#include "components/stabilisation.h"

namespace fibra {

void assembleStabilisation(const FibreStore& fibres, const StabilisationStore& stabilisation,
                           const IterationInput& input, LinearSystem& ls);

// The stabilisation forces of the state fibres.q (one entry per DOF, N or N mm).
Eigen::VectorXd stabilisationForce(const FibreStore& fibres, const StabilisationStore& stabilisation);

}  // namespace fibra
