// Element stretch check: the smallest axial stretch and section volume ratio of the fibres, to
// reject a state where an element has folded or a section has collapsed.
//
// Reads  FibreStore (order, element nodes, q, qRef).
// Computes at z = -1, -1/2, 0, 1/2, 1 of every element
//          lambda(z) = dx0/dz(z) . t / |dX0/dz(z)|, t the unit tangent at the element's middle:
//                      the centreline's stretch along the element's own direction (negative
//                      where it runs back: a fold; bending within an element lowers it only by
//                      the cosine of the turn from its middle);
//          J(z) = det[dx0/dz, g1, g2] / det[dX0/dz, G1, G2]: the volume ratio at the centreline
//                      (axial stretch times section area, negative when the section has turned
//                      over against the axis),
//        and returns the smallest of them with its element. Serial; 5 points per element.
// Why: Saint Venant-Kirchhoff's energy stays finite as a stretch goes through 0, so Newton can
// converge to an element compressed through zero length and folded, or to a section tilted into
// the axis (samples/two_beams_sliding.json's first step in 10 increments: B's first element
// folded, lambda = -1.58; in 5: lambda 0.73 but a director tilted into the axis, J < 0; 14 N and
// 4.3 N of tension in B where the path in 25 increments has 0.66 N). No fibre of the
// applications comes near lambda or J = 1/2; the step driver rejects a converged attempt below
// kFoldedStretch and cuts it (docs/METHOD.md "Folded elements").
#pragma once

#include "components/fibres.h"

namespace fibra {

inline constexpr double kFoldedStretch = 0.5;

struct StretchCheck {
  double smallest = 1;  // smallest lambda or J, - (negative: folded back, turned over)
  Index element = -1;   // where; -1 without elements
  bool volume = false;  // the smallest is a volume ratio J (else a stretch lambda)
};

StretchCheck smallestStretch(const FibreStore& fibres, const Eigen::VectorXd& q);

}  // namespace fibra
