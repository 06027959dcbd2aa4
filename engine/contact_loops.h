// The nested solution loops of one increment with contact (paper section 4.4):
//
//   loop A (fixed point, <= n_A): detect proximity zones and contact elements at the reference
//          state, give them the friction history of their particles
//     loop B (fixed point, <= n_B): normals
//       Newton-Raphson: beam strains, contact and sliding status (elements and normals fixed)
//     adapt the penalty of every zone towards p_max (eq. 13), record the friction history
//
// Loop B stops early when no normal turned by more than 1e-3 rad; loop A when the fibres moved
// less than 1e-3 R since its elements were detected (a new detection would find the same set)
// and no penalty changed by more than 10%. The reference state of loop A's first pass is the last converged state; of
// the next passes, the state the previous pass converged to — unless that state penetrates the
// newly detected elements deeper than the Newton step limit allows (stepPenetration p_max),
// then the pass restarts from the increment's start with the new elements (reported).
// Newton's steps are limited so that no element closes deeper than stepPenetration p_max in one
// step: without it the first step of an increment that brings fibres into contact overshoots by
// millimetres and Newton then cycles between contact states.
#pragma once

#include "engine/world_state.h"
#include "systems/newton.h"

namespace fibra {

// Resolves ContactSettings and the tool and stabilisation stores from the scene.
void buildContact(WorldState& w);

// Solves the attempt at pseudo-time tTry from the converged state; fills `report`.
NewtonResult solveContactIncrement(WorldState& w, double tTry, const NewtonSettings& settings,
                                   const NewtonCallbacks& callbacks, StepTimings& timings,
                                   ContactReport& report);

// What an increment changes besides q: the whole contact state of a converged state (zones
// with their identities and penalties, fibre-fibre and fibre-tool contact elements with their
// friction references and last forces, the friction history, the tool penalties and
// reactions) and the residual assembled there. Saved at a converged state and restored, as it
// was, when an attempt fails or is cancelled, so that the world shows exactly that state.
struct ContactCheckpoint {
  FrictionHistoryStore history;
  std::vector<double> toolPenalty;
  std::vector<Vec3> toolReaction;
  std::map<std::uint64_t, double> zonePenalty;
  ZoneStore zones;
  ZoneStore previousZones;        // the zone identity's previous call
  std::uint64_t nextZoneId = 1;
  ContactElementStore elements;
  ContactMechanicsStore mechanics;
  ToolContactStore toolContacts;
  Eigen::VectorXd r, fext;
};
ContactCheckpoint contactCheckpoint(const WorldState& w);
void restoreContact(WorldState& w, const ContactCheckpoint& c);

}  // namespace fibra
