// Friction history store (paper section 4.3.1): contact elements do not persist from one contact
// loop to the next, so the reversible slip is kept on the particles of the beams instead. Each
// entry is one particle of one fibre in contact with one partner (another fibre or a tool),
// sorted by (fibre, partner, s) for lookups by interpolation along the fibre. No logic here; see
// systems/friction_history.h.
#pragma once

#include "components/fibres.h"

#include <vector>

namespace fibra {

struct FrictionHistoryStore {
  // --- per stored particle, sorted by (fibre, partner, s) ---
  std::vector<Index> fibre;    // fibre holding the particle
  std::vector<Index> partner;  // the other fibre, or -1 - tool
  std::vector<double> s;       // reference arc length of the particle, mm
  std::vector<Vec3> gRev;      // reversible slip of this particle relative to the partner, mm

  Index size() const { return Index(fibre.size()); }
};

}  // namespace fibra
