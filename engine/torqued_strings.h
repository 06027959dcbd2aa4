// Fibres without bending stiffness whose sections are twisted (docs/METHOD.md "Strings under
// torque").
//
// A rod of bending stiffness B under tension T and an axial torque M stays straight only while
// M < 2 sqrt(B T) (Greenhill's criterion for a long rod; A. E. H. Love, "A treatise on the
// mathematical theory of elasticity", §272; checked in tests/test_twisted_string.cpp). With
// bending_factor 0 only the tension's geometric stiffness B = T R^2 / 4 is left (the axial
// strain's terms quadratic in the section coordinate), so the limit is T R (R the radius;
// measured 0.9-1.2 T R, bench/twisted_string.py), and beyond it the string zigzags from node to
// node, kinks that the line contact between fibres misses (docs/RESULTS.md "Twisted yarn: the
// procedure"). A smaller torsion_factor lowers the torque.
#pragma once

#include "engine/world.h"

#include <vector>

namespace fibra {

struct TorquedString {
  Index fibre;    // index into world.fibres()
  double torque;  // N mm, the largest estimate below
  double radius;  // R, mm
};

// The fibres (increasing) whose material has bending_factor 0 and torsion_factor > 0 and that the
// scene twists about their own axis. A node grips the section when it holds a director component
// c that the spin about the local tangent t turns, |e_c . (t x g)| > 0.1 |g| (t from the
// neighbouring reference nodes, g the reference director). Torques:
//  - boundary conditions turn gripped sections by phi(s, time) = angle(time) a . t (0 for a grip
//    that does not rotate; a the rotation axis, unit); between neighbouring gripped sections s1 <
//    s2 along the fibre, torsion_factor G J |phi(s2) - phi(s1)| / (s2 - s1) at the tables' times
//    (G = E / (2 (1 + nu)), J = pi R^4 / 2): the elastic torque of a straight fibre twisted;
//  - moment loads M on nodes that do not grip, of a fibre gripped elsewhere: |sum of M . t times
//    the table's largest |value||, what the grips react.
// The larger of the two (not their sum).
// A fibre gripped at one section only, or turned as a whole, carries no torque from its
// boundary conditions. fibra check and fibra run print the fibres as a note (app/terminal.cpp).
std::vector<TorquedString> torquedStrings(const World& world);

}  // namespace fibra
