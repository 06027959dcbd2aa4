#include "systems/friction_history.h"

#include "core/columns.h"
#include "systems/interpolation.h"

#include <algorithm>
#include <tuple>

namespace fibra {

void recordFrictionHistory(const FibreStore& fs, const ContactElementStore& el,
                           const ContactForceStore& f, const ToolContactStore& tel,
                           const ContactForceStore& tf, FrictionHistoryStore& history) {
  std::vector<HistoryEntry> entries;
  for (Index e = 0; e < el.size(); ++e) {
    if (f.normalForce[e] <= 0) continue;
    entries.push_back({el.fibreI[e], el.fibreJ[e], el.sI[e], f.gRev[e]});
    entries.push_back({el.fibreJ[e], el.fibreI[e], el.sJ[e], -f.gRev[e]});
  }
  for (Index i = 0; i < tel.size(); ++i)
    if (tf.normalForce[i] > 0)
      entries.push_back({fs.elementFibre[tel.element[i]], -1 - tel.tool[i],
                         arcLength(fs, tel.element[i], tel.z[i]), tf.gRev[i]});
  recordHistory(entries, history);
}

void recordHistory(std::vector<HistoryEntry>& entries, FrictionHistoryStore& out) {
  std::sort(entries.begin(), entries.end(), [](const HistoryEntry& a, const HistoryEntry& b) {
    return std::tie(a.fibre, a.partner, a.s) < std::tie(b.fibre, b.partner, b.s);
  });
  clearColumns(out);
  for (const HistoryEntry& e : entries) {
    out.fibre.push_back(e.fibre);
    out.partner.push_back(e.partner);
    out.s.push_back(e.s);
    out.gRev.push_back(e.gRev);
  }
}

Vec3 lookupHistory(const FrictionHistoryStore& h, Index fibre, Index partner, double s, double reach) {
  // First entry not before (fibre, partner, s).
  Index lo = 0, hi = h.size();
  while (lo < hi) {
    const Index mid = (lo + hi) / 2;
    if (std::tie(h.fibre[mid], h.partner[mid], h.s[mid]) < std::tie(fibre, partner, s)) lo = mid + 1;
    else hi = mid;
  }
  const bool hasAfter = lo < h.size() && h.fibre[lo] == fibre && h.partner[lo] == partner &&
                        h.s[lo] - s <= reach;
  const bool hasBefore = lo > 0 && h.fibre[lo - 1] == fibre && h.partner[lo - 1] == partner &&
                         s - h.s[lo - 1] <= reach;
  if (hasBefore && hasAfter) {
    const double span = h.s[lo] - h.s[lo - 1];
    const double u = span > 0 ? (s - h.s[lo - 1]) / span : 0.5;
    return (1 - u) * h.gRev[lo - 1] + u * h.gRev[lo];
  }
  if (hasAfter) return h.gRev[lo];
  if (hasBefore) return h.gRev[lo - 1];
  return Vec3::Zero();
}

}  // namespace fibra
