// Fibre-fibre contact law system: the force and stiffness of every fibre-fibre contact element at
// the current state, for fixed particles and normals (paper section 4).
//
// Reads  FibreStore (q), ContactParams (p_reg / p_max, g_T,max, symmetrised; the forced
//        normals' direction and allowance: a forced element's d is shifted by a N), ZoneStore
//        (penalty, p_max and mu per zone: its pair class's), ContactElementStore (particle
//        weights, element weight w_e, normal, friction reference, forced sign).
//        IterationInput (with or without the tangent).
// Writes ContactForceStore (gap, R_N, force, stiffness, g_rev, slip per element; facing
//        particles, rolling weights and friction blocks of elements on facing particles),
//        FrictionStatusStore (the branch each element took; held statuses are read:
//        systems/friction_status.h).
// Per element: d = x^I - x^J from the particle weights, the law of systems/contact_law.h with the
// penalty k_zone w_e (w_e: the element's share of the line, mean 1 over the zone,
// systems/contact_elements.h), p_reg = (p_reg / p_max) p_max,zone and mu = mu_zone. With
// ContactParams::facingParticles (contact `facing_particles`) an element with a fixed normal and
// no end face measures its gap on its facing particles and its normal force acts there
// (systems/facing_particles.h: the outlines' points extremal along N, taken anew each time);
// its slip and friction force stay on d (contact_law.h contactLawSplit).
// With ContactParams::newtonNormals (contact `normal_update` "newton"), every element whose
// normal is neither forced nor an end face's (with "newton_frictionless": every frictionless
// parallel element, once loop B diverged) recomputes N from the state and is linearised in it
// (systems/normal_linearisation.h: ContactForceStore::normalJacobian); the others keep the
// fixed-normal law (their NormalJacobian has I.count == 0).
// Threading: parallel over elements, each writing its own entries. Runs beside the beam
// evaluation and the tool contact law: it writes nothing they read.
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "components/contact_params.h"
#include "components/friction_status.h"
#include "components/iteration.h"

namespace fibra {

void evaluateFibreContacts(const FibreStore& fibres, const ContactParams& params,
                           const ZoneStore& zones, const ContactElementStore& elements,
                           const IterationInput& input, FrictionStatusStore& status,
                           ContactForceStore& forces);

}  // namespace fibra
