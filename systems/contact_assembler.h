// Contact assembler: forces and tangents of the fibre-fibre contact elements.
//
// Reads  the state q, ContactMechanicsStore (particles, normals, friction references, zone
//        penalties, clique colours), the law parameters.
// Writes ContactMechanicsStore results (gap, R_N, force, g_rev, slip) and LinearSystem r, K.
// Per element (systems/contact_law.h): d = x^I - x^J, the law gives the force f on I and
// S = -df/dd; the element adds r -= D^T f, K += D^T S D (systems/contact_scatter.h).
// Threading: the laws are evaluated in parallel over elements (each writes its own results);
// the scatter runs colour by colour, cliques of one colour (no shared node) in parallel, the
// elements of a clique in ascending order: every entry receives its contributions in a fixed
// order, so the result does not depend on the thread count.
#pragma once

#include "components/contact_mechanics.h"
#include "components/linear_system.h"

namespace fibra {

struct ContactAssemblyParams {
  double pMax = 0;       // mm
  double pRegRatio = 0;  // p_reg / p_max
  double mu = 0;         // friction coefficient
  double gMax = 0;       // reversible slip, mm
  bool symmetrised = false;
};

// Groups the elements by clique and colours the contact cliques greedily by node (call after
// the elements or their cliques change). `contactCliques` is the number of contact cliques.
void colourContactCliques(ContactMechanicsStore& m, Index contactCliques);

void assembleContacts(const Eigen::VectorXd& q, const ContactAssemblyParams& params,
                      bool withTangent, ContactMechanicsStore& m, LinearSystem& ls);

}  // namespace fibra
