// Penalty adapter (eq. 13): after each loop A pass, the penalty of every zone is scaled so that
// its deepest penetration tends to p_max; the same adapter serves fibre-fibre zones and the
// (tool, fibre) zones of the tools.
//
//   k_z <- k_z * clamp(g_z / (target p_max,z), 1 / beta, beta),   g_z = max over the zone's
//   elements of -g_N (only zones with a penetration, g_z > 0, change),
// target = ContactParams::penaltyTarget (0.9: aims a little inside p_max), beta =
// ContactParams::penaltyChange (bounds one update).
//
// adaptZonePenalties      reads ContactParams, ContactElementStore (zone), ContactForceStore
//                         (gap); writes ZoneStore::penalty, ContactLoopStats::penaltyChange.
// adaptToolZonePenalties  the same over ToolContactStore (zone) and ToolZoneStore.
// penaltyChange is the largest |factor - 1| of the update. Serial (a pass over the elements).
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

// The adapter itself: zone of each element, its gap (mm), p_max per zone (mm), penalties to
// update (N/mm). Returns the largest |factor - 1|.
double adaptPenalties(std::span<const Index> zoneOf, std::span<const double> gap,
                      std::span<const double> pMax, std::span<double> penalty, double target,
                      double beta);

}  // namespace fibra
