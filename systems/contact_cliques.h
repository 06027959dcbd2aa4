// Contact cliques: binds the fibre-fibre contact elements to the tangent's sparsity pattern.
//
// Reads  FibreStore (element nodes), ContactParams (normalsInNewton), ContactElementStore (sideI,
//        sideJ: the two beam elements; fibre and s of the sections).
// Writes ContactCliqueStore (keys, colours, each element's clique, elements grouped by clique);
//        LinearSystem's pattern and scatter maps when the clique set changes.
// A contact clique couples the DOFs of the two beam elements (eI, eJ) of a contact element; all
// elements of one pair share it. The set of cliques only grows (a new pair rebuilds the
// pattern, which re-runs CHOLMOD's analysis), so that contact elements that come and go between
// iterations do not cost a new pattern each time, until more than half of it is unused (then it
// is rebuilt from the current pairs: cliques > 2 x used + 64). Only then are the cliques
// re-coloured: greedily in key order, a clique takes the first colour that none of the cliques
// sharing one of its nodes has, so cliques of a colour scatter in parallel without conflicts.
// Widening (while normalsInNewton, systems/contact_params.h): a linearised normal reads the
// section tangents, and a section within 1e-9 h of an interior node takes the mean of both
// elements' tangents
// (contactSection, systems/contact_geometry.h); that side's clique then also covers the other
// element at the node (w = 1: the one before the particle's element, 2: the one after), so that
// the whole derivative has a place in the pattern (systems/normal_linearisation.h).
// Threading: keys and look-ups in parallel; sorting, colouring and grouping serial.
#pragma once

#include "components/contact.h"
#include "components/contact_cliques.h"
#include "components/contact_params.h"
#include "components/linear_system.h"

namespace fibra {

void bindContactCliques(const FibreStore& fibres, const ContactParams& params,
                        const ContactElementStore& elements, ContactCliqueStore& cliques,
                        LinearSystem& ls);

}  // namespace fibra
