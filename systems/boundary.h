// Boundary system: held DOFs, dead loads and reactions.
//
// applyConstraints  reads ConstraintStore, GroupStore, FibreStore::qRef; writes the held DOFs
//                   of q: x0 = c + R(t)(X0 - c) + d(t), g_a = R(t) G_a, R(t) the rotation by
//                   angle(t) about the BC's axis through c (default c = X0).
// assembleLoads     reads LoadStore, GroupStore, FibreStore (q), IterationInput (time,
//                   withTangent); writes LinearSystem fext, r (subtracts f_ext) and K (adds the
//                   moment loads' stiffness). Serial: loads are few.
//   Force F on a node:   Pi = -F . x0.
//   Line force w (N/mm) on an element: consistent nodal forces w (h/2) int N_a dz.
//   Moment M on a node:  Pi = -|M| phi, phi the rotation of the section about the fixed axis
//     e = M/|M|: phi = atan2(S, C), C = sum_a u_a . g_a, S = sum_a (e x u_a) . g_a with
//     u_a = G_a - (G_a . e) e the reference directors projected normal to e (the planar
//     rotation about e that best maps the reference projections onto the current ones). A
//     torque about a fixed axis: conservative, symmetric tangent, smooth even when a director
//     turns parallel to e.
// reaction          reads r on a BC's held DOFs: force sum r_x0; moment about p:
//                   sum (x0 - p) x r_x0 + g1 x r_g1 + g2 x r_g2 (the virtual work of a rigid
//                   rotation of the held sections).
#pragma once

#include "components/boundary.h"
#include "components/iteration.h"
#include "components/linear_system.h"
#include "core/report.h"

namespace fibra {

void applyConstraints(const FibreStore& fibres, const ConstraintStore& constraints,
                      const GroupStore& groups, double time, Eigen::VectorXd& q);

void assembleLoads(const FibreStore& fibres, const LoadStore& loads, const GroupStore& groups,
                   const IterationInput& input, LinearSystem& ls);

Reaction reactionOf(const ConstraintStore& constraints, const Eigen::VectorXd& q,
                    const Eigen::VectorXd& r, Index bc, const Vec3& point);

}  // namespace fibra
