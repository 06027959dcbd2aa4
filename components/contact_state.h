// The contact state of one increment: everything contact carries from a converged state to the
// next, and what the world shows of it. One flat struct with two instances in the world
// (engine/world_state.h): `committed`, the last converged state, and `trial`, the attempt in
// progress. An attempt starts with trial = committed; accepting it swaps them; a failed or
// cancelled attempt is discarded, so committed is never touched by an attempt. No logic here.
#pragma once

#include "components/contact.h"
#include "components/contact_forces.h"
#include "components/friction_history.h"
#include "components/friction_status.h"
#include "components/tools.h"

namespace fibra {

struct ContactState {
  // fibre-fibre
  ZoneStore zones;               // proximity zones, their identities and penalties
  ContactElementStore elements;  // contact elements: particles, normals, friction reference
  ContactForceStore forces;      // their forces at the last evaluation
  FrictionStatusStore frictionStatus;  // their stick/slip status within the Newton pass
  // fibre-tool
  ToolZoneStore toolZones;       // per (tool, fibre): penalty
  ToolContactStore toolElements; // contact elements with the tools
  ContactForceStore toolForces;  // their forces at the last evaluation
  FrictionStatusStore toolFrictionStatus;  // their stick/slip status within the Newton pass
  // both
  FrictionHistoryStore history;  // reversible slips on the fibres, at the last loop A pass
};

}  // namespace fibra
