#include "systems/beam_assembler.h"

#include "systems/beam_element.h"

#include <tbb/parallel_for.h>

namespace fibra {
namespace {

template <int Order>
void assembleElement(const FibreStore& fs, const BeamStore& beams, const Eigen::VectorXd& q,
                     Index e, bool withTangent, LinearSystem& ls) {
  constexpr int n = kElementDofs<Order>;
  const Index d0 = kNodeDofs * fs.elementFirstNode[e];
  const ElementVector<Order> qe = q.segment<n>(d0);
  ElementVector<Order> f;
  ElementMatrix<Order> K;
  beamElement<Order>(elementPoints(beams, e), qe, f, withTangent ? &K : nullptr);
  ls.r.segment<n>(d0) += f;
  if (!withTangent) return;
  const Index* pos = &ls.positions[ls.cliqueFirst[e]];
  double* values = ls.K.valuePtr();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (const Index p = pos[i * n + j]; p >= 0) values[p] += K(i, j);
}

}  // namespace

void assembleBeams(const FibreStore& fs, const BeamStore& beams, const Eigen::VectorXd& q,
                   bool withTangent, LinearSystem& ls) {
  for (const std::vector<Index>& colour : beams.colours) {
    tbb::parallel_for(size_t(0), colour.size(), [&](size_t k) {
      const Index e = colour[k];
      if (fs.order[fs.elementFibre[e]] == 2)
        assembleElement<2>(fs, beams, q, e, withTangent, ls);
      else
        assembleElement<1>(fs, beams, q, e, withTangent, ls);
    });
  }
}

double beamEnergy(const FibreStore& fs, const BeamStore& beams, const Eigen::VectorXd& q) {
  double energy = 0;
  for (Index e = 0; e < fs.elements(); ++e) {
    const Index d0 = kNodeDofs * fs.elementFirstNode[e];
    const ElementPoints pts = elementPoints(beams, e);
    if (fs.order[fs.elementFibre[e]] == 2)
      energy += beamElementEnergy<2>(pts, q.segment<kElementDofs<2>>(d0));
    else
      energy += beamElementEnergy<1>(pts, q.segment<kElementDofs<1>>(d0));
  }
  return energy;
}

}  // namespace fibra
