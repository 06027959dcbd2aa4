// Beam scatter: adds every beam element's force and tangent (BeamForceStore) into the linear
// system.
//
// Reads  FibreStore (element nodes), BeamStore (colours), BeamForceStore, IterationInput
//        (withTangent), LinearSystem scatter maps (beam element e is clique e).
// Writes LinearSystem::r (+= f_e on the element's DOFs), LinearSystem::K values (+= K_e).
// Threading: elements of one colour share no node, so they scatter in parallel without
// conflicts; the colours run one after the other. Every matrix and residual entry therefore
// receives its contributions in a fixed order: the result does not depend on the thread count.
#pragma once

#include "components/beam_forces.h"
#include "components/beam_store.h"
#include "components/iteration.h"
#include "components/linear_system.h"

namespace fibra {

void scatterBeams(const FibreStore& fibres, const BeamStore& beams, const BeamForceStore& forces,
                  const IterationInput& input, LinearSystem& ls);

}  // namespace fibra
