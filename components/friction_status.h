// Stick/slip status of the contact elements within one Newton pass (docs/METHOD.md, "Stick and
// slip within a pass"). Written by the contact law systems at each assembly with the tangent;
// the contact loops open a pass (flip counts cleared) and settle the held statuses at its end
// (systems/friction_status.h). One store for the fibre-fibre elements and one for the tool
// elements (ContactState). No logic here.
#pragma once

#include "core/types.h"

#include <cstdint>
#include <vector>

namespace fibra {

enum FrictionStatus : std::uint8_t { kStatusStick = 0, kStatusSlip = 1, kStatusNone = 2 };

struct FrictionStatusStore {
  // --- per contact element (same index as its ContactElementStore / ToolContactStore) ---
  std::vector<std::uint8_t> last;   // status at the pass's last assembly with the tangent
                                    // (kStatusNone before the first, or without normal force)
  std::vector<std::uint8_t> flips;  // stick <-> slip changes between those assemblies, this pass
  std::vector<std::uint8_t> held;   // kStatusNone: the return mapping decides (eqs. 15-16);
                                    // kStatusStick / kStatusSlip: that branch, for the pass
  std::vector<double> trialRatio;   // |t| / g_T,max of the trial slip at the last evaluation
                                    // (0 without normal force or friction), dimensionless

  Index size() const { return Index(held.size()); }
};

}  // namespace fibra
