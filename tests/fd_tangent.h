// The assembled tangent by central finite differences of the residual the Newton loop
// differentiates: the assemble stage run at time t for q +- h on every free DOF, with the
// contact elements and normals as they are (tests only).
#pragma once

#include "engine/world_state.h"

#include <Eigen/Dense>

namespace fibra::test {

// K_fd(i, j) = (r_i(q + h e_j) - r_i(q - h e_j)) / 2h over the free DOFs; q is left as found.
inline Eigen::MatrixXd finiteDifferenceTangent(WorldState& w, double t, double h = 1e-8) {
  const Index n = w.system.freeCount;
  Eigen::MatrixXd K(n, n);
  for (Index j = 0; j < n; ++j) {
    const Index d = w.system.dofOf[j];
    w.fibres.q(d) += h;
    runStage(w, w.pipeline.assemble, t, false);
    const Eigen::VectorXd rp = w.system.r;
    w.fibres.q(d) -= 2 * h;
    runStage(w, w.pipeline.assemble, t, false);
    w.fibres.q(d) += h;
    for (Index i = 0; i < n; ++i)
      K(i, j) = (rp(w.system.dofOf[i]) - w.system.r(w.system.dofOf[i])) / (2 * h);
  }
  return K;
}

}  // namespace fibra::test
