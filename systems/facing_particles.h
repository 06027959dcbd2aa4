// Facing particles of a contact element: the normal force acts where the two outlines are
// extremal along the normal, whatever the sections' spin; friction acts on the material particles,
// between which its slip is measured.
//
// The paper's particles (eq. 9) are material points of the outlines, fixed for a detection pass.
// When a section spins about its axis within the pass, its particle rolls off the line of
// centres: the gap measured between the rolled particles misses the overlap by R (1 - cos alpha)
// per side, and the force N R_N acting there has a lever arm R sin(alpha) about the axis. Where
// the contact is frictionless, nothing but torsion resists the spin and that torque drives it
// further (a frictionless plain weave with its crossings followed: 15 p_max of overlap where the
// element reported 0.84, its warp section spun 14 deg; docs/CONTACT.md "Facing particles"). With
// friction the spin is physical — a fibre rolled by its neighbours' friction, under a frictionless
// tool — and a pass can still roll a particle off: in the 250-fibre crush one fibre's sections
// spun 11 deg within an increment, an element reported 0.93 p_max where its sections overlapped
// by 3.2, and the next increments' sets (6-10 p_max of overlap) were refused (docs/CONTACT.md
// "Frictional elements on facing particles"). With N fixed (loop B), an element instead takes
// at every evaluation the points
// of the outlines x0 + G xi, |xi| = R, extremal along N:
//   xi_I = -R_I G_I^T N / |G_I^T N|,   xi_J = +R_J G_J^T N / |G_J^T N|,
//   g = (x0_I - x0_J) . N - R_I |G_I^T N| - R_J |G_J^T N|            (support functions)
// so the gap is the true surface gap along N (the half-widths of systems/contact_queries.h), and
// the normal force passes the axis: r x N . t = 0 for a circular section. As xi extremises the
// support function, dg/dq is the particle's weight vector at xi (no term from xi's own
// variation); the tangent adds the outlines' curvature, K += R_N (R / rho) w w^T per side, with
// rho = |G^T N|, u = G^T N / rho, v = (-u2, u1) and w = sum_a N_a (v1 N on g1_a, v2 N on g2_a).
// A frictional element's slip stays that of its material particles, d_T = x^I - x^J (eq. 14:
// the relative motion of material points, spin included), and its friction force acts on them;
// its tangent then has the blocks of systems/contact_law.h contactLawSplit.
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "components/particle_weights.h"
#include "core/types.h"

#include <Eigen/Core>

namespace fibra {

struct FacingSide {
  ParticleWeights particle;  // at the extremal point, weights on (x0, g1, g2) of the element
  ParticleWeights rolling;   // c[a][0] = 0, c[a][f] = sqrt(R / rho) N_a v_f: K += R_N (.) N N^T
  Vec3 position = Vec3::Zero();  // the particle's position, mm
};

// Side of an element whose material particle has the weights `material` (its element and
// shape functions), radius R (mm), outward direction `out` (-N for side I, +N for side J).
// q: the DOFs (mm, -). False when the section is normal to `out` (no extremal point).
bool facingSide(const Eigen::VectorXd& q, const ParticleWeights& material, double R,
                const Vec3& out, FacingSide& side);

// The particles element e's last normal force acted on: its facing particles when it had them,
// else its material particles (side 0: I, 1: J). Friction always acts on the material ones.
inline const ParticleWeights& forceParticle(const ContactElementStore& el,
                                            const ContactForceStore& f, Index e, int side) {
  if (e < Index(f.facing.size()) && f.facing[e]) return side == 0 ? f.facingI[e] : f.facingJ[e];
  return side == 0 ? el.sideI[e] : el.sideJ[e];
}

}  // namespace fibra
