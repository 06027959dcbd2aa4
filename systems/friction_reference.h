// Friction reference (paper section 4.3.1): the state from which the slip of every new contact
// element is measured, and the reversible slip it starts with, transferred from the friction
// history of its particles; fibre-fibre and fibre-tool elements alike.
//
// Reads  FibreStore (q), ToolStore (motion), FrictionHistoryStore, IterationInput (time).
// Writes ContactElementStore::d0, gRev0 and ToolContactStore::d0, gRev0.
//   fibre-fibre: d0 = x^I - x^J,  g_rev,0 = P_N (h_I(s_I) - h_J(s_J)) / 2
//   fibre-tool:  d0 = x - M(t) p, g_rev,0 = P_N h(s)
// with h_f(s) the slip stored on fibre f against the element's partner, interpolated along the
// fibre within one element length (systems/friction_history.h), P_N = I - N N^T.
// Serial (look-ups in the sorted history).
#pragma once

#include "components/contact.h"
#include "components/friction_history.h"
#include "components/iteration.h"
#include "components/tools.h"

namespace fibra {

void setFrictionReference(const FibreStore& fibres, const ToolStore& tools,
                          const FrictionHistoryStore& history, const IterationInput& input,
                          ContactElementStore& elements, ToolContactStore& toolElements);

}  // namespace fibra
