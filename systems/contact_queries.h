// Contact queries: quantities the nested loops and the reports read off the contact state,
// fibre-fibre and fibre-tool elements alike. Pure functions over const stores, called directly
// by the driver (they change no store, so they are not task-graph stages).
//
// stepLimit           the largest step length a in (0, 1] along dq (all DOFs) such that no
//                     element closes deeper than allowed = stepPenetration p_max in one Newton
//                     step, and none already in contact closes by more than that:
//                     dg = N . (dx^I - dx^J), a = min over closing elements (dg < 0) of
//                     max(g + allowed, allowed) / -dg, g the gap at the last evaluation. (An
//                     absolute bound g + a dg >= -allowed froze Newton when the penalty was too
//                     soft for the load: the element sat at -allowed and every step had a = 0.)
// deepestDetected     the largest penetration of the elements at their detection (or last
//                     normal update), as a multiple of their zone's p_max.
// fillContactReport   counts (zones, elements, active, sliding) and the largest penetration.
// trueOverlap         over the elements of a detection from the state q (closest sections, the
//                     particles re-located on the deformed outlines): max of r_I + r_J - d, d =
//                     |x0I - x0J| the distance of the section centres, r = |x - x0| the deformed
//                     radius of each section towards the other (its particle's distance from its
//                     centre); on an end-face element (kEndFaceI/J) the face point's depth
//                     below the other fibre's surface, r - |P_t (x - x0)|; 0 when none
//                     overlaps; mm. Independent of the elements a state was solved with: it
//                     measures what they may under-report.
// compareContactSets  a detection from the accepted state (`fresh`) against the set the state
//                     was solved with (`used`): zones paired by id; zones without a partner or
//                     with another element count are counted; elements of paired zones paired
//                     by index, those closed in either set: the largest |g_fresh - g_used| /
//                     p_max and the largest particle
//                     shift sqrt(ds^2 + |dxi|^2) / R of either side (s arc length, xi section
//                     coordinates, R the side's radius).
#pragma once

#include "components/contact_params.h"
#include "components/contact_state.h"
#include "core/report.h"

#include <Eigen/Core>

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

// Fills zones, elements, toolElements, active, sliding, maxPenetration, maxPenetrationRatio.
void fillContactReport(const ContactParams& params, const ContactState& state, ContactReport& r);

double trueOverlap(const FibreStore& fibres, const Eigen::VectorXd& q,
                   const ContactElementStore& detected);

// Fills r.redetectZoneChanges, redetectGapChange, redetectParticleShift.
void compareContactSets(const FibreStore& fibres, const ContactState& used,
                        const ContactState& fresh, ContactReport& r);

}  // namespace fibra
