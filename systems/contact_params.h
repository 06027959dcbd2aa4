// Contact parameters derived per fibre pair (docs/CONTACT.md): the proximity distance
// Delta_prox(I, J), the test-point spacing l_zp(I, J), the pair class of (I, J) and, under
// forced normals, the orientation of the forced normal. Header-only.
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

// Whether fibre-fibre normals may be linearised in Newton now: contact normal_update "newton",
// or "newton_frictionless" ("auto") once loop B diverged in this attempt, or "auto" in an attempt
// with every normal linearised (allNormals) (systems/normal_linearisation.h
// says which elements).
inline bool normalsInNewton(const ContactParams& p) {
  return p.newtonNormals && (!p.newtonFrictionlessOnly || p.unstableNormals || p.allNormals);
}

// Pair-class index of fibres I and J (ContactClasses::mu, pMax).
inline int pairClass(const ContactParams& p, Index I, Index J) {
  const ContactClasses& c = p.pairs;
  return c.pairOf[c.classOf[I] * c.classes + c.classOf[J]];
}

// p_max of the pair class of fibres I and J (mm); the scene-wide p_max without classes.
inline double pairPMax(const ContactParams& p, Index I, Index J) {
  return p.pairs.pMax.empty() ? p.pMax : p.pairs.pMax[pairClass(p, I, J)];
}

// Level of fibre f at reference arc length s (mm): the last piece starting at or before s
// (0 for a fibre without a level table).
inline double levelAt(const ContactParams& p, Index f, double s) {
  const ContactClasses& c = p.pairs;
  double level = 0;
  for (Index i = c.firstLevel[f]; i < c.firstLevel[f + 1] && c.levelFrom[i] <= s; ++i)
    level = c.level[i];
  return level;
}

// Orientation the forced normal of an element between (I, sI) and (J, sJ) would have: +1 (N =
// +D, I over J) when I's level there is the higher, -1 when J's is, 0 when the normal is not
// forced (no forced direction in this step, fibres of one class, or equal levels). Decided once,
// at the element's generation (ContactElementStore::forced).
inline int forcedSign(const ContactParams& p, Index I, double sI, Index J, double sJ) {
  if (p.forcedNormal.squaredNorm() == 0 || p.pairs.classOf[I] == p.pairs.classOf[J]) return 0;
  const double lI = levelAt(p, I, sI), lJ = levelAt(p, J, sJ);
  return lI > lJ ? 1 : lI < lJ ? -1 : 0;
}

// The overlap a forced element's gap allows in the current attempt (ContactParams::
// forcedAllowance, mm; 0 for an element whose normal is not forced, `forced` its
// ContactElementStore::forced): its gap is D.(x_over - x_under) - (R_over + R_under) + allowance.
inline double forcedAllowance(const ContactParams& p, int forced) {
  return forced ? p.forcedAllowance : 0.0;
}

}  // namespace fibra
