#include "systems/stabilisation.h"

#include <tbb/parallel_for.h>

namespace fibra {
namespace {

double dofStiffness(const FibreStore& fs, const std::vector<double>& k, Index dof) {
  const Index n = dof / kNodeDofs;
  const double R = fs.radius[fs.nodeFibre[n]];
  return dof % kNodeDofs < 3 ? k[n] : k[n] * R * R;
}

}  // namespace

void assembleStabilisation(const FibreStore& fs, const StabilisationStore& st,
                           const IterationInput& input, LinearSystem& ls) {
  const Eigen::VectorXd &q = fs.q, &qStart = st.qStart;
  const std::vector<double>& k = st.stiffness;
  const bool withTangent = input.withTangent;
  tbb::parallel_for(Index(0), fs.nodes(), [&](Index n) {
    if (k[n] == 0) return;
    for (Index d = kNodeDofs * n; d < kNodeDofs * (n + 1); ++d) {
      const Index eq = ls.equation[d];
      if (eq < 0) continue;
      const double kd = dofStiffness(fs, k, d);
      ls.r(d) += kd * (q(d) - qStart(d));
      if (withTangent) ls.K.valuePtr()[ls.diagonal[eq]] += kd;
    }
  });
}

Eigen::VectorXd stabilisationForce(const FibreStore& fs, const StabilisationStore& st) {
  const Eigen::VectorXd &q = fs.q, &qStart = st.qStart;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
  for (Index d = 0; d < q.size(); ++d) f(d) = dofStiffness(fs, st.stiffness, d) * (q(d) - qStart(d));
  return f;
}

}  // namespace fibra
