// The nested solution loops of one increment with contact (paper section 4.4), as a list of
// stages (engine/pipeline.h) over the trial contact state:
//
//   loop A (fixed point, <= n_A): detect proximity zones and contact elements at the reference
//          state, give them the friction history of their particles          [stage detect]
//     loop B (fixed point, <= n_B):
//       Newton-Raphson: beam strains, contact and sliding status (elements
//       and normals fixed; an element whose stick/slip branch keeps changing
//       is held in it for the pass)                                           [stage assemble]
//       held branches checked against the slip circle (systems/friction_status.h)
//       normals at the new state                                             [stage normals]
//       once the updates show an unstable map, the Anderson-mixed normals instead
//       (contact normal_acceleration, systems/normal_acceleration.h)
//     adapt the penalty of every zone towards p_max (eq. 13), record the
//     friction history                                                        [stage adapt]
//
// Loop B stops early when no normal turned by more than 1e-3 rad and no held branch was found on
// the wrong side of the slip circle (beyond contact.friction_hold_tolerance); loop A when the fibres moved
// less than 1e-3 R since its elements were detected (a new detection would find the same set)
// and no penalty changed by more than 10%. The reference state of loop A's first pass is the last
// converged state; of the next passes, the state the previous pass converged to — unless that
// state penetrates the newly detected elements deeper than the Newton step limit allows
// (stepPenetration p_max), then the pass restarts from the increment's start with the new
// elements (reported)                                                         [stage reference].
// When loop A stops, the penalties go back to those its last pass was solved with: the accepted
// state is the equilibrium of its own elements and penalties, and the next increment starts
// from it. (Keeping the adapted penalties, as before, left the accepted states of the squeezed
// 7- and 19-fibre bundles out of equilibrium by 0.04-1.7 times the reference force; the next
// increment's Newton had to absorb that jump, and the 19-fibre bundle failed at t = 0.48.) The
// friction history recorded by the adapt stage is kept. The loop's normals are not rolled back:
// the last update's turn is below the tolerance, and it leaves 1e-5-3e-4 of the reference force.
// Acceptance (fibre-fibre contact): the set is compared with a detection from the converged
// state; when the fibres truly overlap (centrelines and radii, end faces against the other's
// surface) by more than 1.5 x the deepest penetration the elements report (and p_max), the state
// is solved again with the new detection's elements, at most twice, and the attempt fails (a
// cutback) if it still is; likewise where an element of the set pushes (R_N > 0), its fibres
// parallel there, while the fibres near it stand more than p_max apart (a normal that lags behind a slip: a false
// equilibrium, systems/contact_queries.h falseForce): an inconsistent set is never accepted
// (ContactReport::consistencyPasses counts the passes added). Under the default Gauss placement, the zones
// where the overlap was found take Lobatto elements from that new detection on
// (ZoneStore::refined, carried by zone identity; ContactReport::refinedZones): a set whose
// fibres overlap between its Gauss points, at a node, would otherwise be placed the same again.
// Newton's steps are limited so that no element closes deeper than stepPenetration p_max in one
// step (systems/contact_queries.h): without it the first step of an increment that brings fibres
// into contact overshoots by millimetres and Newton then cycles between contact states.
// Cancellation is checked after every detection (and inside it, per chunk of work) and by
// Newton between iterations.
#pragma once

#include "engine/world_state.h"
#include "systems/newton.h"

namespace fibra {

// Solves the attempt at pseudo-time tTry from the converged state into the trial contact state;
// fills `report`.
NewtonResult solveContactIncrement(WorldState& w, double tTry, const NewtonSettings& settings,
                                   const NewtonCallbacks& callbacks, StepTimings& timings,
                                   ContactReport& report);

}  // namespace fibra
