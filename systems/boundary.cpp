#include "systems/boundary.h"

#include "systems/interpolation.h"
#include "systems/motion.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace fibra {
namespace {

// Adds v to K(I, J) for free DOFs I, J present in the pattern.
void addEntry(LinearSystem& ls, Index I, Index J, double v) {
  if (I < 0 || J < 0) return;
  if (ls.symmetric && I > J) return;
  const int* ip = ls.K.innerIndexPtr();
  const int* op = ls.K.outerIndexPtr();
  const int* it = std::lower_bound(ip + op[J], ip + op[J + 1], I);
  if (it != ip + op[J + 1] && *it == I) ls.K.valuePtr()[it - ip] += v;
}

// Torque |M| about the fixed axis e on node n: Pi = -|M| phi, phi = atan2(S, C) with
// C = sum_a u_a . g_a, S = sum_a (e x u_a) . g_a and u_a = G_a - (G_a . e) e: the angle of the
// planar rotation about e that best maps the reference directors' projections onto the
// current ones. C and S are linear in g, so dphi = (C dS - S dC) / rho^2 and
// d2phi = [dC dS] [[2CS, S^2 - C^2], [S^2 - C^2, -2CS]] [dC dS]^T / rho^4, rho^2 = C^2 + S^2.
void addMoment(const FibreStore& fs, Index n, const Vec3& M, const Eigen::VectorXd& q,
               bool withTangent, LinearSystem& ls) {
  const double m = M.norm();
  if (m == 0) return;
  const Vec3 e = M / m;
  const Index d = kNodeDofs * n + 3;  // first director DOF
  Eigen::Matrix<double, 6, 1> dC, dS;
  for (int a = 0; a < 2; ++a) {
    const Vec3 G = fs.qRef.segment<3>(d + 3 * a);
    const Vec3 u = G - G.dot(e) * e;
    dC.segment<3>(3 * a) = u;
    dS.segment<3>(3 * a) = e.cross(u);
  }
  const Eigen::Matrix<double, 6, 1> g = q.segment<6>(d);
  const double C = dC.dot(g), S = dS.dot(g), rho2 = C * C + S * S;
  if (rho2 == 0) return;
  const Eigen::Matrix<double, 6, 1> grad = -m * (C * dS - S * dC) / rho2;
  ls.r.segment<6>(d) += grad;
  ls.fext.segment<6>(d) -= grad;
  if (!withTangent) return;
  Eigen::Matrix<double, 6, 2> B;
  B << dC, dS;
  Eigen::Matrix2d H;
  H << 2 * C * S, S * S - C * C, S * S - C * C, -2 * C * S;
  const Eigen::Matrix<double, 6, 6> Kg = -m * B * H * B.transpose() / (rho2 * rho2);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) addEntry(ls, ls.equation[d + i], ls.equation[d + j], Kg(i, j));
}

// Consistent nodal forces of a line load w (N/mm): f_a = w (h/2) int_{-1}^{1} N_a dz.
void addLineForce(const FibreStore& fs, const LoadStore& loads, Index l, const Vec3& w,
                  LinearSystem& ls) {
  static constexpr double kWeights[2][3] = {{1, 1, 0}, {1.0 / 3, 4.0 / 3, 1.0 / 3}};
  for (Index k = loads.elementFirst[l]; k < loads.elementFirst[l + 1]; ++k) {
    const Index e = loads.elements[k], f = fs.elementFibre[e];
    const double half = 0.5 * elementLength(fs, f);
    for (int a = 0; a <= fs.order[f]; ++a) {
      const Vec3 fa = kWeights[fs.order[f] - 1][a] * half * w;
      const Index d = kNodeDofs * (fs.elementFirstNode[e] + a);
      ls.r.segment<3>(d) -= fa;
      ls.fext.segment<3>(d) += fa;
    }
  }
}

}  // namespace

void applyConstraints(const FibreStore& fs, const ConstraintStore& cs, const GroupStore& groups,
                      double time, Eigen::VectorXd& q) {
  for (size_t k = 0; k < cs.dof.size(); ++k) {
    const Index node = cs.dof[k] / kNodeDofs, comp = cs.dof[k] % kNodeDofs;
    const int block = comp / 3;
    const Vec3 ref = fs.qRef.segment<3>(kNodeDofs * node + 3 * block);
    const RigidMotion m = motionAt(cs.motion[cs.owner[k]], ref, time);
    const Vec3 target = block == 0 ? m(ref) : Vec3(m.R * ref);
    q(cs.dof[k]) = target(comp % 3);
  }
}

void assembleLoads(const FibreStore& fs, const LoadStore& loads, const GroupStore& groups,
                   const IterationInput& input, LinearSystem& ls) {
  const Eigen::VectorXd& q = fs.q;
  const double time = input.time;
  const bool withTangent = input.withTangent;
  ls.fext.setZero(q.size());
  for (Index l = 0; l < loads.size(); ++l) {
    const Vec3 v = loads.vector[l] * tableValue(loads.table[l], time);
    const Index g = loads.group[l];
    if (loads.kind[l] == LoadKind::LineForce) {
      addLineForce(fs, loads, l, v, ls);
      continue;
    }
    for (Index k = groups.first[g]; k < groups.first[g] + groups.count[g]; ++k) {
      const Index n = groups.members[k];
      if (loads.kind[l] == LoadKind::Force) {
        ls.r.segment<3>(kNodeDofs * n) -= v;
        ls.fext.segment<3>(kNodeDofs * n) += v;
      } else {
        addMoment(fs, n, v, q, withTangent, ls);
      }
    }
  }
}

Reaction reactionOf(const ConstraintStore& cs, const Eigen::VectorXd& q, const Eigen::VectorXd& r,
                    Index bc, const Vec3& point) {
  Reaction out;
  for (size_t k = 0; k < cs.dof.size(); ++k) {
    if (cs.owner[k] != bc) continue;
    const Index node = cs.dof[k] / kNodeDofs, comp = cs.dof[k] % kNodeDofs;
    const int block = comp / 3;
    const Vec3 rk = Vec3::Unit(comp % 3) * r(cs.dof[k]);
    const Vec3 arm = q.segment<3>(kNodeDofs * node + 3 * block) - (block == 0 ? point : Vec3::Zero());
    if (block == 0) out.force += rk;
    out.moment += arm.cross(rk);
  }
  return out;
}

}  // namespace fibra
