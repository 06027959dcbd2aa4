// Contact particles: every fibre-fibre contact element's two material particles (fibre, s, xi)
// as weights on their elements' DOFs (systems/particle.h), which is all the law and the scatter
// need of them while they are fixed (eq. 2: x is linear in the DOFs).
//
// Reads  FibreStore (element layout), ContactElementStore (fibreI/J, sI/J, xi).
// Writes ContactElementStore::sideI, sideJ. Parallel over elements, each writing its own entries.
#pragma once

#include "components/contact.h"

namespace fibra {

void bindContactParticles(const FibreStore& fibres, ContactElementStore& elements);

}  // namespace fibra
