// Penalty adapter (eq. 13): after each loop A pass, the penalty of every zone is scaled so that
// its deepest penetration tends to p_max, within bounds tied to the section stiffness; the same
// adapter serves fibre-fibre zones and the (tool, fibre) zones of the tools.
//
//   k_z <- clamp(k_z * clamp(g_z / (target p_max,z), 1 / beta, beta), k_lo s_z, k_hi s_z),
//   g_z = max over the zone's elements of -g_N (only zones with a penetration, g_z > 0, change),
// target = ContactParams::penaltyTarget (0.9: aims a little inside p_max), beta =
// ContactParams::penaltyChange (bounds one update), s_z = the zone's section stiffness
// min(E_I R_I, E_J R_J) (N/mm), k_lo, k_hi = the zone's penaltyMin, penaltyMax (its pair
// class's, docs/SCENE.md; a tool zone's: the contact section's).
// Why the bounds: eq. 13 alone divides the penalty of a zone with almost no load by beta at every
// pass (1000x per increment with 3 passes), so a zone that the next increment loads starts from a
// penalty that no longer bites (a frozen residual, overlaps of many p_max). The floor keeps
// k >= k_lo E R: a softer penalty buys nothing, since an unloaded zone's penetration is below
// p_max whatever k; the ceiling keeps the tangent's conditioning (k / E R <= k_hi). A zone held
// at the ceiling with its deepest penetration above p_max costs accuracy: it is counted.
//
// adaptZonePenalties      reads ContactParams, ContactElementStore (zone), ContactForceStore
//                         (gap), ZoneStore (pMax, stiffness, penaltyMin, penaltyMax); writes
//                         ZoneStore::penalty, ContactLoopStats (penaltyChange, zonesAtCeiling).
// adaptToolZonePenalties  the same over ToolContactStore (zone) and ToolZoneStore.
// penaltyChange is the largest |k_new / k_old - 1| of the update. Serial (a pass over elements).
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "components/contact_params.h"
#include "components/iteration.h"
#include "components/tools.h"

#include <span>

namespace fibra {

void adaptZonePenalties(const ContactParams& params, const ContactElementStore& elements,
                        const ContactForceStore& forces, ZoneStore& zones, ContactLoopStats& stats);

void adaptToolZonePenalties(const ContactParams& params, const ToolContactStore& elements,
                            const ContactForceStore& forces, ToolZoneStore& zones,
                            ContactLoopStats& stats);

// The zones' columns the adapter reads and writes: p_max (mm), section stiffness (N/mm), the
// bounds k_lo, k_hi (multiples of the stiffness), penalties to update (N/mm).
struct PenaltyZones {
  std::span<const double> pMax, stiffness, penaltyMin, penaltyMax;
  std::span<double> penalty;
};

// The adapter itself over the zone of each element and its gap (mm). Fills stats.penaltyChange
// (largest |k_new / k_old - 1|) and stats.zonesAtCeiling.
void adaptPenalties(std::span<const Index> zoneOf, std::span<const double> gap, PenaltyZones zones,
                    const ContactParams& params, ContactLoopStats& stats);

}  // namespace fibra
