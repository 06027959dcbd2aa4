#include "systems/stabilisation.h"

#include <tbb/parallel_for.h>

namespace fibra {
namespace {

// A node's stiffness k on DOF d: k on the centroid, k R^2 on the directors.
double onDof(const FibreStore& fs, double k, Index d) {
  const double R = fs.radius[fs.nodeFibre[d / kNodeDofs]];
  return d % kNodeDofs < 3 ? k : k * R * R;
}

Eigen::VectorXd force(const FibreStore& fs, const StabilisationStore& st, bool spring) {
  const Eigen::VectorXd &q = fs.q, &qStart = st.qStart;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
  for (Index d = 0; d < q.size(); ++d)
    f(d) = onDof(fs, spring ? st.stiffness[d / kNodeDofs] : st.viscous, d) * (q(d) - qStart(d));
  return f;
}

}  // namespace

void assembleStabilisation(const FibreStore& fs, const StabilisationStore& st,
                           const IterationInput& input, LinearSystem& ls) {
  const Eigen::VectorXd &q = fs.q, &qStart = st.qStart;
  const bool withTangent = input.withTangent;
  tbb::parallel_for(Index(0), fs.nodes(), [&](Index n) {
    const double k = st.stiffness[n] + st.viscous;
    if (k == 0) return;
    for (Index d = kNodeDofs * n; d < kNodeDofs * (n + 1); ++d) {
      const Index eq = ls.equation[d];
      if (eq < 0) continue;
      const double kd = onDof(fs, k, d);
      ls.r(d) += kd * (q(d) - qStart(d));
      if (withTangent) ls.K.valuePtr()[ls.diagonal[eq]] += kd;
    }
  });
}

Eigen::VectorXd springForce(const FibreStore& fs, const StabilisationStore& st) { return force(fs, st, true); }

Eigen::VectorXd viscousForce(const FibreStore& fs, const StabilisationStore& st) { return force(fs, st, false); }

}  // namespace fibra
