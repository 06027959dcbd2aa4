// Section law: the energy of a beam section at one axial point for a material whose law is not
// Saint Venant-Kirchhoff (`law` "neo_hookean"), integrated point by point over the section.
//
// Reads  one LawSection and its SectionPoints (BeamStore), the point's generalised strains e (15).
// Adds   its energy W, sigma = dW/de (15) and D = d2W/de2 (15 x 15), exact. Pure function: the
//        beam element calls it from many threads.
//
// At section point xi the Green-Lagrange strain is E(xi) = Phi(xi) e (beam_section.h); the
// stiffness factors act on its fluctuation, E_eff = E_bar + S (E - E_bar), E_bar the section mean
// (so that bending_factor and torsion_factor mean what they mean for Saint Venant-Kirchhoff).
// With the reference metric G_ij (covariant) and G^ij, C_ij = G_ij + 2 E_eff,ij, J^2 = det C / det G:
//   W(E)           = mu/2 (G^ij C_ij - 3) - mu ln J + lambda/2 (ln J)^2   (compressible neo-Hookean)
//   S^ij = dW/dE_ij = mu G^ij + (lambda ln J - mu) C^ij,              C^ij = (C^-1)^ij
//   dS^ij/dE_kl    = lambda C^ij C^kl + (mu - lambda ln J) (C^ik C^jl + C^il C^jk)
// (Bonet and Wood, Nonlinear Continuum Mechanics for Finite Element Analysis, 2nd ed., 2008,
// eqs. 6.28 and 6.29, written on the convected basis). At E = 0 the tangent is Saint
// Venant-Kirchhoff's, lambda G^ij G^kl + mu (G^ik G^jl + G^il G^jk).
// Poisson locking (the directors make E11, E22, E12 constant over the section, so bending is
// resisted by lambda + 2 mu instead of E): enhanced transverse strains, E11, E22 and E12 each
// + alpha_a (xi1 - c1) + alpha_b (xi2 - c2) (c the section's centre), six parameters per axial
// point that minimise the section's energy at fixed e (Newton from alpha = 0 to round-off) and are
// condensed: sigma = dW/de at the minimum, D = W_ee - W_ea W_aa^-1 W_ae. Saint Venant-Kirchhoff's
// cure, a constant quadratic correction, is exact for its quadratic energy but turns the bending
// moment back near R kappa = 0.45 under this one (a thick roll-up: docs/METHOD.md).
// Beyond small strains the laws part: Saint Venant-Kirchhoff's uniaxial stress turns back below
// the stretch 1/sqrt(3) and vanishes at 0, so a beam bent to R kappa ~ 0.42 softens on its inner
// side, its moment has a maximum, and an element can fold (docs/METHOD.md "Folded elements"); W
// here grows without bound as J -> 0. A state with det C <= 0 at a section point has no energy:
// W is +inf, and the element's residual is not finite (Newton halves its step).
// Each independent component E_p (p in [11 22 33 12 13 23]) counts both E_ij and E_ji:
// dW/dE_p = S : B_p, d2W/dE_p dE_q = B_p : dS/dE : B_q, B_p the symmetric unit tensor of p.
#pragma once

#include "components/beam_store.h"

namespace fibra {

// Returns the energy (N mm) of the section law at one axial point and adds sigma (N mm) and, when
// D is not null, D (N mm); +inf where some section point has det C <= 0.
double addSectionLaw(const LawSection& section, const SectionPoint* points, const Vec15& e,
                     Vec15& sigma, Mat15* D);

// The neo-Hookean energy density (MPa) of the strain E [11 22 33 12 13 23] on a basis with
// metric gCov, gCon, with dW/dE_p (s) and d2W/dE_p dE_q (c, when not null); +inf where det C <= 0.
// Exposed for tests.
double neoHookean(const Vec6& E, const Mat3& gCov, const Mat3& gCon, double lambda, double mu,
                  Vec6& s, Eigen::Matrix<double, 6, 6>* c);

}  // namespace fibra
