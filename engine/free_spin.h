// Fibres whose spin about their axis only contact friction holds (docs/METHOD.md "Free spin").
//
// A straight fibre held at positions only (any number of nodes, all on its axis) can spin by phi
// about its unit axis t without moving a held DOF: the spin turns each director g by phi t x g
// and moves no centreline point. Friction resists it while one of the fibre's contacts sticks,
// and nothing does once all of them slip (the slip branch has no stiffness along the slip), so
// Newton may stagnate there. Holding at a node a director component c that the spin turns,
// |e_c . (t x g)| > 0.1 |g| in the reference state, grips the fibre.
#pragma once

#include "engine/world.h"

#include <vector>

namespace fibra {

// Whether component c (3..8: g1x..g2z) of node n's reference director g moves when the section
// spins about the unit axis t, |e_c . (t x g)| > 0.1 |g|: holding it grips the spin. False for
// position components (c < 3).
bool gripsSpin(const FibreStore& fs, Index n, Index c, const Vec3& t);

// Friction that can act in the scene: between fibres (the section's or a pair rule's mu, with
// two fibres or self-contact) or with a tool, in a step whose friction factor is not 0.
bool frictionCanAct(const SceneDef& scene);

// The fibres (indices into world.fibres(), increasing) that are straight in the reference state
// (every node within 1e-6 of the fibre's length of the line through its end nodes), hold at
// least one position DOF, and no director component that their spin turns. Empty when no
// friction can act. fibra check and fibra run print them as a note (app/terminal.cpp).
std::vector<Index> freeSpinFibres(const World& world);

}  // namespace fibra
