// Face follow: the particles of a frictionless end-face element moved to the face's deepest
// point at every normal update of loop B, instead of staying where the last detection put them.
//
// Reads  FibreStore (layout, radii), q, ContactParams (friction factor), ZoneStore (friction and
//        p_max per zone), ContactElementStore (fallback's kEndFaceI/J, fibreI/J, sI/J, xi*, gap).
// Writes ContactElementStore::sI or sJ (the other fibre's section), xiI*, xiJ*, sideI, sideJ of
//        the elements it moves, and ContactLoopStats::faceShift, the largest move of a face
//        point or of the other section (mm).
// Runs with loop B's normal update, before the normals (between Newton passes: the particles are
// fixed within a pass, as crossing follow's sections, systems/crossing_follow.h); loop B goes on
// while a face point moves more than particle_tolerance x R_min.
// Computes, for each end-face element (systems/contact_elements.cpp: the face point deepest in
// the other fibre, that fibre's section at its closest centreline point) whose zone is
// frictionless and whose gap is below the zone's p_max (an open face is left to the next
// detection: moving it would only ask for loop B passes that change nothing), the same pair at the state q within the elements it was detected in: the disc
// point nearest the other section's tangent line (discPointNearestLine, ties towards the current
// point), then that section moved along its element to the point's closest centreline point
// (Newton on (x0(z) - x) . dx0/dz = 0), until neither moves (1e-12 R, 1e-12 in z) or 20 rounds;
// the other particle faces the face point. A closest point that leaves the element, or a face
// point within R_other / 2 of the other axis (kFaceClearance), leaves the element as it is for
// the next detection.
// Why: a face resting on a fibre's flank rolls while Newton solves (frictionless, nothing holds
// its rim point); its fixed particle then pushes where the face no longer is deepest, and the
// next detection finds the rim elsewhere, many p_max deep (a face tilted 20 degrees about the
// diagonal pushed onto a fibre failed as an inconsistent set, 15 p_max against 0.12 reported).
// With friction the particles are material points (the slip is measured between them): left.
// Parallel over elements, each writing its own entries; the shift by a max-reduction.
#pragma once

#include "components/contact.h"
#include "components/contact_params.h"
#include "components/iteration.h"

namespace fibra {

// q: the state [x0 g1 g2] per node (fibres' layout).
void followEndFaces(const FibreStore& fibres, const Eigen::VectorXd& q, const ContactParams& params,
                    const ZoneStore& zones, ContactElementStore& elements, ContactLoopStats& stats);

}  // namespace fibra
