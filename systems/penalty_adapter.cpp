#include "systems/penalty_adapter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibra {

double adaptPenalties(std::span<const Index> zoneOf, std::span<const double> gap,
                      std::span<const double> pMax, std::span<double> penalty, double target,
                      double beta) {
  std::vector<double> deepest(penalty.size(), 0.0);
  for (size_t e = 0; e < zoneOf.size(); ++e)
    deepest[zoneOf[e]] = std::max(deepest[zoneOf[e]], -gap[e]);
  double change = 0;
  for (size_t z = 0; z < penalty.size(); ++z) {
    if (deepest[z] <= 0) continue;
    const double factor = std::clamp(deepest[z] / (target * pMax[z]), 1 / beta, beta);
    penalty[z] *= factor;
    change = std::max(change, std::abs(factor - 1));
  }
  return change;
}

void adaptZonePenalties(const ContactParams& p, const ContactElementStore& el,
                        const ContactForceStore& f, ZoneStore& zones, ContactLoopStats& stats) {
  stats.penaltyChange =
      adaptPenalties(el.zone, f.gap, zones.pMax, zones.penalty, p.penaltyTarget, p.penaltyChange);
}

void adaptToolZonePenalties(const ContactParams& p, const ToolContactStore& el,
                            const ContactForceStore& f, ToolZoneStore& zones,
                            ContactLoopStats& stats) {
  stats.penaltyChange =
      adaptPenalties(el.zone, f.gap, zones.pMax, zones.penalty, p.penaltyTarget, p.penaltyChange);
}

}  // namespace fibra
