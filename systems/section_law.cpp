#include "systems/section_law.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace fibra {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Phi = Eigen::Matrix<double, 6, kGenStrains>;

constexpr int kComp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

// A symmetric tensor from its components [11 22 33 12 13 23].
Mat3 tensorOf(const Vec6& v) {
  Mat3 T;
  for (int p = 0; p < 6; ++p) T(kComp[p][0], kComp[p][1]) = T(kComp[p][1], kComp[p][0]) = v(p);
  return T;
}

// B_p : T for every p (off-diagonal p counts T_ij + T_ji).
Vec6 contractBasis(const Mat3& T) {
  Vec6 v;
  for (int p = 0; p < 6; ++p) {
    const int i = kComp[p][0], j = kComp[p][1];
    v(p) = i == j ? T(i, i) : T(i, j) + T(j, i);
  }
  return v;
}

// Phi(xi): E(xi) = Phi(xi) e, the strain polynomial of beam_section.h at (x1, x2).
Phi strainMap(double x1, double x2) {
  Phi P = Phi::Zero();
  P(0, 0) = P(1, 1) = P(3, 2) = 1;             // E11 E22 E12
  P(4, 3) = 1, P(4, 5) = x1, P(4, 6) = x2;     // E13
  P(5, 4) = 1, P(5, 7) = x1, P(5, 8) = x2;     // E23
  P(2, 9) = 1, P(2, 10) = x1, P(2, 11) = x2;   // E33
  P(2, 12) = x1 * x1, P(2, 13) = x1 * x2, P(2, 14) = x2 * x2;
  return P;
}

}  // namespace

double neoHookean(const Vec6& E, const Mat3& gCov, const Mat3& gCon, double lambda, double mu,
                  Vec6& s, Mat6* c) {
  const Mat3 C = gCov + 2 * tensorOf(E);
  const double ratio = C.determinant() * gCon.determinant();  // J^2
  if (!(ratio > 0)) return std::numeric_limits<double>::infinity();
  const double lnJ = 0.5 * std::log(ratio);
  const Mat3 Ci = C.inverse();
  const Mat3 S = mu * gCon + (lambda * lnJ - mu) * Ci;
  s = contractBasis(S);
  if (c) {
    // B_p : (dS/dE) : B_q = lambda (Ci:B_p)(Ci:B_q) + 2 (mu - lambda lnJ) tr(Ci B_p Ci B_q)
    // (the form of beam_section.cpp's svkForm, with C^-1 for G^-1)
    const Vec6 ci = contractBasis(Ci);
    for (int p = 0; p < 6; ++p) {
      const int i = kComp[p][0], j = kComp[p][1];
      for (int q = p; q < 6; ++q) {
        const int k = kComp[q][0], l = kComp[q][1];
        // tr(Ci B_p Ci B_q), B_p = e_i e_j^T + e_j e_i^T (halved on the diagonal)
        double t = Ci(j, k) * Ci(l, i) + Ci(j, l) * Ci(k, i) + Ci(i, k) * Ci(l, j) + Ci(i, l) * Ci(k, j);
        if (i == j) t *= 0.5;
        if (k == l) t *= 0.5;
        (*c)(p, q) = (*c)(q, p) = lambda * ci(p) * ci(q) + 2 * (mu - lambda * lnJ) * t;
      }
    }
  }
  return 0.5 * mu * ((gCon.cwiseProduct(C)).sum() - 3) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
}

