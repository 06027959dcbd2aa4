// Clears the linear system before an assembly: r = 0 on every DOF, and K's values = 0 (pattern
// kept) when the tangent is asked for.
//
// Reads  FibreStore (the DOF count), IterationInput (withTangent). Writes LinearSystem r, K.
#pragma once

#include "components/iteration.h"
#include "components/linear_system.h"

namespace fibra {

void clearSystem(const FibreStore& fibres, const IterationInput& input, LinearSystem& ls);

}  // namespace fibra
