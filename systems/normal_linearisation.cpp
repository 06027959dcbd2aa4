#include "systems/normal_linearisation.h"

#include "systems/contact_geometry.h"
#include "systems/contact_normals.h"
#include "systems/particle.h"

#include <unsupported/Eigen/AutoDiff>

namespace fibra {
namespace {

// Forward-mode scalar: a value and its derivatives with respect to v (18 entries).
using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 18, 1>>;
using VAD = Vec3Of<AD>;

// x as the independent variables v[first .. first + 2].
VAD seeded(const Vec3& x, int first) {
  VAD v;
  for (int k = 0; k < 3; ++k) v[k] = AD(x[k], 18, first + k);
  return v;
}

Vec3 valueOf3(const VAD& v) { return {v[0].value(), v[1].value(), v[2].value()}; }

// R_N(g) of eq. 12 (penaltyForce, systems/contact_law.h), k in N/mm, p_reg in mm.
AD normalForceOf(const AD& g, double k, double pReg) {
  if (g > 0) return AD(0.0);
  if (g >= -pReg) return k * g * g / (2 * pReg);
  return -k * g - k * pReg / 2;
}

}  // namespace

SectionWeights sectionWeights(const FibreStore& fs, Index f, double s) {
  SectionWeights w;
  const double dzds = 2 * fs.elementCount[f] / fs.length[f];
  const int order = fs.order[f];
  const auto add = [&](Index element, double z, double centreScale, double tangentScale) {
    double N[3], dN[3];
    lagrangeShape(order, z, N, dN);
    for (int a = 0; a <= order; ++a) {
      const Index node = fs.elementFirstNode[element] + a;
      int i = 0;
      while (i < w.count && w.node[i] != node) ++i;
      if (i == w.count) w.node[w.count++] = node;
      w.centre[i] += centreScale * N[a];
      w.tangent[i] += tangentScale * dN[a] * dzds;
    }
  };
  const Index node = interiorNodeAt(fs, f, s);
  if (node < 0) {
    const FibrePoint p = locate(fs, f, s);
    add(p.element, p.z, 1, 1);
  } else {  // x0 from the element starting there, dx0/ds the mean of both elements'
    const Index e = fs.firstElement[f] + node;
    add(e, -1.0, 1, 0.5);
    add(e - 1, 1.0, 0, 0.5);
  }
  return w;
}

LinearisedContact linearisedContact(const FibreStore& fs, const Eigen::VectorXd& q,
                                    const ContactElementStore& el, Index e,
                                    const ContactLawParams& p, double thetaParallel,
                                    double thetaCross) {
  const Index fI = el.fibreI[e], fJ = el.fibreJ[e];
  const Section I = contactSection(fs, q, fI, el.sI[e]);
  const Section J = contactSection(fs, q, fJ, el.sJ[e]);
  const VAD xI = seeded(particlePosition(q, el.sideI[e]), 0);
  const VAD xJ = seeded(particlePosition(q, el.sideJ[e]), 3);
  const NormalOf<AD> n = normalOfSections<AD>(
      seeded(I.x0, 6), seeded(J.x0, 9), seeded(I.dx0ds, 12), seeded(J.dx0ds, 15), xI, xJ, I.g1,
      fs.radius[fI], fs.radius[fJ], thetaParallel, thetaCross, el.fallback[e],
      endRoom(fs, fI, el.sI[e], fJ, el.sJ[e]));
  const VAD& N = n.normal;
  const VAD d = xI - xJ;
  const AD g = d.dot(N);                                    // mm
  const AD R = normalForceOf(g, p.penalty, p.pReg);         // N
  VAD f = R * N;                                            // N
  LinearisedContact out;
  out.law.gap = g.value();
  out.law.normalForce = R.value();
  out.law.normal = valueOf3(N);
  if (p.mu > 0 && R.value() > 0) {
    const VAD w = d + (el.gRev0[e] - el.d0[e]).cast<AD>();
    const VAD trial = w - N * N.dot(w);                    // P (g_rev,0 + d - d0), mm
    const AD t = trial.norm();
    VAD gRev = trial;
    if (t > p.gMax) {
      out.law.slip = true;
      gRev = trial * (p.gMax / t);
    }
    f -= (p.mu / p.gMax) * R * gRev;
    out.law.gRev = valueOf3(gRev);
  }
  out.law.force = valueOf3(f);
  for (int i = 0; i < 3; ++i) out.jacobian.dfdv.row(i) = f[i].derivatives().transpose();
  out.law.stiffness = -out.jacobian.dfdv.leftCols<3>();
  out.jacobian.I = sectionWeights(fs, fI, el.sI[e]);
  out.jacobian.J = sectionWeights(fs, fJ, el.sJ[e]);
  out.normal = valueOf3(N);
  return out;
}

}  // namespace fibra
