// Boundary system: held DOFs, dead loads and reactions.
//
// applyConstraints  reads ConstraintStore, GroupStore, FibreStore::qRef; writes the held DOFs
//                   of q: x0 = c + R(t)(X0 - c) + d(t), g_a = R(t) G_a, R(t) the rotation by
//                   angle(t) about the BC's axis through c (default c = X0).
// assembleLoads     reads LoadStore, GroupStore, q; writes LinearSystem fext, r (subtracts
//                   f_ext) and K (adds the moment loads' stiffness). Serial: loads are few.
//   Force F on a node:   Pi = -F . x0.
//   Moment M on a node:  Pi = -|M| sum_a w_a phi_a, phi_a = atan2(b2 . g_a, b1 . g_a) the angle
//     of director a in the plane normal to e = M/|M| (b1, b2 = e x b1 a basis of that plane),
//     w_a = |P G_a|^2 / sum_b |P G_b|^2 from the reference directors. A torque about a fixed
//     axis, conservative: dphi/dg = (-y b1 + x b2)/rho^2, d2phi/d(x,y)^2 =
//     [[2xy, y^2-x^2], [y^2-x^2, -2xy]]/rho^4 with x = b1.g, y = b2.g, rho^2 = x^2 + y^2.
// reaction          reads r on a BC's held DOFs: force sum r_x0; moment about p:
//                   sum (x0 - p) x r_x0 + g1 x r_g1 + g2 x r_g2 (the virtual work of a rigid
//                   rotation of the held sections).
#pragma once

#include "components/boundary.h"
#include "components/linear_system.h"
#include "engine/world.h"

namespace fibra {

void applyConstraints(const FibreStore& fibres, const ConstraintStore& constraints,
                      const GroupStore& groups, double time, Eigen::VectorXd& q);

void assembleLoads(const FibreStore& fibres, const LoadStore& loads, const GroupStore& groups,
                   const Eigen::VectorXd& q, double time, bool withTangent, LinearSystem& ls);

Reaction reactionOf(const ConstraintStore& constraints, const Eigen::VectorXd& q,
                    const Eigen::VectorXd& r, Index bc, const Vec3& point);

}  // namespace fibra
