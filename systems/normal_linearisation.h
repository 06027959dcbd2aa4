// The contact law of a fibre-fibre element with its normal following the state (contact
// `normal_update` "newton"): the normal N is recomputed from the current state at every assembly
// by eqs. 10-11 (normalOfSections, systems/contact_normals.h) and its derivative enters the
// tangent, so that Newton converges to an equilibrium whatever its stability (loop B, the fixed
// point on N, amplifies a lateral perturbation of a cylinder lying on a cylinder: docs/CONTACT.md).
//
// Reads  the state q (FibreStore), the element's particles (weights) and sections (fibre, s),
//        its law parameters, friction reference (d0, g_rev,0) and forced sign (a forced normal
//        is fixed, not linearised).
// Writes one element's ContactLawResult (gap, R_N, f, g_rev, slip; stiffness = -df/dx^I at
//        fixed N, for reports) and its NormalJacobian (df/dv and the sections' weights).
//
// The element's force on I is a function of v = (x^I, x^J, x0I, x0J, a_I, a_J) (18 values: the
// particles, mm; the section centres, mm; a = dx0/ds, unit-free):
//   N = N(x0I, x0J, a_I, a_J, x^I, x^J)                  (eqs. 10-11; x^I, x^J on end faces and
//                                                          in the coincident-centres fallback)
//   g = (x^I - x^J) . N,  R_N = R_N(g)                    (eqs. 11, 12)
//   trial t = P (g_rev,0 + d - d0), P = I - N N^T          (eq. 14; = g_rev,0 + P (d - d0) of the
//                                                          fixed-normal law when g_rev,0 is normal
//                                                          to N, systems/contact_law.h)
//   g_rev = t, or g_max t / |t| when |t| > g_max           (eqs. 15, 16)
//   f = R_N N - (mu / g_max) R_N g_rev                     (N on I; J gets -f)
// df/dv by forward-mode differentiation (Eigen's AutoDiffScalar, 18 derivatives) of this very
// code: every branch (penalty branch, stick or slip, crossing weight clamped or not, fallbacks)
// is the one the values take, and within it the derivative is exact. v is linear in the DOFs q:
// x^I = sum c_a,f (x0, g1, g2)_a (the particle weights), x0I = sum N_a(z) x0_a, a_I = sum N_a'(z)
// dz/ds x0_a (the section weights; at an interior node the mean of two elements' derivatives,
// systems/contact_geometry.h's contactSection), so the element adds (systems/contact_scatter.h)
//   r -= D^T f,  K += D^T (-df/dv) V,  D = dd/dq, V = dv/dq.
// A section at an interior node takes the mean of both elements' tangents: its clique is widened
// by the other element (systems/contact_cliques.h), so nothing is left out of K. Forced normals
// (constant) and end faces keep the fixed-normal law (linearisedNormal below).
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "systems/contact_law.h"
#include "systems/contact_params.h"

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
};

// The section of fibre f at reference arc length s (mm) as weights on nodal x0 (the rule of
// contactSection, systems/contact_geometry.h).
SectionWeights sectionWeights(const FibreStore& fs, Index f, double s);

// Element e at the state q: N by eqs. 10-11 with radii RI, RJ (mm) and the crossing angles (rad),
// the law of `p` with its friction reference, f and df/dv.
LinearisedContact linearisedContact(const FibreStore& fs, const Eigen::VectorXd& q,
                                    const ContactElementStore& el, Index e,
                                    const ContactLawParams& p, double thetaParallel,
                                    double thetaCross);

}  // namespace fibra
