#include "systems/beam_element.h"

#include "systems/beam_section.h"
#include "systems/interpolation.h"
#include "systems/section_law.h"

#include <cmath>

namespace fibra {
namespace {

using Vec15v = Eigen::Matrix<double, 15, 1>;  // the five vectors v_a stacked
template <int Order>
using Interp = Eigen::Matrix<double, 15, kElementDofs<Order>>;  // v = T q

// T: v_a = sum_n S_a(n) u_n(field a), S_a = N (value) or dN/dz (derivative).
template <int Order>
Interp<Order> interpolationMatrix(double z) {
  double N[3], dN[3];
  lagrangeShape(Order, z, N, dN);
  Interp<Order> T = Interp<Order>::Zero();
  for (int a = 0; a < 5; ++a) {
    const double* S = kVecDeriv[a] ? dN : N;
    for (int n = 0; n <= Order; ++n)
      for (int i = 0; i < 3; ++i) T(3 * a + i, kNodeDofs * n + 3 * kVecField[a] + i) = S[n];
  }
  return T;
}

Vec15 strainsOf(const Vec15v& v, const Vec15& eRef) {
  Vec15 e;
  for (int k = 0; k < kGenStrains; ++k) {
    const StrainPair& sp = kStrainPairs[k];
    e(k) = sp.c * v.segment<3>(3 * sp.a).dot(v.segment<3>(3 * sp.b)) - eRef(k);
  }
  return e;
}

// dPi/dv: F_a = sum_k sigma_k c_k (delta(a,a_k) v_{b_k} + delta(a,b_k) v_{a_k}).
Vec15v vectorForces(const Vec15v& v, const Vec15& sigma) {
  Vec15v F = Vec15v::Zero();
  for (int k = 0; k < kGenStrains; ++k) {
    const StrainPair& sp = kStrainPairs[k];
    const double s = sigma(k) * sp.c;
    F.segment<3>(3 * sp.a) += s * v.segment<3>(3 * sp.b);
    F.segment<3>(3 * sp.b) += s * v.segment<3>(3 * sp.a);
  }
  return F;
}

// d2Pi/dv2 = G^T D G (material) + stress-weighted identity blocks (geometric).
Mat15 vectorHessian(const Vec15v& v, const Vec15& sigma, const Mat15& D) {
  Mat15 G = Mat15::Zero();  // de/dv
  for (int k = 0; k < kGenStrains; ++k) {
    const StrainPair& sp = kStrainPairs[k];
    G.block<1, 3>(k, 3 * sp.a) += sp.c * v.segment<3>(3 * sp.b).transpose();
    G.block<1, 3>(k, 3 * sp.b) += sp.c * v.segment<3>(3 * sp.a).transpose();
  }
  Mat15 H = G.transpose() * D * G;
  for (int k = 0; k < kGenStrains; ++k) {
    const StrainPair& sp = kStrainPairs[k];
    const double s = sigma(k) * sp.c;
    H.block<3, 3>(3 * sp.a, 3 * sp.b).diagonal().array() += s;
    H.block<3, 3>(3 * sp.b, 3 * sp.a).diagonal().array() += s;
  }
  return H;
}

// The energy of point p at the generalised strains e, with sigma = dPi_p/de and, when `law` is
// not null, D = d2Pi_p/de2 in *law: the constant form D_p, plus a nonlinear law's section
// integral (then *D points to *law; for Saint Venant-Kirchhoff it stays at D_p, uncopied).
double pointEnergy(const ElementPoints& pts, int p, const Vec15& e, Vec15& sigma,
                   const Mat15** D, Mat15* law) {
  sigma.noalias() = pts.D[p] * e;
  double energy = 0.5 * e.dot(sigma);
  if (D) *D = &pts.D[p];
  if (pts.law[p] < 0) return energy;
  if (D) *law = pts.D[p], *D = law;
  return energy + addSectionLaw(pts.lawSections[pts.law[p]], pts.sectionPoints, e, sigma,
                                D ? law : nullptr);
}

}  // namespace

template <int Order>
double beamElement(const ElementPoints& pts, const ElementVector<Order>& q,
                   ElementVector<Order>& f, ElementMatrix<Order>* K) {
  double energy = 0;
  f.setZero();
  if (K) K->setZero();
  for (int p = 0; p < pts.count; ++p) {
    const Interp<Order> T = interpolationMatrix<Order>(pts.z[p]);
    const Vec15v v = T * q;
    const Vec15 e = strainsOf(v, pts.eRef[p]);
    Vec15 sigma;
    const Mat15* D = nullptr;
    Mat15 lawD;
    energy += pointEnergy(pts, p, e, sigma, K ? &D : nullptr, &lawD);
    if (!std::isfinite(energy)) {
      f.setConstant(energy);
      return energy;
    }
    f.noalias() += T.transpose() * vectorForces(v, sigma);
    if (K) K->noalias() += T.transpose() * vectorHessian(v, sigma, *D) * T;
  }
  return energy;
}

template <int Order>
double beamElementEnergy(const ElementPoints& pts, const ElementVector<Order>& q) {
  double energy = 0;
  for (int p = 0; p < pts.count; ++p) {
    const Vec15 e = strainsOf(interpolationMatrix<Order>(pts.z[p]) * q, pts.eRef[p]);
    Vec15 sigma;
    energy += pointEnergy(pts, p, e, sigma, nullptr, nullptr);
  }
  return energy;
}

template <int Order>
Vec15 beamStrains(const ElementVector<Order>& q, double z, const Vec15& eRef) {
  return strainsOf(interpolationMatrix<Order>(z) * q, eRef);
}

template double beamElement<1>(const ElementPoints&, const ElementVector<1>&, ElementVector<1>&,
                               ElementMatrix<1>*);
template double beamElement<2>(const ElementPoints&, const ElementVector<2>&, ElementVector<2>&,
                               ElementMatrix<2>*);
template double beamElementEnergy<1>(const ElementPoints&, const ElementVector<1>&);
template double beamElementEnergy<2>(const ElementPoints&, const ElementVector<2>&);
template Vec15 beamStrains<1>(const ElementVector<1>&, double, const Vec15&);
template Vec15 beamStrains<2>(const ElementVector<2>&, double, const Vec15&);

}  // namespace fibra
