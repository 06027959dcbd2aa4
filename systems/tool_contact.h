// Tool contact law system: the force and stiffness of every fibre-tool contact element at the
// current state and time, with the laws of fibre-fibre contact (systems/contact_law.h).
//
// Reads  FibreStore (q), ToolStore (motion, friction), ToolZoneStore (penalty, p_max),
//        ContactParams (p_reg / p_max, g_T,max, symmetrised), ToolContactStore (particles,
//        weights, normals, tool points, friction reference), IterationInput (time).
// Writes ContactForceStore of the tool elements (gap, R_N, force on the fibre, stiffness,
//        g_rev, slip), FrictionStatusStore (as the fibre-fibre law: systems/friction_status.h).
// Per element: d = x(particle) - M(t) p, the law with the zone's penalty times the element's
// weight (1 lateral, |t . N| on an end face: systems/tool_detection.cpp). The force the fibres
// exert on a tool is the sum of -force over its elements (World::toolReaction).
// Threading: parallel over elements, each writing its own entries. Runs beside the beam
// evaluation and the fibre-fibre contact law.
#pragma once

#include "components/contact_forces.h"
#include "components/contact_params.h"
#include "components/friction_status.h"
#include "components/iteration.h"
#include "components/tools.h"

namespace fibra {

void evaluateToolContacts(const FibreStore& fibres, const ToolStore& tools,
                          const ToolZoneStore& zones, const ContactParams& params,
                          const ToolContactStore& contacts, const IterationInput& input,
                          FrictionStatusStore& status, ContactForceStore& forces);

}  // namespace fibra
