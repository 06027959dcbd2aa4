// The contact law of a fibre-fibre element with its normal following the state (contact
// `normal_update` "newton"): the normal N is recomputed from the current state at every assembly
// by eqs. 10-11 (normalOfSections, systems/contact_normals.h) and its derivative enters the
// tangent, so that Newton converges to an equilibrium whatever its stability (loop B, the fixed
// point on N, amplifies a lateral perturbation of a cylinder lying on a cylinder: docs/CONTACT.md).
//
// Reads  the state q (FibreStore), the element's particles (weights) and sections (fibre, s),
//        its law parameters, friction reference (d0, g_rev,0) and forced sign (a forced normal
//        is fixed, not linearised).
// Writes one element's ContactLawResult (gap, R_N, f = f_N + f_T, g_rev, slip; stiffness =
//        -df/dx^I at fixed N, for reports), its NormalJacobian (the forces' derivatives and the
//        sections' weights) and, with facing particles, the points the normal force acts on.
//
// The element's forces on I are functions of v = (x_N^I, x_N^J, x0I, x0J, a_I, a_J, x^I, x^J)
// (24 values: the points the normal force acts on, mm; the section centres, mm; a = dx0/ds,
// unit-free; the material particles, mm):
//   N = N(x0I, x0J, a_I, a_J, x^I, x^J)                  (eqs. 10-11; x^I, x^J on end faces and
//                                                          in the coincident-centres fallback)
//   g = (x_N^I - x_N^J) . N,  R_N = R_N(g)                (eqs. 11, 12)
//   trial t = P (g_rev,0 + d - d0), P = I - N N^T, d = x^I - x^J  (eq. 14; = g_rev,0 + P (d - d0)
//                                                          of the fixed-normal law when g_rev,0
//                                                          is normal to N, systems/contact_law.h)
//   g_rev = t, or g_max t / |t| when |t| > g_max           (eqs. 15, 16)
//   f_N = R_N N on x_N^I,  f_T = -(mu / g_max) R_N g_rev on x^I  (J gets -f_N, -f_T)
// With contact.facing_particles x_N are the points of the outlines extremal along N at this
// state, x0 + G xi, xi = R G^T o / |G^T o| (o = -N on I, +N on J; systems/facing_particles.h):
// the gap is the surfaces' whatever the sections' spin, and f_N passes the axis (with material
// particles a section spun within a pass carries f_N on a lever arm R sin(alpha), a torque that
// drives the spin further: in a twisted 91-fibre bundle whose contacts all slip, Newton circled
// on the outer fibres' director DOFs). Their weights are held for d/dv (the gap's variation with
// xi vanishes at the extremum), and the residual's variation with xi enters as the rolling
// stiffness through the directors at fixed N (systems/facing_particles.h) plus its part through
// N: d xi/dv = (R / |a|) v (G v)^T (+/- dN/dv), v normal to u = a / |a| in the section's plane.
// df_N/dv and df_T/dv by forward-mode differentiation (Eigen's AutoDiffScalar, 24 derivatives)
// of this very code: every branch (penalty branch, stick or slip, crossing weight clamped or not,
// fallbacks) is the one the values take, and within it the derivative is exact. v is linear in
// the DOFs q: x = sum c_a,f (x0, g1, g2)_a (the particle weights), x0I = sum N_a(z) x0_a, a_I =
// sum N_a'(z) dz/ds x0_a (the section weights; at an interior node the mean of two elements'
// derivatives, systems/contact_geometry.h's contactSection), so the element adds
// (systems/contact_scatter.h)
//   r -= D_N^T f_N + D^T f_T,  K += D_N^T (-df_N/dv) V + D^T (-df_T/dv) V + rolling,  V = dv/dq.
// A section at an interior node takes the mean of both elements' tangents: its clique is widened
// by the other element (systems/contact_cliques.h), so nothing is left out of K. Forced normals
// (constant) and end faces keep the fixed-normal law (linearisedNormal below).
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "systems/contact_law.h"
#include "systems/contact_params.h"
#include "systems/facing_particles.h"

namespace fibra {

// Element e is parallel (eq. 10 crossing weight 0: the normal follows the centres' offset) and
// frictionless (its pair class's mu x the step's friction factor is 0): a fibre lying on it is
// laterally unstable under load, and only friction or the normal's derivative holds it.
inline bool frictionlessParallel(const ContactParams& p, const ContactElementStore& el, Index e) {
  return !(el.crossWeight[e] > 0) &&
         !(p.pairs.mu[pairClass(p, el.fibreI[e], el.fibreJ[e])] * p.frictionFactor > 0);
}

// Whether element e's normal follows the state in Newton: contact `normal_update` "newton", a
// normal that is not forced (constant) and not an end face's (kEndFaceI/J: N through the face
// particle, kept fixed in a pass and updated by loop B as with "loop": linearised, the end of a
// cantilever sliding off a crossing fibre's flank diverges where the fixed point converges).
// With newtonFrictionlessOnly ("newton_frictionless") only frictionlessParallel elements, and
// only once loop B diverged (unstableNormals): linearisable says which they would be; every one
// in an attempt of "auto" with allNormals.
inline bool linearisableNormal(const ContactParams& p, const ContactElementStore& el, Index e) {
  return !(el.fallback[e] & (kEndFaceI | kEndFaceJ)) &&
         !el.forced[e] &&
         (!p.newtonFrictionlessOnly || p.allNormals || frictionlessParallel(p, el, e));
}
inline bool linearisedNormal(const ContactParams& p, const ContactElementStore& el, Index e) {
  return normalsInNewton(p) && linearisableNormal(p, el, e);
}

struct LinearisedContact {
  ContactLawResult law;
  NormalJacobian jacobian;
  Vec3 normal = Vec3::Zero();  // N at this state, unit, from J to I
  bool facing = false;         // the normal force acts on the facing points I, J below
  FacingSide I, J;
};

// The section of fibre f at reference arc length s (mm) as weights on nodal x0 (the rule of
// contactSection, systems/contact_geometry.h).
SectionWeights sectionWeights(const FibreStore& fs, Index f, double s);

// Element e at the state q: N by eqs. 10-11 with radii RI, RJ (mm) and the crossing angles (rad),
// the law of `p` with its friction reference, f and df/dv. `hold`: the element's stick/slip
// status held for the Newton pass (systems/friction_status.h; kStatusNone: the return mapping
// decides), as in contactLaw; law.trialRatio reports |trial| / g_max for the tracking.
// `facing`: the gap and the normal force on the outlines' points extremal along N
// (contact.facing_particles, systems/facing_particles.h), the slip and friction on the material
// particles; else both on the material particles (where a section is normal to N as well).
LinearisedContact linearisedContact(const FibreStore& fs, const Eigen::VectorXd& q,
                                    const ContactElementStore& el, Index e,
                                    const ContactLawParams& p, double thetaParallel,
                                    double thetaCross, std::uint8_t hold = kStatusNone,
                                    bool facing = false);

}  // namespace fibra
