// Tool contact in the world: the stages the contact loops call for the fibre-tool contact
// elements (systems/tool_contact.h), mirroring engine/fibre_contact.h.
//   detect   elements at the current state (time t); rebase: friction reference (d_0 at the
//            current state and time, slip from the history against the tool);
//   normals  surface normals at the particles' current positions, slips re-projected;
//   adapt    eq. 13 per (tool, fibre) zone.
#pragma once

#include "systems/friction_history.h"
#include "engine/world_state.h"

#include <vector>

namespace fibra {

void detectToolStage(WorldState& w, double t);
void rebaseToolContacts(WorldState& w, double t);
double updateToolStageNormals(WorldState& w, double t);  // largest turn of a normal, rad
double adaptToolPenalties(WorldState& w);                // largest relative change of a penalty
void toolHistoryEntries(const WorldState& w, std::vector<HistoryEntry>& out);
double toolStepLimit(const WorldState& w, const Eigen::VectorXd& dq);
double deepestToolContact(const WorldState& w);          // largest penetration / p_max
void toolContactReport(const WorldState& w, ContactReport& r);

}  // namespace fibra