namespace {

constexpr int kEnhanced = 6;         // enhanced transverse strain parameters per axial point
constexpr int kLocalIterations = 30;  // Newton iterations on them, at most

using Mat66 = Eigen::Matrix<double, 6, kEnhanced>;

// Psi(xi): the enhanced transverse strains, E11, E22, E12 each + alpha_a (xi1 - c1) + alpha_b
// (xi2 - c2), zero on the section's mean.
Mat66 enhancedMap(const LawSection& section, const SectionPoint& pt) {
  const double d1 = pt.x1 - section.centre1, d2 = pt.x2 - section.centre2;
  Mat66 P = Mat66::Zero();
  P(0, 0) = d1, P(0, 1) = d2;  // E11
  P(1, 2) = d1, P(1, 3) = d2;  // E22
  P(3, 4) = d1, P(3, 5) = d2;  // E12
  return P;
}

// Phi_eff(xi): E_eff = E_bar + S (E(xi) - E_bar) = Phi_eff e.
Phi effectiveMap(const LawSection& section, const SectionPoint& pt) {
  return section.mean + section.scale.asDiagonal() * (strainMap(pt.x1, pt.x2) - section.mean);
}

// The section's energy at (e, alpha), with g = dW/dalpha and H = d2W/dalpha2; +inf where some
// point has det C <= 0.
double enhancedEnergy(const LawSection& section, const SectionPoint* points, const Vec15& e,
                      const Vec6& alpha, Vec6& g, Mat6& H) {
  double energy = 0;
  g.setZero();
  H.setZero();
  Vec6 s;
  Mat6 c;
  for (int k = 0; k < section.count; ++k) {
    const SectionPoint& pt = points[section.first + k];
    const Mat66 psi = enhancedMap(section, pt);
    const Vec6 E = effectiveMap(section, pt) * e + psi * alpha;
    const double W = neoHookean(E, pt.gCov, pt.gCon, section.lambda, section.mu, s, &c);
    if (!std::isfinite(W)) return W;
    energy += pt.w * W;
    g.noalias() += pt.w * psi.transpose() * s;
    H.noalias() += pt.w * psi.transpose() * c * psi;
  }
  return energy;
}

}  // namespace

double addSectionLaw(const LawSection& section, const SectionPoint* points, const Vec15& e,
                     Vec15& sigma, Mat15* D) {
  // The enhanced parameters minimise the section's energy at fixed e: Newton from 0, halved
  // while a step leaves the law's domain, until the step is below round-off (alpha in 1/mm:
  // times R it is a strain).
  Vec6 alpha = Vec6::Zero(), g;
  Mat6 H;
  double energy = enhancedEnergy(section, points, e, alpha, g, H);
  for (int it = 0; it < kLocalIterations && std::isfinite(energy); ++it) {
    const Vec6 step = -H.ldlt().solve(g);
    if (!(step.cwiseAbs().maxCoeff() * section.radius > 1e-15)) break;
    double a = 1, trial;
    while (!std::isfinite(trial = enhancedEnergy(section, points, e, alpha + a * step, g, H)) &&
           a > 1e-9)
      a *= 0.5;
    if (!std::isfinite(trial)) return trial;
    alpha += a * step;
    energy = trial;
  }
  if (!std::isfinite(energy)) return energy;
  // At the minimum dW/dalpha = 0: sigma = dW/de there, and D = W_ee - W_ea W_aa^-1 W_ae.
  Vec6 s;
  Mat6 c;
  Eigen::Matrix<double, kGenStrains, kEnhanced> Dea = Eigen::Matrix<double, kGenStrains, kEnhanced>::Zero();
  Mat15 Dee = Mat15::Zero();
  for (int k = 0; k < section.count; ++k) {
    const SectionPoint& pt = points[section.first + k];
    const Mat66 psi = enhancedMap(section, pt);
    const Phi phi = effectiveMap(section, pt);
    neoHookean(phi * e + psi * alpha, pt.gCov, pt.gCon, section.lambda, section.mu, s,
               D ? &c : nullptr);
    sigma.noalias() += pt.w * phi.transpose() * s;
    if (!D) continue;
    Dee.noalias() += pt.w * phi.transpose() * c * phi;
    Dea.noalias() += pt.w * phi.transpose() * c * psi;
  }
  if (D) *D += Dee - Dea * H.ldlt().solve(Dea.transpose());
  return energy;
}

}  // namespace fibra
