// Beam section system: builds the per-point section stiffness D and reference products of every
// beam element (the BeamStore) from the reference state.
//
// Reads  FibreStore (qRef, order, radius, material), MaterialStore, per-fibre BeamIntegration.
// Writes BeamStore. Runs once per scene, parallel over elements (each writes its own points).
//
// Kinematics (paper eq. 2): x = x0 + xi1 g1 + xi2 g2, convected coordinates (xi1, xi2, z).
// With v0 = x0,z  v1 = g1  v2 = g2  v3 = g1,z  v4 = g2,z (and V_a in the reference), the
// covariant base vectors are a1 = v1, a2 = v2, a3 = v0 + xi1 v3 + xi2 v4 and the Green-Lagrange
// components E_ij = (a_i.a_j - A_i.A_j)/2 are polynomials in (xi1, xi2):
//   E11 = e0  E22 = e1  E12 = e2
//   E13 = e3 + xi1 e5 + xi2 e6        E23 = e4 + xi1 e7 + xi2 e8
//   E33 = e9 + xi1 e10 + xi2 e11 + xi1^2 e12 + xi1 xi2 e13 + xi2^2 e14
// with e_k = c_k (v_a.v_b - V_a.V_b) (table kStrainPairs). E = E(xi) = Phi(xi) e.
//
// Constitutive law per point: Saint Venant-Kirchhoff, W = lambda/2 (A^ij E_ij)^2
// + mu A^ik A^jl E_ij E_kl, with the contravariant reference metric A^ij. Two corrections act on
// the fluctuation E' = E - mean_section(E):
//  * Poisson locking: E11, E22 are constant over the section, so under bending E33' is resisted
//    by lambda + 2 mu instead of E. We subtract (lambda + 2 mu - E)/2 eps_n'^2, eps_n' the
//    physical axial strain of E' (A^3 direction), which restores EI exactly and leaves the mean
//    (axial stretch with free Poisson contraction) untouched.
//  * Stiffness factors: E33' is scaled by sqrt(f_bend), E13', E23' by sqrt(f_tors) - the
//    "reduced moments of inertia used for stresses" of the paper (section 2.2).
// W is quadratic in e, so the section energy integral is 1/2 e^T D e with a constant D:
//   Moments:    metric frozen at the centroid, exact disc moments int xi1^a xi2^b dA;
//   Quadrature: pointwise metric (curved references), polar rule rings x sectors.
#pragma once

#include "components/beam_store.h"

#include <stdexcept>
#include <vector>

namespace fibra {

struct StrainPair {
  int a, b;  // the two interpolated vectors v_a, v_b
  double c;  // e_k = c (v_a . v_b - V_a . V_b)
};
inline constexpr StrainPair kStrainPairs[kGenStrains] = {
    {1, 1, 0.5}, {2, 2, 0.5}, {1, 2, 0.5},                // E11 E22 E12
    {1, 0, 0.5}, {2, 0, 0.5},                             // E13, E23 constant parts
    {1, 3, 0.5}, {1, 4, 0.5}, {2, 3, 0.5}, {2, 4, 0.5},   // E13, E23 linear parts
    {0, 0, 0.5}, {0, 3, 1.0}, {0, 4, 1.0},                // E33 constant, linear
    {3, 3, 0.5}, {3, 4, 1.0}, {4, 4, 0.5}};               // E33 quadratic
// Vector a: which nodal field it interpolates (0 x0, 1 g1, 2 g2), and whether it is the
// z-derivative (1) or the value (0).
inline constexpr int kVecField[5] = {0, 1, 2, 1, 2};
inline constexpr int kVecDeriv[5] = {1, 0, 0, 1, 1};

// Number of axial Gauss points of an element of this order under this rule.
inline int axialPoints(int order, AxialRule rule) {
  return rule == AxialRule::Full ? order + 1 : order;
}

// A fibre whose reference section frame folds (its volume factor det[g1 g2 x0' + x1 g1' + x2 g2']
// is not positive somewhere on a section: the centreline bends there tighter than the radius, as
// a quadratic element interpolating a polyline corner inside it does, or the directors lie along
// it). Thrown by buildBeamReference for the lowest such element.
struct FoldedSectionError : std::runtime_error {
  Index fibre;    // the fibre's index
  double s1, s2;  // the element's span of reference arc length, mm
  FoldedSectionError(Index f, double a, double b)
      : std::runtime_error("beam reference: a section frame folds"), fibre(f), s1(a), s2(b) {}
};

// Fills `beams` for every element of `fibres`; integration[f] gives fibre f's rules.
// FoldedSectionError for a fibre whose reference section frame folds.
void buildBeamReference(const FibreStore& fibres, const MaterialStore& materials,
                        const std::vector<BeamIntegration>& integration, BeamStore& beams);

// D of one section: reference vectors V[5] at the point, radius R (mm), material constants,
// axial weight w (folded in). Exposed for tests.
Mat15 sectionStiffness(const Vec3 V[5], double R, double E, double nu, double fBend,
                       double fTors, const BeamIntegration& rule, double w);

}  // namespace fibra
