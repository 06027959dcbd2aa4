// Fibre-fibre contact in the world: the detection pipeline (systems/contact_detection.h) bound to
// the contact mechanics (systems/contact_assembler.h), as the stages the contact loops call.
//
//   detect    runs the detection at the current state; gives every zone its penalty (the same
//             zone id keeps its k; a zone split off another starts from its parent's; a new
//             one from k0 = E R); turns particles (fibre, s, xi) into weights on their element's
//             DOFs; registers the element pairs as cliques of the tangent's pattern, which only
//             grows (a pattern rebuild re-runs CHOLMOD's analysis) until more than half of its
//             contact cliques are unused; colours the cliques for the parallel scatter.
//   rebase    friction reference of the elements at the current state (d_0), reversible slip
//             from the history: (h_I(s_I) - h_J(s_J)) / 2 on the tangent plane.
//   normals   loop B: eqs. 10-11 again at the current state; slips re-projected.
//   adapt     eq. 13 per zone, bounded by the penalty-change factor.
#pragma once

#include "systems/friction_history.h"
#include "engine/world_state.h"

#include <vector>

namespace fibra {

void buildFibreContact(WorldState& w);
void detectFibreContacts(WorldState& w);
void rebaseFibreContacts(WorldState& w);
void registerFibreCliques(WorldState& w);  // binds the elements to the tangent's pattern
double updateFibreNormals(WorldState& w);         // largest turn of a normal, rad
double adaptZonePenalties(WorldState& w);         // largest relative change of a penalty
void fibreHistoryEntries(const WorldState& w, std::vector<HistoryEntry>& out);
double fibreStepLimit(const WorldState& w, const Eigen::VectorXd& dq);
double deepestFibreContact(const WorldState& w);  // largest penetration / p_max
void fibreContactReport(const WorldState& w, ContactReport& r);

}  // namespace fibra
