#include "systems/beam_evaluation.h"

#include "systems/beam_element.h"

#include <tbb/parallel_for.h>

namespace fibra {
namespace {

void sizeStore(const FibreStore& fs, BeamForceStore& out) {
  const Index n = fs.elements();
  out.forceFirst.assign(n + 1, 0);
  out.tangentFirst.assign(n + 1, 0);
  for (Index e = 0; e < n; ++e) {
    const Index dofs = kNodeDofs * (fs.order[fs.elementFibre[e]] + 1);
    out.forceFirst[e + 1] = out.forceFirst[e] + dofs;
    out.tangentFirst[e + 1] = out.tangentFirst[e] + dofs * dofs;
  }
  out.force.assign(out.forceFirst[n], 0.0);
  out.tangent.assign(out.tangentFirst[n], 0.0);
}

template <int Order>
void evaluateElement(const FibreStore& fs, const BeamStore& beams, Index e, bool withTangent,
                     BeamForceStore& out) {
  constexpr int n = kElementDofs<Order>;
  const ElementVector<Order> qe = fs.q.segment<n>(kNodeDofs * fs.elementFirstNode[e]);
  Eigen::Map<ElementVector<Order>> f(&out.force[out.forceFirst[e]]);
  ElementVector<Order> fe;
  if (withTangent) {
    ElementMatrix<Order> K;
    beamElement<Order>(elementPoints(beams, e), qe, fe, &K);
    Eigen::Map<Eigen::Matrix<double, n, n, Eigen::RowMajor>>(&out.tangent[out.tangentFirst[e]]) = K;
  } else {
    beamElement<Order>(elementPoints(beams, e), qe, fe, nullptr);
  }
  f = fe;
}

}  // namespace

void evaluateBeams(const FibreStore& fs, const BeamStore& beams, const IterationInput& input,
                   BeamForceStore& out) {
  if (out.forceFirst.size() != size_t(fs.elements()) + 1) sizeStore(fs, out);
  tbb::parallel_for(Index(0), fs.elements(), [&](Index e) {
    if (fs.order[fs.elementFibre[e]] == 2)
      evaluateElement<2>(fs, beams, e, input.withTangent, out);
    else
      evaluateElement<1>(fs, beams, e, input.withTangent, out);
  });
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
