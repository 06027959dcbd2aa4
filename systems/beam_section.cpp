#include "systems/beam_section.h"

#include "systems/interpolation.h"
#include "systems/section_law.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fibra {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Phi = Eigen::Matrix<double, 6, kGenStrains>;  // E components [11 22 33 12 13 23] from e

constexpr int kMonomials = 6;  // 1, xi1, xi2, xi1^2, xi1 xi2, xi2^2
constexpr int kPow[kMonomials][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
constexpr int kComp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

// Phi_m: the coefficient of monomial m in E(xi) = sum_m phi_m(xi) Phi_m e.
std::array<Phi, kMonomials> monomialMaps() {
  std::array<Phi, kMonomials> P;
  for (auto& p : P) p.setZero();
  P[0](0, 0) = P[0](1, 1) = P[0](3, 2) = P[0](4, 3) = P[0](5, 4) = P[0](2, 9) = 1;
  P[1](4, 5) = P[1](5, 7) = P[1](2, 10) = 1;
  P[2](4, 6) = P[2](5, 8) = P[2](2, 11) = 1;
  P[3](2, 12) = 1;
  P[4](2, 13) = 1;
  P[5](2, 14) = 1;
  return P;
}

double monomial(int m, double x1, double x2) {
  return std::pow(x1, kPow[m][0]) * std::pow(x2, kPow[m][1]);
}

// int over the disc of radius R of xi1^a xi2^b dA.
double discMoment(int a, int b, double R) {
  if (a % 2 || b % 2) return 0;
  return 2 * std::pow(R, a + b + 2) / (a + b + 2) * std::tgamma(0.5 * (a + 1)) *
         std::tgamma(0.5 * (b + 1)) / std::tgamma(0.5 * (a + b + 2));
}

// Symmetric unit tensor of component p.
Eigen::Matrix3d basisTensor(int p) {
  Eigen::Matrix3d B = Eigen::Matrix3d::Zero();
  B(kComp[p][0], kComp[p][1]) = B(kComp[p][1], kComp[p][0]) = 1;
  return B;
}

// A section point whose frame has no positive volume (buildBeamReference reports the element).
struct FoldedFrame {};

// The metric at a section point: contravariant components A^ij and volume factor det.
struct Metric {
  Eigen::Matrix3d con;
  double det;
};

Metric metricAt(const Vec3 V[5], double x1, double x2) {
  Eigen::Matrix3d A;
  A.col(0) = V[1];
  A.col(1) = V[2];
  A.col(2) = V[0] + x1 * V[3] + x2 * V[4];
  const double det = A.determinant();
  if (!(det > 0)) throw FoldedFrame{};
  return {(A.transpose() * A).inverse(), det};
}

// SVK quadratic form on [E11 E22 E33 E12 E13 E23]: W = 1/2 E^T M E.
Mat6 svkForm(const Eigen::Matrix3d& G, double lambda, double mu) {
  Mat6 M;
  for (int p = 0; p < 6; ++p) {
    const Eigen::Matrix3d Bp = basisTensor(p);
    for (int q = 0; q < 6; ++q) {
      const Eigen::Matrix3d Bq = basisTensor(q);
      M(p, q) = lambda * (G.cwiseProduct(Bp)).sum() * (G.cwiseProduct(Bq)).sum() +
                2 * mu * (G * Bp * G * Bq).trace();
    }
  }
  return M;
}

// n: eps_n = n^T E, the physical normal strain along A^3: E_ij A^i3 A^j3 / A^33.
Vec6 axialStrainRow(const Eigen::Matrix3d& G) {
  const Vec3 a = G.col(2);
  Vec6 n;
  for (int p = 0; p < 6; ++p) n(p) = (basisTensor(p).cwiseProduct(a * a.transpose())).sum() / G(2, 2);
  return n;
}

struct Constants {
  double lambda, mu, delta, fBend;
  Vec6 scale;  // sqrt of the stiffness factors on the fluctuation
};

Constants constantsOf(double E, double nu, double fBend, double fTors) {
  Constants k;
  k.lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  k.mu = E / (2 * (1 + nu));
  k.delta = k.lambda + 2 * k.mu - E;
  k.fBend = fBend;
  k.scale << 1, 1, std::sqrt(fBend), 1, std::sqrt(fTors), std::sqrt(fTors);
  return k;
}

// Contribution of one section point of weight wdet: effective strain map
// Phi_hat = mean + S fluct, minus the Poisson-locking correction on the fluctuation.
void addPoint(Mat15& D, const Phi& mean, const Phi& phi, const Metric& g, const Constants& k,
              double wdet) {
  const Phi fluct = phi - mean;
  const Phi eff = mean + k.scale.asDiagonal() * fluct;
  const Mat6 M = svkForm(g.con, k.lambda, k.mu);
  const Eigen::Matrix<double, 1, kGenStrains> axial = axialStrainRow(g.con).transpose() * fluct;
  D.noalias() += wdet * (eff.transpose() * M * eff - k.delta * k.fBend * axial.transpose() * axial);
}

Mat15 momentsStiffness(const Vec3 V[5], double R, const Constants& k) {
  static const auto P = monomialMaps();
  const Metric g = metricAt(V, 0, 0);
  const double area = discMoment(0, 0, R);
  Phi mean = Phi::Zero();
  for (int m = 0; m < kMonomials; ++m) mean += discMoment(kPow[m][0], kPow[m][1], R) / area * P[m];
  // Phi(xi) - mean is polynomial with coefficients fl[m]; integrate products of monomials.
  std::array<Phi, kMonomials> fl = P;
  fl[0] -= mean;
  const Mat6 M = svkForm(g.con, k.lambda, k.mu);
  const Vec6 n = axialStrainRow(g.con);
  Mat15 D = area * mean.transpose() * M * mean;  // cross terms vanish: int fluct dA = 0
  for (int m = 0; m < kMonomials; ++m) {
    for (int l = 0; l < kMonomials; ++l) {
      const double I = discMoment(kPow[m][0] + kPow[l][0], kPow[m][1] + kPow[l][1], R);
      if (I == 0) continue;
      const Phi sm = k.scale.asDiagonal() * fl[m], sl = k.scale.asDiagonal() * fl[l];
      D += I * (sm.transpose() * M * sl -
                k.delta * k.fBend * (n.transpose() * fl[m]).transpose() * (n.transpose() * fl[l]));
    }
  }
  return g.det * D;
}

// The polar rule: u = (r/R)^2 Gauss-Legendre on [0, 1] (r dr = R^2/2 du), equal angles; the
// points with their strain maps, metrics and weights, and the section's mean strain map.
struct Point {
  Phi phi;
  Metric g;
  double w;
  double x1, x2;
};
struct PolarRule {
  std::vector<Point> pts;
  Phi mean;
};

PolarRule polarRule(const Vec3 V[5], double R, int rings, int sectors) {
  static const auto P = monomialMaps();
  double zu[4], wu[4];
  gaussLegendre(rings, zu, wu);
  PolarRule rule;
  rule.mean.setZero();
  double volume = 0;
  for (int i = 0; i < rings; ++i) {
    const double r = R * std::sqrt(0.5 * (zu[i] + 1));
    const double wr = 0.5 * wu[i] * 0.5 * R * R * 2 * std::numbers::pi / sectors;
    for (int j = 0; j < sectors; ++j) {
      const double t = 2 * std::numbers::pi * (j + 0.5) / sectors;
      const double x1 = r * std::cos(t), x2 = r * std::sin(t);
      Phi phi = Phi::Zero();
      for (int m = 0; m < kMonomials; ++m) phi += monomial(m, x1, x2) * P[m];
      const Metric g = metricAt(V, x1, x2);
      rule.mean += wr * g.det * phi;
      volume += wr * g.det;
      rule.pts.push_back({phi, g, wr, x1, x2});
    }
  }
  rule.mean /= volume;
  return rule;
}

Mat15 quadratureStiffness(const Vec3 V[5], double R, const Constants& k, int rings, int sectors) {
  const PolarRule rule = polarRule(V, R, rings, sectors);
  Mat15 D = Mat15::Zero();
  for (const Point& p : rule.pts) addPoint(D, rule.mean, p.phi, p.g, k, p.w * p.g.det);
  return D;
}

// A neo-Hookean section (systems/section_law.h): the points of the polar rule go to `points`
// (from section.first on), their weights with the axial weight w folded in. Poisson locking is
// cured there by enhanced transverse strains, so no constant part is left: D_p is zero.
void lawSection(const Vec3 V[5], double R, const Constants& k, const BeamIntegration& integration,
                double w, LawSection& section, SectionPoint* points) {
  const PolarRule rule = polarRule(V, R, integration.rings, integration.sectors);
  section.mean = rule.mean;
  section.scale = k.scale;
  section.lambda = k.lambda;
  section.mu = k.mu;
  section.radius = R;
  section.count = int(rule.pts.size());
  double volume = 0, c1 = 0, c2 = 0;
  for (int i = 0; i < section.count; ++i) {
    const Point& p = rule.pts[i];
    points[i] = {p.x1, p.x2, w * p.w * p.g.det, p.g.con.inverse(), p.g.con};
    volume += points[i].w, c1 += points[i].w * p.x1, c2 += points[i].w * p.x2;
  }
  section.centre1 = c1 / volume;
  section.centre2 = c2 / volume;
}

}  // namespace

