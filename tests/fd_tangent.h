// The assembled tangent by central finite differences of the residual the Newton loop
// differentiates: the assemble stage run at time t for q +- h on every free DOF, with the
// contact elements and normals as they are; and the contact law's own tangent likewise (tests
// only).
#pragma once

#include "engine/world_state.h"
#include "systems/contact_law.h"

#include <Eigen/Dense>

namespace fibra::test {

// The tangent last assembled as a full matrix: both triangles where only the upper one is stored
// (LinearSystem::symmetric).
inline Eigen::MatrixXd fullTangent(const LinearSystem& ls) {
  const Eigen::MatrixXd K(ls.K);
  if (!ls.symmetric) return K;
  return K.selfadjointView<Eigen::Upper>();
}

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

// The contact law's stiffness -df/dd against central differences of its force (h mm) at d, with
// the branch `hold` (systems/contact_law.h): |K_fd - K| / |K|.
inline double lawTangentError(const Vec3& d, const ContactLawState& s, const ContactLawParams& p,
                              std::uint8_t hold = kStatusNone, double h = 1e-9) {
  const ContactLawResult r = contactLaw(d, s, p, false, hold);
  Eigen::Matrix3d fd;
  for (int i = 0; i < 3; ++i) {
    Vec3 dp = d, dm = d;
    dp(i) += h;
    dm(i) -= h;
    fd.col(i) = -(contactLaw(dp, s, p, false, hold).force - contactLaw(dm, s, p, false, hold).force) /
                (2 * h);
  }
  return (fd - r.stiffness).norm() / r.stiffness.norm();
}

}  // namespace fibra::test
