// Contact queries: quantities the nested loops and the reports read off the contact state,
// fibre-fibre and fibre-tool elements alike. Pure functions over const stores, called directly
// by the driver (they change no store, so they are not task-graph stages).
//
// stepLimit           the largest step length a in (0, 1] along dq (all DOFs) such that no
//                     element closes deeper than allowed = stepPenetration p_max in one Newton
//                     step, and none already in contact closes by more than that:
//                     dg = N . (dx^I - dx^J) (x^I, x^J: the particles the last normal force
//                     acted on, facing ones where it had them: systems/facing_particles.h),
//                     a = min over closing elements (dg < 0) of
//                     max(g + allowed, allowed) / -dg, g the gap at the last evaluation. (An
//                     absolute bound g + a dg >= -allowed froze Newton when the penalty was too
//                     soft for the load: the element sat at -allowed and every step had a = 0.)
// deepestDetected     the largest penetration of the elements at their detection (or last
//                     normal update), as a multiple of their zone's p_max.
// fillContactReport   counts (zones, elements, active, sliding, refined zones) and the largest
//                     penetration.
// trueOverlap         over the elements of a detection from the state q: the fibres' overlap near
//                     each element's sections, measured from the centrelines and the deformed
//                     directors, not from the element's particles or normal. The sections are
//                     moved to the closest points of the two centrelines within one element
//                     (systems/contact_sections.h, closestSectionsNear: held at a fibre's end
//                     where the distance still falls past it), where d = x0I - x0J is normal to
//                     both fibres; there the overlap is w_I + w_J - |d_t|, d_t = P_t d the part of
//                     d across the mean tangent t (d itself at closest points; it matters where
//                     no closest pair is found: parallel fibres, a pair kept where it was),
//                     along n = d_t / |d_t|, w = R |G^T n| the fibre's half-width along n
//                     (G = [g1 g2] the deformed directors, R the radius in section
//                     coordinates): the largest of n . G xi over the outline |xi| = R, which is
//                     also the width of the union of the sections near it since n is normal to
//                     the fibre. (Measured at the element's own sections along the centres'
//                     direction, as before, it read a crossing whose sections lie apart along
//                     the fibres through a sheared section's length: the plectoneme's loop over
//                     the clamped end, sections sheared 6.6 deg, 1.54 p_max where the fibres
//                     crossed with 0.82, and the increment failed as inconsistent. A section
//                     sheared by gamma from the normal plane is a disc seen edge-on along its
//                     tilt: the fibre is R cos gamma wide there; taking the outline point's
//                     distance R instead over-stated the overlap by R (1 - cos gamma), 0.8
//                     p_max at the 5-degree shear of a twisted rod in self-contact.) Where the
//                     closest pair ends on a fibre's end and the other centre lies beyond that
//                     end's plane, and on an end-face element (kEndFaceI/J, at its particle),
//                     the end face's point's depth below the other fibre's surface,
//                     w - |P_t (x - x0)| with w its half-width along P_t (x - x0) (the face
//                     point closest to the other centre: a rim). 0 when none overlaps; mm.
//                     Independent of the elements a state was solved with: it measures what
//                     they may under-report. A forced element's depth is at its own sections,
//                     less the overlap its step still allows (ContactParams::forcedAllowance),
//                     as its gap is. `centrelines`: the state q's (computed by the detection).
//                     `ratios` (optional): receives each element's overlap / its zone's p_max.
// falseForce          over the elements of the set the state q was solved with (`used`) that
//                     push (R_N > 0 at the last evaluation) with their fibres parallel at their
//                     sections (within theta_parallel: N is then the line of centres and g the
//                     sections' own gap; a crossing's elements carry its force through eq. 10's
//                     tangent lines with their own sections apart, and forced elements take
//                     the procedure's normal), the fibres' clearance near the
//                     element: minus their largest overlap within one element length of its
//                     sections, each section x_I(s) of I's window against J's closest point in
//                     J's window, w_I + w_J - |d| along the line between them (support
//                     functions), the best of 33 samples refined by golden section; an end-face
//                     element by its face's depth, as trueOverlap. The window, not the element's
//                     own sections: Gauss elements that straddle a crossing carry its force
//                     through eq. 10's tangent lines while their own sections stand clear. The
//                     largest as a multiple of the element's p_max, with the element's own
//                     sections (where it pushes). An element that
//                     pushes where the fibres near it stand clear carries a force no contact
//                     makes: its normal N lags behind the line of centres, so g = d . N < 0
//                     while |d| > w_I + w_J (a normal loop left unsettled after a slip). Mm; 0
//                     when every pushing element's fibres touch.
// compareContactSets  a detection from the accepted state (`fresh`) against the set the state
//                     was solved with (`used`): zones paired by id; zones without a partner or
//                     with another element count are counted; elements of paired zones paired
//                     by index, those closed in either set: the largest |g_fresh - g_used| /
//                     p_max (g_fresh on facing particles along the fresh normal where the used
//                     element's force acted on facing particles, systems/facing_particles.h:
//                     like for like) and the largest particle
//                     shift sqrt(ds^2 + |dxi|^2) / R of either side (s arc length, xi section
//                     coordinates, R the side's radius); forced elements' gaps with their
//                     allowance, as the solve measured them.
// toolOverlap         a tool's deepest overlap with the fibres: max over sections of w - d, d the
//                     centroid's signed distance from the tool's surface at time t and
//                     w = R |G^T n| the section's half-width along the surface normal n there
//                     (G = [g1 g2] the section's directors), the sections at kToolOverlapCuts + 1
//                     evenly spaced parameters of every element (its end nodes among them); from
//                     the state alone, with no contact element. The scene check's warning for a
//                     tool placed inside the fibres.
#pragma once

