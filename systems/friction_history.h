// Friction-history transfer system (paper section 4.3.1).
//
// record  reads the contact elements of the loop that just converged (their particles and
//         reversible slips) and writes a FrictionHistoryStore: for an element with slip g,
//         particle I stores +g against partner J and particle J stores -g against partner I
//         (a tool side stores nothing). Sorted by (fibre, partner, s).
// lookup  the slip stored on `fibre` against `partner` at arc length s: linear interpolation
//         between the stored particles on either side of s, the nearer one alone when only one
//         lies within `reach` (mm), zero when none does.
// transfer for a new element, g = (h_I(s_I) - h_J(s_J)) / 2 re-projected onto the plane normal
//         to its normal N; for a tool element, g = h(s) re-projected.
// Histories are keyed by the partner, so a fibre touching two neighbours at the same s keeps two
// separate histories. Serial record (a sort), parallel-safe lookups (read-only).
#pragma once

#include "components/friction_history.h"

namespace fibra {

// One particle's entry before sorting.
struct HistoryEntry {
  Index fibre, partner;
  double s;
  Vec3 gRev;
};

void recordHistory(std::vector<HistoryEntry>& entries, FrictionHistoryStore& out);

Vec3 lookupHistory(const FrictionHistoryStore& h, Index fibre, Index partner, double s, double reach);

inline Vec3 projectOnPlane(const Vec3& g, const Vec3& normal) { return g - g.dot(normal) * normal; }

}  // namespace fibra
