#include "systems/boundary.h"

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

Eigen::Matrix3d rotationOf(const BcDef& bc, double time) {
  if (!bc.rotates) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(tableValue(bc.angle, time), bc.axis.normalized()).toRotationMatrix();
}

// Basis (b1, b2) of the plane normal to unit e.
std::pair<Vec3, Vec3> planeBasis(const Vec3& e) {
  Eigen::Index i;
  e.cwiseAbs().minCoeff(&i);
  const Vec3 b1 = (Vec3::Unit(i) - e(i) * e).normalized();
  return {b1, e.cross(b1)};
}

// Torque |M| about fixed axis e on node n: gradient of -|M| sum_a w_a phi_a into r, Hessian into K.
void addMoment(const FibreStore& fs, Index n, const Vec3& M, const Eigen::VectorXd& q,
               bool withTangent, LinearSystem& ls) {
  const double m = M.norm();
  if (m == 0) return;
  const Vec3 e = M / m;
  const auto [b1, b2] = planeBasis(e);
  double wsum = 0, w[2];
  for (int a = 0; a < 2; ++a) {
    const Vec3 G = fs.qRef.segment<3>(kNodeDofs * n + 3 + 3 * a);
    w[a] = (G - G.dot(e) * e).squaredNorm();
    wsum += w[a];
  }
  for (int a = 0; a < 2; ++a) {
    const Index d = kNodeDofs * n + 3 + 3 * a;
    const Vec3 g = q.segment<3>(d);
    const double x = b1.dot(g), y = b2.dot(g), rho2 = x * x + y * y;
    const double c = -m * w[a] / wsum;
    if (rho2 == 0 || c == 0) continue;
    const Vec3 grad = c * (-y * b1 + x * b2) / rho2;
    ls.r.segment<3>(d) += grad;
    ls.fext.segment<3>(d) -= grad;
    if (!withTangent) continue;
    Eigen::Matrix<double, 3, 2> B;
    B << b1, b2;
    Eigen::Matrix2d H;
    H << 2 * x * y, y * y - x * x, y * y - x * x, -2 * x * y;
    const Eigen::Matrix3d Kg = c * B * H * B.transpose() / (rho2 * rho2);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) addEntry(ls, ls.equation[d + i], ls.equation[d + j], Kg(i, j));
  }
}

}  // namespace

void applyConstraints(const FibreStore& fs, const ConstraintStore& cs, const GroupStore& groups,
                      double time, Eigen::VectorXd& q) {
  for (size_t k = 0; k < cs.dof.size(); ++k) {
    const BcDef& bc = cs.def[cs.owner[k]];
    const Index node = cs.dof[k] / kNodeDofs, comp = cs.dof[k] % kNodeDofs;
    const Eigen::Matrix3d R = rotationOf(bc, time);
    const int block = comp / 3;
    const Vec3 ref = fs.qRef.segment<3>(kNodeDofs * node + 3 * block);
    Vec3 target;
    if (block == 0) {
      const Vec3 c = bc.centre.allFinite() ? bc.centre : ref;
      target = c + R * (ref - c) + bc.displacement * tableValue(bc.displacementTable, time);
    } else {
      target = R * ref;
    }
    q(cs.dof[k]) = target(comp % 3);
  }
}

void assembleLoads(const FibreStore& fs, const LoadStore& loads, const GroupStore& groups,
                   const Eigen::VectorXd& q, double time, bool withTangent, LinearSystem& ls) {
  ls.fext.setZero(q.size());
  for (size_t l = 0; l < loads.def.size(); ++l) {
    const LoadDef& def = loads.def[l];
    const Vec3 v = def.vector * tableValue(def.table, time);
    const Index g = loads.group[l];
    for (Index k = groups.first[g]; k < groups.first[g] + groups.count[g]; ++k) {
      const Index n = groups.members[k];
      if (def.kind == LoadKind::Force) {
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
