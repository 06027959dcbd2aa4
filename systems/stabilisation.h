// Stabilisation system: a spring from the free DOFs of the selected fibres to their values at
// the start of the increment, for fibres held only by contact (DESIGN.md 1.4).
//
// Reads  FibreStore (q, radius), the increment's start state q_n, the per-node stiffness.
// Writes LinearSystem r (+= k (q - q_n)) and K (+= k on the diagonal). Parallel over nodes
// (each node writes its own entries). Returns nothing; the driver measures the force left at
// convergence, |k (q - q_n)|, and reports it relative to the reference force.
//   Pi_s = 1/2 sum_n k_n (|x0 - x0_n|^2 + R^2 |g1 - g1_n|^2 + R^2 |g2 - g2_n|^2)
#pragma once

#include "components/linear_system.h"

namespace fibra {

// k per node (N/mm), 0 where off.
void assembleStabilisation(const FibreStore& fibres, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& qStart, const std::vector<double>& nodeStiffness,
                           bool withTangent, LinearSystem& ls);

// The stabilisation forces of the state q (one entry per DOF, N or N mm).
Eigen::VectorXd stabilisationForce(const FibreStore& fibres, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& qStart,
                                   const std::vector<double>& nodeStiffness);

}  // namespace fibra
