#include "systems/contact_particles.h"

#include "systems/particle.h"

#include <tbb/parallel_for.h>

namespace fibra {

void bindContactParticles(const FibreStore& fs, ContactElementStore& el) {
  tbb::parallel_for(Index(0), el.size(), [&](Index e) {
    const FibrePoint pI = locate(fs, el.fibreI[e], el.sI[e]);
    const FibrePoint pJ = locate(fs, el.fibreJ[e], el.sJ[e]);
    el.sideI[e] = particleWeights(fs, pI.element, pI.z, el.xiI1[e], el.xiI2[e]);
    el.sideJ[e] = particleWeights(fs, pJ.element, pJ.z, el.xiJ1[e], el.xiJ2[e]);
  });
}

}  // namespace fibra
