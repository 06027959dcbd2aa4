// Friction history (paper section 4.3.1): the reversible slips of the contact elements kept on
// the fibres' particles from one loop A pass to the next, for fibre-fibre and fibre-tool
// elements alike (one path; the transfer back is systems/friction_reference.h).
//
// recordFrictionHistory (the system) reads the contact elements of the pass that just converged
//         (ContactElementStore, ToolContactStore: particles; their ContactForceStores: R_N and
//         g_rev) and writes the FrictionHistoryStore: for an element carrying a normal force with
//         slip g, particle I stores +g against partner J and particle J stores -g against
//         partner I; a tool element's particle stores g against partner -1 - tool. Sorted by
//         (fibre, partner, s). Serial (a sort).
// lookup  the slip stored on `fibre` against `partner` at arc length s: linear interpolation
//         between the stored particles on either side of s, the nearer one alone when only one
//         lies within `reach` (mm), zero when none does.
// transfer for a new element, g = (h_I(s_I) - h_J(s_J)) / 2 re-projected onto the plane normal
//         to its normal N; for a tool element, g = h(s) re-projected.
// Histories are keyed by the partner, so a fibre touching two neighbours at the same s keeps two
// separate histories. Serial record (a sort), parallel-safe lookups (read-only).
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "components/friction_history.h"
#include "components/tools.h"

namespace fibra {

// One particle's entry before sorting.
struct HistoryEntry {
  Index fibre, partner;
  double s;
  Vec3 gRev;
};

void recordFrictionHistory(const FibreStore& fibres, const ContactElementStore& elements,
                           const ContactForceStore& forces, const ToolContactStore& toolElements,
                           const ContactForceStore& toolForces, FrictionHistoryStore& history);

// The history of these entries (sorted here).
void recordHistory(std::vector<HistoryEntry>& entries, FrictionHistoryStore& out);

Vec3 lookupHistory(const FrictionHistoryStore& h, Index fibre, Index partner, double s, double reach);

inline Vec3 projectOnPlane(const Vec3& g, const Vec3& normal) { return g - g.dot(normal) * normal; }

}  // namespace fibra
