#include "systems/zone_identity.h"

#include "systems/interpolation.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace fibra {
namespace {

// Overlap length of [a1, a2] and [b1, b2] (negative: the gap between them), mm.
double overlap(double a1, double a2, double b1, double b2) {
  return std::min(a2, b2) - std::max(a1, b1);
}

// The old zones of the fibre pair (I, J): a range of the sorted previous store.
std::pair<Index, Index> pairRange(const ZoneStore& old, Index I, Index J) {
  auto key = [&](Index k) { return std::pair{old.fibreI[k], old.fibreJ[k]}; };
  Index lo = 0, hi = old.size();
  while (lo < hi) {
    const Index mid = (lo + hi) / 2;
    if (key(mid) < std::pair{I, J}) lo = mid + 1; else hi = mid;
  }
  Index end = lo;
  while (end < old.size() && key(end) == std::pair{I, J}) ++end;
  return {lo, end};
}

void findMatch(const FibreStore& fs, const ContactParams& p, const ZoneStore& old,
               ZoneStore& zones, std::vector<double>& score, Index z) {
  const Index I = zones.fibreI[z], J = zones.fibreJ[z];
  const double tol = elementLength(fs, I) / testIntervalsPerElement(fs, p, I, J);
  const double j1 = std::min(zones.sJ1[z], zones.sJ2[z]), j2 = std::max(zones.sJ1[z], zones.sJ2[z]);
  const auto [first, last] = pairRange(old, I, J);
  zones.previous[z] = -1;
  for (Index o = first; o < last; ++o) {
    const double ovI = overlap(zones.sI1[z], zones.sI2[z], old.sI1[o], old.sI2[o]);
    const double ovJ = overlap(j1, j2, std::min(old.sJ1[o], old.sJ2[o]), std::max(old.sJ1[o], old.sJ2[o]));
    if (ovI < -tol || ovJ < -tol) continue;
    if (zones.previous[z] < 0 || ovI + ovJ > score[z]) {
      zones.previous[z] = o;
      score[z] = ovI + ovJ;
    }
  }
}

}  // namespace

void matchZones(const FibreStore& fs, const ContactParams& params, const ZoneStore& old,
                ZoneCache& cache, ZoneStore& zones, Trace* trace) {
  Span span(trace, "contact-zone-identity");
  const Index n = zones.size();
  cache.matchScore.resize(n);
  tbb::parallel_for(Index(0), n, [&](Index z) { findMatch(fs, params, old, zones, cache.matchScore, z); });
  cache.bestNew.assign(old.size(), -1);
  for (Index z = 0; z < n; ++z) {
    const Index o = zones.previous[z];
    if (o >= 0 && (cache.bestNew[o] < 0 || cache.matchScore[z] > cache.matchScore[cache.bestNew[o]]))
      cache.bestNew[o] = z;
  }
  zones.nextId = old.nextId;
  for (Index z = 0; z < n; ++z) {
    const Index o = zones.previous[z];
    zones.id[z] = o >= 0 && cache.bestNew[o] == z ? old.id[o] : zones.nextId++;
  }
  span.items(n);
}

}  // namespace fibra
