// Tool normals (the paper's loop B for fibre-tool elements): the surface normal and the gap of
// every tool contact element at its particle's current position, for the same particles.
//
// Reads  FibreStore (q), ToolStore, IterationInput (time).
// Writes ToolContactStore::normal, gap, and gRev0 re-projected onto the new tangent plane;
//        ContactLoopStats::normalTurn, the largest angle a normal turned by (rad).
// Serial in element order (tool contacts are few).
#pragma once

#include "components/iteration.h"
#include "components/tools.h"

namespace fibra {

void updateToolNormals(const FibreStore& fibres, const ToolStore& tools,
                       const IterationInput& input, ToolContactStore& contacts,
                       ContactLoopStats& stats);

}  // namespace fibra
