// Beam store: the reference data of every beam element at its axial integration points.
//
// At an axial point, the Green-Lagrange strain of the section is a polynomial in the section
// coordinates (xi1, xi2) whose 15 coefficients e_k (the generalised strains, see
// systems/beam_section.h) are each c_k (v_a . v_b - V_a . V_b) for two interpolated vectors.
// Saint Venant-Kirchhoff makes the section's energy a constant quadratic form in them:
//   energy of the element = sum over its points p of 1/2 e_p^T D_p e_p   (N mm),
// so the total-Lagrangian element needs, per point, only D_p (axial weight, section
// integration, material, locking cure and stiffness factors all folded in) and the reference
// products eRef_p. A material whose law is not Saint Venant-Kirchhoff (MaterialLaw::NeoHookean)
// has instead at each point a pointwise integral over the section (systems/section_law.h), with
// its LawSection and SectionPoints; its D_p is zero. Filled once per scene by buildBeamReference;
// no logic here.
#pragma once

#include "components/fibres.h"

#include <Eigen/StdVector>
#include <array>

namespace fibra {

constexpr int kGenStrains = 15;
using Mat15 = Eigen::Matrix<double, kGenStrains, kGenStrains>;
using Vec15 = Eigen::Matrix<double, kGenStrains, 1>;

// How a fibre's elements are integrated.
enum class AxialRule { Reduced, Full };         // order or order+1 Gauss points along the axis
// Exact disc moments with the metric frozen at the centroid (exact on straight untwisted
// references only), or a polar rule with the pointwise metric (the default: converged on curved
// and twisted references, docs/METHOD.md "Section integration").
enum class SectionRule { Moments, Quadrature };
struct BeamIntegration {
  AxialRule axial = AxialRule::Reduced;
  SectionRule section = SectionRule::Quadrature;
  int rings = 3;    // Quadrature: radial points (Gauss in r^2)
  int sectors = 8;  // Quadrature: equally spaced angles
};

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix3d;

// A section integrated pointwise for a nonlinear law, at one axial point. Strain components
// in the order [E11 E22 E33 E12 E13 E23] (covariant, on the reference's convected basis).
struct LawSection {
  Eigen::Matrix<double, 6, kGenStrains> mean;  // E_bar = mean e: the section's mean strain
  Vec6 scale;     // sqrt of the stiffness factors on the fluctuation E - E_bar, -
  double lambda;  // Lame constant, MPa
  double mu;      // shear modulus, MPa
  double centre1, centre2;  // the section's centre (mean xi1, xi2 over its volume), mm
  double radius;  // R, mm
  Index first;    // its first point in BeamStore::sectionPoints
  int count;      // its number of points
};

// A point of a LawSection's polar rule.
struct SectionPoint {
  double x1, x2;  // section coordinates xi1, xi2, mm
  double w;       // weight: polar rule x det[A1 A2 A3] x axial Gauss weight, mm^2
  Mat3 gCov;      // reference metric G_ij = A_i . A_j, -
  Mat3 gCon;      // its inverse G^ij, -
};

struct BeamStore {
  // --- per colour: elements that share no node, assembled in parallel without conflicts ---
  std::array<std::vector<Index>, 2> colours;  // even / odd element index within each fibre

  // --- per element ---
  std::vector<Index> firstPoint;  // first axial integration point of the element
  std::vector<int> pointCount;    // axial integration points of the element

  // --- per axial integration point ---
  std::vector<double> z;  // element parameter in [-1, 1]
  std::vector<Mat15, Eigen::aligned_allocator<Mat15>> D;     // section stiffness, weights folded in
  std::vector<Vec15, Eigen::aligned_allocator<Vec15>> eRef;  // c_k V_a . V_b of the reference
  std::vector<Index> law;  // its LawSection in lawSections; -1: Saint Venant-Kirchhoff (D only)

  // --- per LawSection, and per point of its polar rule ---
  std::vector<LawSection, Eigen::aligned_allocator<LawSection>> lawSections;
  std::vector<SectionPoint> sectionPoints;
};

}  // namespace fibra
