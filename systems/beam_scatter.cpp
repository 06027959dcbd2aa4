#include "systems/beam_scatter.h"

#include <tbb/parallel_for.h>

namespace fibra {
namespace {

void scatterElement(const FibreStore& fs, const BeamForceStore& in, Index e, bool withTangent,
                    LinearSystem& ls) {
  const int n = kNodeDofs * (fs.order[fs.elementFibre[e]] + 1);
  const Index d0 = kNodeDofs * fs.elementFirstNode[e];
  const double* f = &in.force[in.forceFirst[e]];
  for (int i = 0; i < n; ++i) ls.r(d0 + i) += f[i];
  if (!withTangent) return;
  const double* K = &in.tangent[in.tangentFirst[e]];
  const Index* pos = &ls.positions[ls.cliqueFirst[e]];
  double* values = ls.K.valuePtr();
  for (int i = 0; i < n * n; ++i)
    if (const Index p = pos[i]; p >= 0) values[p] += K[i];
}

}  // namespace

void scatterBeams(const FibreStore& fs, const BeamStore& beams, const BeamForceStore& forces,
                  const IterationInput& input, LinearSystem& ls) {
  for (const std::vector<Index>& colour : beams.colours)
    tbb::parallel_for(size_t(0), colour.size(), [&](size_t k) {
      scatterElement(fs, forces, colour[k], input.withTangent, ls);
    });
}

}  // namespace fibra
