#include "systems/penalty_adapter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibra {

void adaptPenalties(std::span<const Index> zoneOf, std::span<const double> gap, PenaltyZones z,
                    const ContactParams& p, ContactLoopStats& stats) {
  std::vector<double> deepest(z.penalty.size(), 0.0);
  for (size_t e = 0; e < zoneOf.size(); ++e)
    deepest[zoneOf[e]] = std::max(deepest[zoneOf[e]], -gap[e]);
  const double beta = p.penaltyChange;
  stats.penaltyChange = 0;
  stats.zonesAtCeiling = 0;
  for (size_t i = 0; i < z.penalty.size(); ++i) {
    if (deepest[i] <= 0) continue;
    const double factor = std::clamp(deepest[i] / (p.penaltyTarget * z.pMax[i]), 1 / beta, beta);
    const double lo = z.penaltyMin[i] * z.stiffness[i], hi = z.penaltyMax[i] * z.stiffness[i];
    const double k = std::clamp(z.penalty[i] * factor, lo, hi);
    stats.penaltyChange = std::max(stats.penaltyChange, std::abs(k / z.penalty[i] - 1));
    z.penalty[i] = k;
    if (k == hi && deepest[i] > z.pMax[i]) ++stats.zonesAtCeiling;
  }
}

void adaptZonePenalties(const ContactParams& p, const ContactElementStore& el,
                        const ContactForceStore& f, ZoneStore& zones, ContactLoopStats& stats) {
  adaptPenalties(el.zone, f.gap,
                 {zones.pMax, zones.stiffness, zones.penaltyMin, zones.penaltyMax, zones.penalty}, p,
                 stats);
}

void adaptToolZonePenalties(const ContactParams& p, const ToolContactStore& el,
                            const ContactForceStore& f, ToolZoneStore& zones,
                            ContactLoopStats& stats) {
  adaptPenalties(el.zone, f.gap,
                 {zones.pMax, zones.stiffness, zones.penaltyMin, zones.penaltyMax, zones.penalty}, p,
                 stats);
}

}  // namespace fibra