Mat15 sectionStiffness(const Vec3 V[5], double R, double E, double nu, double fBend,
                       double fTors, const BeamIntegration& rule, double w) {
  const Constants k = constantsOf(E, nu, fBend, fTors);
  if (rule.section == SectionRule::Moments) return w * momentsStiffness(V, R, k);
  return w * quadratureStiffness(V, R, k, rule.rings, rule.sectors);
}

namespace {

// Where each element's law sections go: for a material that is not Saint Venant-Kirchhoff,
// one LawSection per axial point and its rule's points, numbered in element order (so the stores
// do not depend on the thread count).
void placeLawSections(const FibreStore& fs, const MaterialStore& mats,
                      const std::vector<BeamIntegration>& integration, BeamStore& beams) {
  beams.law.assign(beams.z.size(), -1);
  Index sections = 0, points = 0;
  std::vector<Index> firstPoint;
  for (Index e = 0; e < fs.elements(); ++e) {
    const Index f = fs.elementFibre[e];
    if (mats.law[fs.material[f]] == MaterialLaw::SaintVenantKirchhoff) continue;
    for (int p = 0; p < beams.pointCount[e]; ++p) {
      beams.law[beams.firstPoint[e] + p] = sections++;
      firstPoint.push_back(points);
      points += integration[f].rings * integration[f].sectors;
    }
  }
  beams.lawSections.assign(sections, LawSection{});
  for (Index i = 0; i < sections; ++i) beams.lawSections[i].first = firstPoint[i];
  beams.sectionPoints.assign(points, SectionPoint{});
}

// Element e's reference data: per axial point its coordinate, section stiffness (or law
// section) and reference strains.
void elementReference(const FibreStore& fs, const MaterialStore& mats,
                      const std::vector<BeamIntegration>& integration, Index e, BeamStore& beams) {
  const Index f = fs.elementFibre[e];
  const Index mat = fs.material[f];
  const int order = fs.order[f], np = beams.pointCount[e];
  const Constants k = constantsOf(mats.youngModulus[mat], mats.poissonRatio[mat],
                                  mats.bendingFactor[mat], mats.torsionFactor[mat]);
  double zg[4], wg[4], N[3], dN[3];
  gaussLegendre(np, zg, wg);
  for (int p = 0; p < np; ++p) {
    lagrangeShape(order, zg[p], N, dN);
    Vec3 V[5];
    for (auto& v : V) v.setZero();
    for (int a = 0; a <= order; ++a) {
      const Index n = fs.elementFirstNode[e] + a;
      V[0] += dN[a] * x0Of(fs.qRef, n);
      V[1] += N[a] * g1Of(fs.qRef, n);
      V[2] += N[a] * g2Of(fs.qRef, n);
      V[3] += dN[a] * g1Of(fs.qRef, n);
      V[4] += dN[a] * g2Of(fs.qRef, n);
    }
    const Index i = beams.firstPoint[e] + p;
    beams.z[i] = zg[p];
    if (const Index l = beams.law[i]; l >= 0) {
      LawSection& section = beams.lawSections[l];
      lawSection(V, fs.radius[f], k, integration[f], wg[p], section,
                 &beams.sectionPoints[section.first]);
      beams.D[i].setZero();
    } else {
      beams.D[i] = sectionStiffness(V, fs.radius[f], mats.youngModulus[mat],
                                    mats.poissonRatio[mat], mats.bendingFactor[mat],
                                    mats.torsionFactor[mat], integration[f], wg[p]);
    }
    for (int j = 0; j < kGenStrains; ++j) {
      const StrainPair& sp = kStrainPairs[j];
      beams.eRef[i](j) = sp.c * V[sp.a].dot(V[sp.b]);
    }
  }
}

}  // namespace

