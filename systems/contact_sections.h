// Nearest sections in the eq. 8 plane: a contact element's pair of sections moved, within the
// plane of its intermediate point, to the local minimum of their centreline distance; and the
// closest sections of two crossing fibres, that minimum without the plane.
//
// Reads  FibreStore (lengths, element counts), CentrelineStore (the element polynomials).
// Writes nothing: a pure function of its arguments (called per contact element by
//        systems/contact_elements.cpp).
//
// Eq. 8 cuts both fibres by the plane through x_int(zeta) normal to t_int(zeta). Where the
// zone's linear map sI(zeta) <-> sJ(zeta) follows the fibres badly - a strand that wraps around
// another (the ply of a plectoneme), a zone whose ends slide at different rates - the two cuts
// are not facing: their centres lie apart along the fibres, the axial part of D = x_I - x_J is
// taken out of the normal (systems/contact_normals.h), and the gap reports the distance of two
// sections that do not touch while the fibres overlap nearby (a fibre wound round a core, the
// pair 0.2 mm apart along it: 0.0044 mm of overlap missed, tests/test_contact_sections.cpp; on
// bench/plectoneme.json most of the under-report is sampling instead, docs/RESULTS.md). The
// nearest pair keeps what makes eq. 8 well posed on parallel fibres - the pair's midpoint stays
// in the plane - and within it minimises the centreline distance:
//   min f = |x_I(sI) - x_J(sJ)|^2 / 2   subject to   c = ((x_I + x_J) / 2 - x_int) . t = 0,
// by Newton on the KKT system in (sI, sJ, lambda), with d = x_I - x_J, t_f = dx_f/ds:
//   r = [d . t_I + lambda/2 t_I . t,  -d . t_J + lambda/2 t_J . t,  c]
//   dr = [[t_I.t_I + d.x_I'' + lambda/2 x_I''.t,  -t_I.t_J,  t_I.t / 2],
//         [-t_I.t_J,  t_J.t_J - d.x_J'' + lambda/2 x_J''.t,  t_J.t / 2],
//         [t_I.t / 2,  t_J.t / 2,  0]]
// from the eq. 8 pair (c = 0 there; lambda from least squares), each step limited to h / 4 of
// the fibre. On straight parallel fibres the eq. 8 pair is this minimum already (moving the
// sections apart in the plane lengthens d). Kept when Newton converges (|step| <= 1e-10 h) to a
// minimum along the plane's constraint (the Hessian of the Lagrangian positive on c's tangent),
// inside the windows [aI, bI], [aJ, bJ] (mm) and, on one fibre (I == J), with sJ - sI >= sep.
#pragma once

#include "components/contact_cache.h"
#include "components/fibres.h"

namespace fibra {

struct SectionWindows {
  double aI, bI, aJ, bJ;  // where the sections may lie on I and J, mm of arc length
};

// sI, sJ (mm): in, the eq. 8 sections; out, the nearest pair when found (true), unchanged
// otherwise. xInt (mm) and t (unit) are the plane's point and normal; I == J for self-contact,
// with sJ - sI >= sep (mm) kept.
bool nearestSectionsInPlane(const FibreStore& fs, const CentrelineStore& cl, Index I, Index J,
                            const Vec3& xInt, const Vec3& t, const SectionWindows& w, double sep,
                            double& sI, double& sJ);

// Closest sections (the paper's minimum-distance pairing for crossings, section 3.1.1): the
// local minimum of the centreline distance near (sI, sJ), by Newton on
//   F(sI, sJ) = [d . tI, -d . tJ] = 0,  d = xI(sI) - xJ(sJ), t = dx/ds,
//   dF = [[tI . tI + d . xI'', -tI . tJ], [-tI . tJ, tJ . tJ - d . xJ'']].
// The eq. 8 plane through the intermediate point cuts curved fibres away from their closest
// points when the zone's one test point is not at them: at woven crossings the gap was measured
// 0.05 mm off, reporting 0.65 p_max where the fibres overlapped by 9. Fibre ends bound the
// search: where a step leaves a window at its fibre's end (a window bound at s = 0 or L), that
// section is held at the end while the distance still falls past it (F's component outwards
// there, o F_k < 0, o = -1 at s = 0, +1 at L) and Newton goes on in the other alone
// (dF_kk > 0): a fibre crossing over another's end comes closest to it past the end, and the
// minimum over the fibre is at its end section (the end's rim under the other fibre: 5.8e-4 mm
// reported where it was 1.87e-3 deep, tests/test_fibre_ends.cpp; the plectoneme's loop across
// its clamped end). A
// step past a window bound inside the fibre finds nothing. Kept only when Newton converges
// (|step| <= 1e-10 h) inside the windows to a minimum (dF positive definite at every free step),
// with sJ - sI >= sep on one fibre (I == J), and the fibres make more than thetaParallel (rad)
// there (nearly parallel fibres have no well-posed closest pair). sI, sJ (mm): in, the start;
// out, the closest sections when found (true), unchanged otherwise. `curvature` (when given) then
// receives the smaller eigenvalue of dF there, held ends or not (dimensionless: s in mm along
// fibres of unit stretch).
bool closestSectionsNear(const FibreStore& fs, const CentrelineStore& cl, Index I, Index J,
                         const SectionWindows& w, double thetaParallel, double sep, double& sI,
                         double& sJ, double* curvature = nullptr);

}  // namespace fibra
