// Contact detection parameters derived per fibre pair (docs/CONTACT.md): the proximity distance
// Delta_prox(I, J) and the test-point spacing l_zp(I, J). Header-only.
#pragma once

#include "components/contact_params.h"
#include "components/fibres.h"

#include <algorithm>
#include <cmath>

namespace fibra {

// Delta_prox of the pair (I, J), mm.
inline double proximityDistance(const ContactParams& p, Index I, Index J) {
  return p.reach[I] + p.reach[J];
}

// Test-point intervals per element of I for the pair (I, J): l_zp = h_I / m.
inline int testIntervalsPerElement(const FibreStore& fs, const ContactParams& p, Index I,
                                   Index J) {
  const double h = fs.length[I] / fs.elementCount[I];
  const double l = std::isnan(p.testPointSpacing) ? std::min(h / 2, fs.radius[I] + fs.radius[J])
                                                  : p.testPointSpacing;
  return std::max(1, int(std::ceil(h / l * (1 - 1e-12))));
}

}  // namespace fibra
