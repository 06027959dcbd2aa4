// Beam force store: each beam element's internal force and tangent at the last evaluation
// (systems/beam_evaluation.h), kept per element so that the evaluation runs beside the contact
// laws and only the scatter into the linear system is serialised. No logic here.
#pragma once

#include "core/types.h"

#include <vector>

namespace fibra {

struct BeamForceStore {
  // --- per element: offsets into the flat arrays (n = 9 x nodes of the element) ---
  std::vector<Index> forceFirst;     // first of its n entries in `force`
  std::vector<Index> tangentFirst;   // first of its n x n entries in `tangent` (row-major)
  // --- flat ---
  std::vector<double> force;         // f_e = dPi/dq_e, N (x0) or N mm (directors)
  std::vector<double> tangent;       // K_e = d2Pi/dq_e2 (when assembled with the tangent)
};

}  // namespace fibra