#include "components/contact_cache.h"
#include "components/contact_params.h"
#include "components/contact_state.h"
#include "components/tools.h"
#include "core/report.h"
#include "systems/interpolation.h"

#include <Eigen/Core>
#include <vector>

namespace fibra {

// The report counts an element as sliding when its friction force is at least this share of
// the Coulomb limit mu R_N (a re-detected element starts a little inside the limit: its
// reversible slip is interpolated from the recorded history).
inline constexpr double kSlidingShare = 0.99;
inline bool sliding(double normalForce, const Vec3& gRev, double gMax) {
  return normalForce > 0 && gRev.norm() >= kSlidingShare * gMax;
}

double stepLimit(const ContactParams& params, const ContactState& state, const Eigen::VectorXd& dq);

double deepestDetected(const ContactState& state);

// Fills zones, elements, toolElements, active, sliding, maxPenetration, maxPenetrationRatio,
// refinedZones.
void fillContactReport(const ContactParams& params, const ContactState& state, ContactReport& r);

// Half-width of a fibre along a unit direction n normal to its centreline at section S: R |G^T n|,
// the largest n . (xi1 g1 + xi2 g2) over the outline |xi| = R (R: the radius in section
// coordinates, mm; G = [g1 g2]); mm.
double halfWidth(const Section& S, double R, const Vec3& n);

// The true overlap of a detection: the deepest in mm, and the largest as a multiple of the
// element's own p_max (its zone's: contact pairs may give classes different ones), with where
// that one is.
struct Overlap {
  double depth = 0;                // largest overlap over the elements, mm; 0 when none
  double ratio = 0;                // largest overlap / the element's zone p_max
  Index fibreI = -1, fibreJ = -1;  // the fibres of the element of `ratio`, -1 when none
  double sI = 0, sJ = 0;           // the reference arc lengths where it was measured, mm
};
Overlap trueOverlap(const FibreStore& fibres, const Eigen::VectorXd& q,
                    const CentrelineStore& centrelines, const ContactState& detected,
                    const ContactParams& params, std::vector<double>* ratios = nullptr);

// The largest clearance of the fibres at an element of `used` that pushes (mm, and as a multiple
// of that element's p_max), with where; `centrelines`: the state q's.
Overlap falseForce(const FibreStore& fibres, const Eigen::VectorXd& q,
                   const CentrelineStore& centrelines, const ContactState& used,
                   const ContactParams& params);

// Tool `tool`'s deepest overlap with the fibres of state q at pseudo-time t (mm; 0 and element -1
// when none overlaps it), and where: the element and its parameter z in [-1, 1].
struct ToolOverlap {
  double depth = 0;
  Index element = -1;
  double z = 0;
};
inline constexpr int kToolOverlapCuts = 8;  // pieces of an element between the sampled sections
// A tool overlapping the fibres by more than this many of its p_max at a scene's start is warned
// of by `fibra check` and `fibra run` (a tool placed inside the fibres, not one in light contact).
inline constexpr double kToolStartOverlap = 10;
ToolOverlap toolOverlap(const FibreStore& fibres, const Eigen::VectorXd& q, const ToolStore& tools,
                        Index tool, double time);

// Fills r.redetectZoneChanges, redetectGapChange, redetectParticleShift.
void compareContactSets(const FibreStore& fibres, const ContactState& used,
                        const ContactState& fresh, const ContactParams& params, ContactReport& r);

}  // namespace fibra
