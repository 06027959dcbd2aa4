#include "systems/normal_linearisation.h"

#include "systems/contact_geometry.h"
#include "systems/contact_normals.h"
#include "systems/facing_particles.h"
#include "systems/particle.h"

#include <unsupported/Eigen/AutoDiff>

namespace fibra {
namespace {

// Forward-mode scalar: a value and its derivatives with respect to v (24 entries).
using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
using VAD = Vec3Of<AD>;

// x as the independent variables v[first .. first + 2].
VAD seeded(const Vec3& x, int first) {
  VAD v;
  for (int k = 0; k < 3; ++k) v[k] = AD(x[k], 24, first + k);
  return v;
}

Vec3 valueOf3(const VAD& v) { return {v[0].value(), v[1].value(), v[2].value()}; }

// R_N(g) of eq. 12 (penaltyForce, systems/contact_law.h), k in N/mm, p_reg in mm.
AD normalForceOf(const AD& g, double k, double pReg) {
  if (g > 0) return AD(0.0);
  if (g >= -pReg) return k * g * g / (2 * pReg);
  return -k * g - k * pReg / 2;
}

// The facing points' motion through N (NormalJacobian::dxi): xi = R a / |a|, a = G^T o (o = -N
// on I, +N on J), so dxi/dv = (R / |a|) v (v1 g1 + v2 g2)^T do/dv, v = (-u2, u1), u = a / |a|.
void facingMotion(const Section& I, const Section& J, double RI, double RJ, const VAD& N,
                  NormalJacobian& jac) {
  const Section* sec[2] = {&I, &J};
  const double radius[2] = {RI, RJ}, side[2] = {-1, 1};
  const Vec3 n = valueOf3(N);
  for (int k = 0; k < 2; ++k) {
    const Vec3 o = side[k] * n;
    const double a1 = sec[k]->g1.dot(o), a2 = sec[k]->g2.dot(o), rho = std::hypot(a1, a2);
    const double v1 = -a2 / rho, v2 = a1 / rho;
    const Vec3 wg = v1 * sec[k]->g1 + v2 * sec[k]->g2;
    Eigen::Matrix<double, 1, 24> dO = Eigen::Matrix<double, 1, 24>::Zero();  // (G v) . do/dv
    for (int i = 0; i < 3; ++i) dO += side[k] * wg[i] * N[i].derivatives().transpose();
    jac.dxi.row(2 * k) = radius[k] / rho * v1 * dO;
    jac.dxi.row(2 * k + 1) = radius[k] / rho * v2 * dO;
  }
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
                                    double thetaCross, std::uint8_t hold, bool facing) {
  const Index fI = el.fibreI[e], fJ = el.fibreJ[e];
  const double RI = fs.radius[fI], RJ = fs.radius[fJ];
  const Section I = contactSection(fs, q, fI, el.sI[e]);
  const Section J = contactSection(fs, q, fJ, el.sJ[e]);
  const Vec3 mI = particlePosition(q, el.sideI[e]), mJ = particlePosition(q, el.sideJ[e]);
  const VAD xmI = seeded(mI, 18), xmJ = seeded(mJ, 21);
  const NormalOf<AD> n = normalOfSections<AD>(
      seeded(I.x0, 6), seeded(J.x0, 9), seeded(I.dx0ds, 12), seeded(J.dx0ds, 15), xmI, xmJ, I.g1,
      RI, RJ, thetaParallel, thetaCross, el.fallback[e],
      endRoom(fs, q, fI, el.sI[e], fJ, el.sJ[e], thetaParallel));
  const VAD& N = n.normal;
  LinearisedContact out;
  out.normal = valueOf3(N);
  // the points the normal force acts on: the outlines' extremal points along N at this state
  // (their weights fixed for the derivative: the gap's variation with them vanishes there), or
  // the material particles
  out.facing = facing && facingSide(q, el.sideI[e], RI, -out.normal, out.I) &&
               facingSide(q, el.sideJ[e], RJ, out.normal, out.J);
  const VAD xfI = seeded(out.facing ? out.I.position : mI, 0);
  const VAD xfJ = seeded(out.facing ? out.J.position : mJ, 3);
  const AD g = (xfI - xfJ).dot(N);                          // mm
  const AD R = normalForceOf(g, p.penalty, p.pReg);         // N
  const VAD fN = R * N;                                     // N
  VAD fT = VAD::Zero();
  out.law.gap = g.value();
  out.law.normalForce = R.value();
  out.law.normal = out.normal;
  if (p.mu > 0 && R.value() > 0) {
    const VAD w = xmI - xmJ + (el.gRev0[e] - el.d0[e]).cast<AD>();
    const VAD trial = w - N * N.dot(w);                    // P (g_rev,0 + d - d0), mm
    const AD t = trial.norm();
    VAD gRev = trial;
    out.law.trialRatio = t.value() / p.gMax;
    if (hold == kStatusNone ? t.value() > p.gMax : hold == kStatusSlip && t.value() > 0) {
      out.law.slip = true;
      gRev = trial * (p.gMax / t);
    }
    fT = -(p.mu / p.gMax) * R * gRev;
    out.law.gRev = valueOf3(gRev);
  }
  out.law.force = valueOf3(fN) + valueOf3(fT);
  NormalJacobian& jac = out.jacobian;
  for (int i = 0; i < 3; ++i) {
    jac.dfN.row(i) = fN[i].derivatives().transpose();
    jac.dfT.row(i) = fT[i].derivatives().transpose();
  }
  if (out.facing) facingMotion(I, J, RI, RJ, N, jac);
  out.law.stiffness = -(jac.dfN.leftCols<3>() + jac.dfT.middleCols<3>(18));
  jac.I = sectionWeights(fs, fI, el.sI[e]);
  jac.J = sectionWeights(fs, fJ, el.sJ[e]);
  return out;
}

}  // namespace fibra
