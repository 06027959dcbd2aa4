#include "systems/zone_penalty.h"

#include "systems/contact_params.h"

#include <algorithm>
#include <cmath>

namespace fibra {

void carryZonePenalties(const FibreStore& fs, const MaterialStore& materials,
                        const ContactParams& p, const ZoneStore& previous, ZoneStore& z) {
  const auto ER = [&](Index f) { return materials.youngModulus[fs.material[f]] * fs.radius[f]; };
  for (Index i = 0; i < z.size(); ++i) {
    const Index o = z.previous[i];
    z.stiffness[i] = std::min(ER(z.fibreI[i]), ER(z.fibreJ[i]));
    const double k0 = std::isfinite(p.initialPenalty) ? p.initialPenalty : z.stiffness[i];
    z.penalty[i] = o >= 0 ? previous.penalty[o] : k0;
    z.refined[i] = o >= 0 ? previous.refined[o] : 0;
    const int c = pairClass(p, z.fibreI[i], z.fibreJ[i]);
    z.pMax[i] = p.pairs.pMax[c];
    z.friction[i] = p.pairs.mu[c];
    z.penaltyMin[i] = p.pairs.penaltyMin[c];
    z.penaltyMax[i] = p.pairs.penaltyMax[c];
  }
}

}  // namespace fibra
