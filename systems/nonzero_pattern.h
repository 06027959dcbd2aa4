// Non-zero pattern system: the tangent as the factorisations see it, without most of the
// entries that K's stored pattern holds as exact zeros.
//
// Reads  LinearSystem: K on its stored pattern (fixed between contact detections: it holds
//        every candidate contact element of the proximity zones, and a candidate that does not
//        touch carries no stiffness, so most of its entries are exact zeros: 77% on the
//        250-fibre yarn, docs/RESULTS.md "Explicit zeros"), freeCount, symmetric, revision,
//        diagonal.
// Writes NonzeroPattern (its own state): the pattern P it analyses, as a mask over K's stored
//        entries; `compact`, a LinearSystem holding K's values on P (CSC, same storage as K:
//        upper triangle when symmetric) with P's own revision (freeCount, symmetric; the
//        scatter maps are left empty).
// Computes, in one pass over K per call (nz(K): the stored entries that are not exactly 0;
// diag: the diagonal entries, always kept so that every factorisation sees the diagonal):
//   with slack s >= 1, P is kept while nz(K) ⊆ P and |P| <= s |nz(K) ∪ diag|;
//   otherwise P := P ∪ nz(K) ∪ diag when that is within s |nz(K) ∪ diag|, else nz(K) ∪ diag,
//   and P's revision is bumped (the factorisations then analyse it again). A new revision of
//   K's stored pattern (a contact pass's detection) carries P over by coordinates (the entries
//   of P that the new stored pattern still holds) before the rule; P's revision stays when P
//   keeps all its entries in the same order (the arrays a factorisation's analysis refers to). P starts from nz(K) ∪ diag at the first call, when K's size changes
//   and after a restart (storedRevision = -1: LinearSolver::forgetPattern, each increment). The
//   union and the carry let contacts that come and go within an increment keep their entries,
//   so that P is analysed again only when new contact coupling appears or P has emptied. s = 0
//   turns it off: P is K's stored pattern.
// Determinism: P follows the values alone; the same sequence of K gives the same P.
#pragma once

#include "components/linear_system.h"

#include <cstdint>
#include <vector>

namespace fibra {

struct NonzeroPattern {
  double slack = 0;                 // s (dimensionless); 0: K's stored pattern
  std::vector<std::uint8_t> in;     // per stored entry of K: 1 when in P
  Index storedRevision = -1;        // the K pattern revision `in` refers to (-1: start afresh)
  Index entries = 0;                // |P|
  std::vector<Index> mark;          // scratch, per row of K
  LinearSystem compact;             // K's values on P; compact.revision is P's revision
  // counters (since construction): passes, and how many of them built a new P
  int passes = 0, patterns = 0;
};

// Updates p from ls (the rule above) and returns the system to factorise: p.compact, or ls
// itself when p.slack is 0. The returned reference stays valid until the next call.
const LinearSystem& updateNonzeroPattern(const LinearSystem& ls, NonzeroPattern& p);

}  // namespace fibra
