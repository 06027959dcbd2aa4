// Stick and slip within a Newton pass (docs/METHOD.md, "Stick and slip within a pass").
//
// The return mapping of eqs. 15-16 is not differentiable where |t| = g_T,max: in stick the
// friction has the stiffness (mu R_N / g_max) P in every tangential direction, in slip none along
// the slip direction. An element whose solution lies near that circle makes Newton jump between
// the two branches, and a dense bundle repeats such jumps in exact cycles (measured: 8 elements
// of a squeezed 7-fibre bundle alternating every iteration, relative residual 1e-3). So:
//   - within a pass, an element whose branch changed `maxFlips` times between assemblies with
//     the tangent is held in the branch it has then, for the rest of the pass (the law with a
//     held status: systems/contact_law.h), and Newton solves a smooth problem;
//   - at the end of the pass, a held element is consistent when its trial slip is on its branch's
//     side of the circle within a relative tolerance tol: stick |t| <= (1 + tol) g_max, slip
//     |t| >= (1 - tol) g_max. Both branches give the same force on the circle, so within tol the
//     friction force is off by at most tol mu R_N. An inconsistent element is held in the other
//     branch for the next pass (the contact loops run one more).
// Reads/writes FrictionStatusStore; element by element, no threading of their own (called from
// the parallel law loops on distinct elements, or once per pass).
#pragma once

#include "components/friction_status.h"
#include "systems/contact_law.h"

namespace fibra {

// The store sized for n elements; a store of another size is reset (a new contact set).
void sizeFrictionStatus(FrictionStatusStore& s, Index n);

// Every element free again (a new detection: the elements are new).
void clearFrictionStatus(FrictionStatusStore& s);

// A new Newton pass: flip counts and last statuses cleared, held statuses kept.
void openFrictionPass(FrictionStatusStore& s);

// Element e after an evaluation of the law: its trial ratio; with the tangent, a change of branch
// counted, and the branch held once it changed maxFlips times (maxFlips <= 0: never held).
void trackFrictionStatus(FrictionStatusStore& s, Index e, const ContactLawResult& r,
                         bool withTangent, int maxFlips);

// End of a converged pass: held elements off their branch by more than tol switched to the other
// branch (kept held); returns how many.
Index settleFrictionStatus(FrictionStatusStore& s, double tol);

// Held elements now, and the largest relative excess of a held element over its branch's side
// of the circle (0 when every held element is consistent).
struct HeldFriction {
  Index held = 0;
  double excess = 0;
};
HeldFriction heldFriction(const FrictionStatusStore& s);

}  // namespace fibra
