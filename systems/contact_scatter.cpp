#include "systems/contact_scatter.h"

#include <tbb/parallel_for.h>

namespace fibra {

void scatterFibreContacts(const ContactElementStore& el, const ContactForceStore& f,
                          const ContactCliqueStore& c, const IterationInput& input,
                          LinearSystem& ls) {
  const double sign[2] = {1, -1};
  for (Index colour = 0; colour < c.colours(); ++colour) {
    const Index first = c.colourFirst[colour], count = c.colourFirst[colour + 1] - first;
    tbb::parallel_for(Index(0), count, [&](Index k) {
      const Index q = c.colourClique[first + k];
      for (Index i = c.cliqueFirst[q]; i < c.cliqueFirst[q + 1]; ++i) {
        const Index e = c.byClique[i];
        if (f.normalForce[e] == 0) continue;
        const ParticleWeights sides[2] = {el.sideI[e], el.sideJ[e]};
        scatterContact(sides, sign, 2, f.force[e], f.stiffness[e], c.firstClique + q,
                       input.withTangent, ls);
      }
    });
  }
}

void scatterToolContacts(const ToolContactStore& el, const ContactForceStore& f,
                         const IterationInput& input, LinearSystem& ls) {
  const double sign = 1;
  for (Index i = 0; i < el.size(); ++i)
    if (f.normalForce[i] > 0)
      scatterContact(&el.side[i], &sign, 1, f.force[i], f.stiffness[i], el.element[i],
                     input.withTangent, ls);
}

}  // namespace fibra
