// Penalty adaptation within bounds tied to the section stiffness (systems/penalty_adapter.h):
// eq. 13 alone divides the penalty of a nearly unloaded zone by beta at every pass; the floor
// k_lo E R stops it, the ceiling k_hi E R caps it and a zone held there deeper than p_max is
// counted; zones without penetration keep their penalty.
#include "systems/penalty_adapter.h"

#include <doctest/doctest.h>

#include <vector>

using namespace fibra;

TEST_CASE("the penalty adapter keeps every zone's penalty within its bounds") {
  ContactParams p;  // target 0.9, beta 10, bounds 1 ... 1e4 x E R
  const double ER = 400, pMax = 1e-3;
  // Zone 0: almost no load (1e-9 mm); zone 1: deep (1e3 p_max); zone 2: on target; zone 3: open.
  const std::vector<Index> zoneOf = {0, 1, 1, 2, 3};
  const std::vector<double> gap = {-1e-9, -1.0, -0.5, -0.9 * pMax, 1e-3};
  const std::vector<double> pMaxZ(4, pMax), stiffness(4, ER);
  std::vector<double> lo(4, p.penaltyMin), hi(4, p.penaltyMax);
  std::vector<double> k = {1000 * ER, 0.9e4 * ER, ER, ER};
  ContactLoopStats stats;
  for (int pass = 0; pass < 6; ++pass)
    adaptPenalties(zoneOf, gap, {pMaxZ, stiffness, lo, hi, k}, p, stats);
  CHECK(k[0] == doctest::Approx(ER));        // 1/10 per pass, stopped at the floor
  CHECK(k[1] == doctest::Approx(1e4 * ER));  // x10 per pass, stopped at the ceiling
  CHECK(stats.zonesAtCeiling == 1);          // and still 1000 p_max deep: counted
  CHECK(k[2] == doctest::Approx(ER));        // on target: unchanged
  CHECK(k[3] == ER);                         // no penetration: unchanged
  CHECK(stats.penaltyChange == 0);           // the last pass changed nothing
  // Without the floor, the unloaded zone's penalty falls by 10 per pass.
  lo.assign(4, 1e-12);
  std::vector<double> free = {ER, ER, ER, ER};
  adaptPenalties(zoneOf, gap, {pMaxZ, stiffness, lo, hi, free}, p, stats);
  adaptPenalties(zoneOf, gap, {pMaxZ, stiffness, lo, hi, free}, p, stats);
  CHECK(free[0] == doctest::Approx(ER / 100));
}
