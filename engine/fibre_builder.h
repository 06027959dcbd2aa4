// Fibre builder: turns a FibreDef (line, polyline or helix) into nodes and elements of a
// FibreStore, with reference directors: G1, G2 orthonormal and normal to the tangent at every
// node (transported without twist along lines and polylines; radial and binormal-like along a
// helix). Nodes lie at equal reference arc length; the current state starts at the reference.
#pragma once

#include "components/fibres.h"
#include "engine/scene.h"

namespace fibra {

// Appends fibre `def` (material index `material`) to `fibres`. Throws SceneError naming
// `path` (e.g. "fibres[3]") for a degenerate geometry.
void addFibre(FibreStore& fibres, const FibreDef& def, Index material, const std::string& path);

// Reference arc length of a geometry, mm.
double geometryLength(const GeometryDef& g);

}  // namespace fibra
