// Energy balance (docs/METHOD.md "Energy balance"): the work of every force on the fibres,
// accumulated over the converged increments.
//
// energyForces   reads FibreStore (layout), ConstraintStore (held DOFs), LinearSystem (r, fext),
//                the contact state (elements with their particle weights, forces; may be null);
//                writes EnergyForces: generalised forces per DOF (a particle force F on
//                x = sum_a c_a0 x0_a + c_a1 g1_a + c_a2 g2_a gives c_af F on node a's field f);
//                an element's normal part is R_N N with the N its force was computed with
//                (ContactForceStore::normal), on the particles it acted on (facing ones where
//                it had them); the rest of f is friction's, on the material particles.
// accumulateEnergy reads the forces of the last and the new converged state, their states q and
//                the stabilisation (spring and viscous forces of the new state, anchored at the
//                increment's start); writes EnergyBalance:
//   W_x += 1/2 (f_x,last + f_x,new) . (q_new - q_last)   (trapezoid; x = dead loads, supports,
//          normal contact, friction, tools), the supports' forces being r on the held DOFs
//          (r = f_int - f_ext - f_contact, so a support balances it);
//   W_stab -= 1/2 (f_spring + f_viscous) . (q_new - q_last)   (exact: linear springs from 0);
//   strain = U(q_new) - U(q at t = 0).
// Serial passes over DOFs and contact elements.
#pragma once

#include "components/boundary.h"
#include "components/contact_state.h"
#include "components/energy.h"
#include "components/linear_system.h"

namespace fibra {

void energyForces(const FibreStore& fibres, const ConstraintStore& constraints,
                  const LinearSystem& system, const ContactState* contact, EnergyForces& out);

void accumulateEnergy(const EnergyForces& last, const EnergyForces& now,
                      const Eigen::VectorXd& qLast, const Eigen::VectorXd& qNow,
                      const Eigen::VectorXd& stabilisationForce, double strain,
                      EnergyBalance& balance);

}  // namespace fibra
