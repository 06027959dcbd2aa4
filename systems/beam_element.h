// Beam element: energy, internal force and exact tangent of one element (paper section 2.2).
//
// Reads one element's nodal DOFs q_e = [x0 g1 g2] per node and its BeamStore points (D_p, eRef_p).
// Writes its energy, force f_e = dPi/dq_e and tangent K_e = d2Pi/dq_e2. Pure function, no state:
// the assembler calls it from many threads.
//
// Pi_e = sum_p 1/2 e_p^T D_p e_p with e_k = c_k v_a.v_b - eRef_k (beam_section.h), plus at the
// points of a nonlinear law the pointwise section integral W_p(e_p) (systems/section_law.h), which
// adds to sigma its dW_p/de and to D its d2W_p/de2. Writing sigma = dPi_p/de_p (the generalised
// stresses; D e_p for Saint Venant-Kirchhoff), D = d2Pi_p/de_p2 and F_a = dPi/dv_a:
//   F_a = sum_k sigma_k c_k (delta(a, a_k) v_{b_k} + delta(a, b_k) v_{a_k})
//   d2Pi/dv_a dv_b = G_a^T D G_b + sum_k sigma_k c_k (delta(a,a_k) delta(b,b_k)
//                                                   + delta(a,b_k) delta(b,a_k)) I3,
// with G_a = de/dv_a (15 x 3). Each v_a = sum_n S_a(n) u_n(field a), S_a = N or dN/dz, so
//   f(n, field a) += S_a(n) F_a,   K(n field a, m field b) += S_a(n) S_b(m) d2Pi/dv_a dv_b.
// The strains are exactly quadratic in q, so this tangent is exact. Where a section point's
// det C <= 0 (a nonlinear law's section turned inside out) the energy is +inf and the force is
// not finite.
#pragma once

#include "components/beam_store.h"

#include <Eigen/Core>

namespace fibra {

template <int Order>
constexpr int kElementDofs = kNodeDofs * (Order + 1);

template <int Order>
using ElementVector = Eigen::Matrix<double, kElementDofs<Order>, 1>;
template <int Order>
using ElementMatrix = Eigen::Matrix<double, kElementDofs<Order>, kElementDofs<Order>>;

// The integration points of one element, as stored in the BeamStore.
struct ElementPoints {
  const double* z;
  const Mat15* D;
  const Vec15* eRef;
  int count;
  const Index* law;                   // per point: its LawSection, or -1
  const LawSection* lawSections;      // BeamStore::lawSections
  const SectionPoint* sectionPoints;  // BeamStore::sectionPoints
};

inline ElementPoints elementPoints(const BeamStore& b, Index e) {
  const Index i = b.firstPoint[e];
  return {&b.z[i], &b.D[i], &b.eRef[i], b.pointCount[e], &b.law[i], b.lawSections.data(),
          b.sectionPoints.data()};
}

// Energy (N mm). K may be null (force only).
template <int Order>
double beamElement(const ElementPoints& pts, const ElementVector<Order>& q,
                   ElementVector<Order>& f, ElementMatrix<Order>* K);

// Energy only.
template <int Order>
double beamElementEnergy(const ElementPoints& pts, const ElementVector<Order>& q);

// Generalised strains e at element parameter z (for output and tests).
template <int Order>
Vec15 beamStrains(const ElementVector<Order>& q, double z, const Vec15& eRef);

extern template double beamElement<1>(const ElementPoints&, const ElementVector<1>&,
                                      ElementVector<1>&, ElementMatrix<1>*);
extern template double beamElement<2>(const ElementPoints&, const ElementVector<2>&,
                                      ElementVector<2>&, ElementMatrix<2>*);
extern template double beamElementEnergy<1>(const ElementPoints&, const ElementVector<1>&);
extern template double beamElementEnergy<2>(const ElementPoints&, const ElementVector<2>&);
extern template Vec15 beamStrains<1>(const ElementVector<1>&, double, const Vec15&);
extern template Vec15 beamStrains<2>(const ElementVector<2>&, double, const Vec15&);

}  // namespace fibra
