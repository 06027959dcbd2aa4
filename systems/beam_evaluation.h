// Beam evaluation: every beam element's internal force and tangent at the current state, into
// the BeamForceStore (systems/beam_scatter.h adds them to the linear system).
//
// Reads  FibreStore (order, element nodes, q), BeamStore (points), IterationInput (withTangent).
// Writes BeamForceStore (f_e, and K_e when the tangent is asked for; sized on first use).
// Threading: parallel over elements, each writing its own entries; independent of the thread
// count. Runs beside the contact laws: it writes nothing they read.
//   f_e = dPi_e/dq_e,  K_e = d2Pi_e/dq_e2,  Pi_e = sum_p 1/2 e_p^T D_p e_p   (systems/beam_element.h)
#pragma once

#include "components/beam_forces.h"
#include "components/beam_store.h"
#include "components/iteration.h"

namespace fibra {

void evaluateBeams(const FibreStore& fibres, const BeamStore& beams, const IterationInput& input,
                   BeamForceStore& forces);

// Total strain energy of the state q, N mm (serial, for reports and tests).
double beamEnergy(const FibreStore& fibres, const BeamStore& beams, const Eigen::VectorXd& q);

}  // namespace fibra
