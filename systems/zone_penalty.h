// Zone penalties carried by zone identity: every zone of a new detection gets the penalty k of
// the zone it comes from (eq. 13 adapts k from call to call, so a zone keeps what it learned).
//
// It carries the zone's Lobatto refinement the same way (`refined`, set by the acceptance of
// a contact set: engine/contact_loops.cpp), so a zone keeps the finer sampling it was given.
//
// Reads  FibreStore (radii, materials), MaterialStore (E), ContactParams (initial k, the pair
//        classes), the previous call's ZoneStore (penalty, refined), the new zones' `previous`.
// Writes the new ZoneStore's penalty, refined, pMax, friction, penalty bounds and
//        stiffness columns.
//   k_z = k_previous(z) when the zone matches a previous one (its own id continued, or a part
//         split off it: systems/zone_identity.h), else k0 = min(E_I R_I, E_J R_J) (or the
//         scene's initial penalty); refined_z = refined_previous(z), else 0; p_max,z, mu_z and the penalty bounds = those of the pair
//         class of (I, J) (looked
//         up once per zone: systems/contact_params.h); stiffness_z = min(E_I R_I, E_J R_J).
// Serial over zones (a copy per zone).
#pragma once

#include "components/contact.h"
#include "components/contact_params.h"

namespace fibra {

void carryZonePenalties(const FibreStore& fibres, const MaterialStore& materials,
                        const ContactParams& params, const ZoneStore& previous, ZoneStore& zones);

}  // namespace fibra