void buildBeamReference(const FibreStore& fs, const MaterialStore& mats,
                        const std::vector<BeamIntegration>& integration, BeamStore& beams) {
  const Index ne = fs.elements();
  beams.firstPoint.resize(ne);
  beams.pointCount.resize(ne);
  Index total = 0;
  for (auto& c : beams.colours) c.clear();
  for (Index e = 0; e < ne; ++e) {
    const Index f = fs.elementFibre[e];
    beams.colours[(e - fs.firstElement[f]) % 2].push_back(e);
    beams.firstPoint[e] = total;
    beams.pointCount[e] = axialPoints(fs.order[f], integration[f].axial);
    total += beams.pointCount[e];
  }
  beams.z.resize(total);
  beams.D.resize(total);
  beams.eRef.resize(total);
  placeLawSections(fs, mats, integration, beams);
  std::vector<char> folded(std::size_t(ne), 0);
  tbb::parallel_for(Index(0), ne, [&](Index e) {
    try {
      elementReference(fs, mats, integration, e, beams);
    } catch (const FoldedFrame&) {
      folded[std::size_t(e)] = 1;
    }
  });
  const auto first = std::find(folded.begin(), folded.end(), 1);
  if (first == folded.end()) return;
  const Index e = Index(first - folded.begin()), f = fs.elementFibre[e];
  const double h = fs.length[f] / double(fs.elementCount[f]);
  const double k = double(e - fs.firstElement[f]);
  throw FoldedSectionError(f, k * h, (k + 1) * h);
}

}  // namespace fibra
