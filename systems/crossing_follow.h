// Crossing follow: the sections of a frictionless crossing's point element moved to the closest
// points of the two centrelines at every normal update of loop B, instead of staying at the
// material points the last detection chose.
//
// Reads  FibreStore (layout, radii), q, ContactParams (theta_parallel, friction factor),
//        ZoneStore (friction per zone), ContactElementStore (crossing, fibreI/J, sI/J).
// Writes ContactElementStore::sI, sJ, xiI*, xiJ*, sideI, sideJ of the elements it moves, and
//        ContactLoopStats::crossingShift, the largest |s_new - s_old| over them (mm).
// Runs with loop B's normal update (between Newton passes, the sections fixed within a pass so
// that the tangent stays consistent: moved at every Newton evaluation, the omitted variation of
// the sections cost the woven fabrics their convergence); loop B goes on while a section moves
// more than particle_tolerance x R_min.
// Computes, for each element flagged `crossing` (detection placed it at the closest points of
// two crossing centrelines, systems/contact_elements.h) whose zone is frictionless (mu x the
// step's friction factor = 0), the local minimum of |x0I(sI) - x0J(sJ)| by Gauss-Newton on
//   F = [d . tI, -d . tJ] = 0,  d = x0I - x0J,  t = dx0/dz,
//   A = [[tI . tI, -tI . tJ], [-tI . tJ, tJ . tJ]]  (the curvature terms d . x'' dropped: |d|,
// about R_I + R_J, is far smaller than the centrelines' radii of curvature, so the iteration
// converges linearly at a rate of about |d| / rho), and the particles of eq. 9 (towards the
// other section's centre) there. Only within the elements the sections were detected in (their
// particle weights and the linear system's pattern stay): closest points that leave them, or no
// convergence in 20 steps, leave the element as it is for the next detection. Fibres within
// theta_parallel of each other have no well-posed closest pair: their elements stay.
// Off unless the scene asks (contact.follow_crossings; docs/CONTACT.md "Crossings that follow":
// the frictionless plain biaxial tension fails with it).
// Why: a frictionless crossing slides while Newton solves; the detected material points then
// drift from the closest points, and the force acts where the fibres no longer are closest (a
// woven twill's settle kept overlaps of 1.16 p_max where its elements reported 0.86;
// docs/CONTACT.md "Crossings that follow"). With friction the particles are material points
// (the slip is measured between them), so frictional crossings are left alone.
// Parallel over elements, each writing its own entries; the shift by a max-reduction.
#pragma once

#include "components/contact.h"
#include "components/contact_params.h"
#include "components/iteration.h"

namespace fibra {

// q: the state [x0 g1 g2] per node (fibres' layout).
void followCrossings(const FibreStore& fibres, const Eigen::VectorXd& q, const ContactParams& params,
                     const ZoneStore& zones, ContactElementStore& elements, ContactLoopStats& stats);

}  // namespace fibra
