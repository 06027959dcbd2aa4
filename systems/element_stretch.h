// Element stretch check: the smallest axial stretch of the fibres' centrelines, to reject a
// state where an element has folded.
//
// Reads  FibreStore (order, element nodes, q, qRef).
// Computes lambda(z) = dx0/dz(z) . t / |dX0/dz(z)| at z = -1, -1/2, 0, 1/2, 1 of every element,
//        t the unit tangent at the element's middle: the centreline's stretch along the
//        element's own direction (negative where it runs back: a fold; bending within an element
//        lowers it only by the cosine of the turn from its middle), and returns the smallest
//        with its element. Serial; 5 points per element.
// Why: Saint Venant-Kirchhoff's energy, W = E/8 (lambda^2 - 1)^2 along the axis, stays finite as
// lambda goes through 0, so Newton can converge to an element compressed through zero length
// and folded (samples/two_beams_sliding.json's first step in 10 increments: B's first element
// folded, 14 N of tension in B where the path in 25 increments has 0.66 N). No fibre of the
// applications comes near lambda = 1/2 along its axis; the step driver rejects a converged
// attempt below kFoldedStretch and cuts it (docs/METHOD.md "Folded elements").
#pragma once

#include "components/fibres.h"

namespace fibra {

inline constexpr double kFoldedStretch = 0.5;

struct StretchCheck {
  double smallest = 1;  // smallest lambda, - (negative: folded back)
  Index element = -1;   // where; -1 without elements
};

StretchCheck smallestStretch(const FibreStore& fibres, const Eigen::VectorXd& q);

}  // namespace fibra
