// Fibres without bending stiffness whose sections are twisted (docs/METHOD.md "Strings under
// torque").
//
// A rod of bending stiffness B under tension T and an axial torque M stays straight only while
// M < 2 sqrt(B T) (Greenhill's criterion for a long rod; A. E. H. Love, "A treatise on the
// mathematical theory of elasticity", §272; checked in tests/test_twisted_string.cpp). With
// bending_factor 0 the limit is 0, and the finite elements buckle at their own scale, a zigzag
// from node to node, once M passes about T h / pi (h the element length: the shortest wave the
// mesh carries); the line contact between fibres misses those kinks (docs/RESULTS.md "Twisted
// yarn: the procedure"). A smaller torsion_factor lowers the torque.
#pragma once

#include "engine/world.h"

#include <vector>

namespace fibra {

struct TorquedString {
  Index fibre;           // index into world.fibres()
  double torque;         // N mm: torsion_factor G J phi / L, or the moment load's axial part
  double elementLength;  // h = L / elements, mm
};

// The fibres (increasing) whose material has bending_factor 0 and torsion_factor > 0 and that
// the scene twists about their own axis t (the unit chord of the reference centreline, first node
// to last):
//  - a held director component of one of their nodes belongs to a boundary condition that rotates
//    by the angle table's largest |phi| about an axis a with |a . t| > 0.1: torque
//    torsion_factor G J |phi| |a . t| / L (G = E / (2 (1 + nu)), J = pi R^4 / 2, L the fibre's
//    reference length), the elastic torque of a straight fibre twisted end to end;
//  - or a moment load M (times its table's largest |value|) acts on one of their nodes with
//    |M . t| > 0.1 |M|: torque |M . t|.
// The largest of these per fibre. fibra check and fibra run print them as a note
// (app/terminal.cpp).
std::vector<TorquedString> torquedStrings(const World& world);

}  // namespace fibra
