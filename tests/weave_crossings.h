// The crossings of a reduced woven sample (scripts/fabric_loadings.py: n x n yarns of 3 fibres,
// or `fibres`; yarn axes `spacing` apart, fibres (n + 1) x spacing long, centred on the origin;
// a crimped fibre's arc length at a crossing taken as its straight one), measured from
// the nodes alone (tests/centreline_measure.h), not from the contact elements: the largest
// overlap between fibres of crossing yarns and whether the pattern's over yarn lies above.
#pragma once

#include "centreline_measure.h"
#include "engine/world.h"
#include "io/fabric_generator.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>

namespace fibra::test {

struct WeaveLayout {
  int yarns = 3;         // in each direction
  double spacing = 1.5;  // between yarn axes, mm
  int fibres = 3;        // per yarn
};

struct Crossings {
  double worstOverlap = -1e300;  // largest w_I + w_J - d over the fibre pairs of the crossings
                                 // (overlapAt), mm
  int inOrder = 0, total = 0;    // crossings whose over yarn lies above the other
};

// Fibre k of warp (or weft) yarn y of the generator named "fab".
inline Index weaveFibre(const World& w, const char* dir, int y, int k) {
  const std::string name = std::string("fab.") + dir + std::to_string(y) + ".f" + std::to_string(k);
  const std::vector<std::string>& names = w.fibres().name;
  const auto it = std::find(names.begin(), names.end(), name);
  REQUIRE_MESSAGE(it != names.end(), "no fibre " << name);
  return Index(it - names.begin());
}

// Warp yarn c crosses weft yarn r at (x_r, y_c): over each pair of their fibres, the closest
// approach of the centrelines near there; the yarns' mean heights z at the crossing.
inline Crossings measureCrossings(const World& w, const WeavePattern& pattern, WeaveLayout l) {
  const FibreStore& fs = w.fibres();
  const auto axis = [&](int y) { return (y - (l.yarns - 1) / 2.0) * l.spacing; };
  const auto arc = [&](double coordinate) { return coordinate + (l.yarns + 1) * l.spacing / 2; };
  Crossings m;
  for (int c = 0; c < l.yarns; ++c)
    for (int r = 0; r < l.yarns; ++r) {
      const double sWarp = arc(axis(r)), sWeft = arc(axis(c));
      double zWarp = 0, zWeft = 0;
      for (int k = 0; k < l.fibres; ++k) {
        const Index I = weaveFibre(w, "warp", c, k), J = weaveFibre(w, "weft", r, k);
        zWarp += centreline(fs, fs.q, I, sWarp).z() / l.fibres;
        zWeft += centreline(fs, fs.q, J, sWeft).z() / l.fibres;
        for (int l2 = 0; l2 < l.fibres; ++l2) {
          const Index L = weaveFibre(w, "weft", r, l2);
          const Closest d = closestApproach(fs, fs.q, I, L, sWarp, sWeft);
          m.worstOverlap = std::max(m.worstOverlap, overlapAt(fs, fs.q, I, L, d));
        }
      }
      const bool warpOver = pattern[r % pattern.size()][c % pattern[0].size()] == 1;
      m.inOrder += warpOver ? zWarp > zWeft : zWeft > zWarp;
      ++m.total;
    }
  return m;
}

}  // namespace fibra::test
