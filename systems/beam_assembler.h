// Beam assembler: adds every beam element's internal force to the residual and its tangent to
// the sparse matrix.
//
// Reads  FibreStore (order, element nodes), BeamStore (points, colours), the state q,
//        LinearSystem scatter maps (beam element e is clique e).
// Writes LinearSystem::r (adds f_int on every DOF), LinearSystem::K values (adds K_e).
// Threading: elements of one colour share no node, so they scatter in parallel without
// conflicts; the colours run one after the other. Every matrix and residual entry therefore
// receives its contributions in a fixed order: the result does not depend on the thread count.
#pragma once

#include "components/beam_store.h"
#include "components/linear_system.h"

namespace fibra {

void assembleBeams(const FibreStore& fibres, const BeamStore& beams, const Eigen::VectorXd& q,
                   bool withTangent, LinearSystem& ls);

// Total strain energy, N mm (serial, for reports and tests).
double beamEnergy(const FibreStore& fibres, const BeamStore& beams, const Eigen::VectorXd& q);

}  // namespace fibra
