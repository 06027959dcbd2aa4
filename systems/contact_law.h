// Contact-friction law of one contact element (paper section 4), as a function of the relative
// position d = x^I(xi^I) - x^J(xi^J) of its two material particles (or of a fibre particle and
// a tool point). For fixed particles and a fixed normal, d is linear in the DOFs, so the law's
// derivative with respect to d is all the element needs.
//
//   gap          g = d . N                                               (eq. 11)
//   normal force R_N = 0                          g > 0
//                    = k g^2 / (2 p_reg)           -p_reg <= g <= 0      (eq. 12)
//                    = -k g - k p_reg / 2          g < -p_reg
//   friction     trial  t = g_rev,0 + P (d - d_0), P = I - N N^T          (eq. 14)
//                g_rev = t if |t| <= g_max, else g_max t / |t|            (eq. 15, 16)
//                (a status held for the Newton pass, systems/friction_status.h, takes its
//                branch whatever |t|: stick g_rev = t, slip g_rev = g_max t / |t| for t != 0)
//                force on I: -mu R_N g_rev / g_max (at most mu R_N: Coulomb in slip)
// The force on particle I is f = R_N N - mu R_N g_rev / g_max (on J: -f), so the element adds
// -f . dd/dq to the residual and -(df/dd) to the tangent in d-space:
//   df/dd = R_N' N N^T - (mu / g_max) (g_rev R_N' N^T + R_N dg_rev/dd),
//   dg_rev/dd = P (stick) or (g_max / |t|) (P - u u^T), u = t / |t| (slip).
// Only g_rev R_N' N^T (the normal force scaling the friction force) is non-symmetric; the
// symmetrised tangent drops it.
// Split particles (contactLawSplit): the gap measured by one pair of points, d_N (the facing
// particles, systems/facing_particles.h), the slip by another, d_T (the material particles).
// The normal force R_N N acts on the first pair, the friction force on the second, and the
// stiffness comes in three blocks: -d(R_N N)/dd_N = -R_N' N N^T, and of the friction force
// f_T = -mu R_N g_rev / g_max: -df_T/dd_T = (mu / g_max) R_N dg_rev/dd_T and
// -df_T/dd_N = (mu / g_max) g_rev R_N' N^T (the non-symmetric one). With d_N = d_T their sum
// is the single pair's stiffness. Pure functions; no state.
#pragma once

#include "components/contact_forces.h"
#include "components/friction_status.h"
#include "core/columns.h"
#include "components/fibres.h"

#include <Eigen/Core>

namespace fibra {

struct ContactLawParams {
  double penalty = 0;     // k, N/mm (per contact element)
  double pReg = 0;        // regularisation threshold p_reg, mm
  double mu = 0;          // friction coefficient (0: frictionless)
  double gMax = 0;        // reversible slip g_T,max, mm
};

struct ContactLawState {
  Vec3 normal = Vec3::Zero();  // N, unit, oriented from J to I
  Vec3 d0 = Vec3::Zero();      // d at the reference state of the friction increment, mm
  Vec3 gRev0 = Vec3::Zero();   // reversible slip at that state (in the plane normal to N), mm
};

struct ContactLawResult {
  double gap = 0;               // g, mm
  double normalForce = 0;       // R_N >= 0, N
  Vec3 normal = Vec3::Zero();   // N used, unit
  Vec3 gRev = Vec3::Zero();     // reversible slip now, mm
  bool slip = false;            // the slip branch was taken (|trial| > g_max unless held)
  double trialRatio = 0;        // |trial| / g_max (0 without friction or normal force)
  Vec3 force = Vec3::Zero();    // f on particle I (J gets -f), N
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();  // -df/dd, N/mm
  // contactLawSplit only (else zero): the blocks of the friction force f_T = f - R_N N, N/mm
  Eigen::Matrix3d frictionStiffness = Eigen::Matrix3d::Zero();  // -df_T/dd_T
  Eigen::Matrix3d coupling = Eigen::Matrix3d::Zero();           // -df_T/dd_N
};

// Normal force R_N(g) and dR_N/dg of eq. 12.
inline void penaltyForce(double g, double k, double pReg, double& R, double& dR) {
  if (g > 0) {
    R = dR = 0;
  } else if (g >= -pReg) {
    R = k * g * g / (2 * pReg);
    dR = k * g / pReg;
  } else {
    R = -k * g - k * pReg / 2;
    dR = -k;
  }
}

// The normal force on the gap g = d_N . N (eq. 12) and the friction force on the slip of d_T
// (eqs. 14-16): `stiffness` -d(R_N N)/dd_N, `frictionStiffness` and `coupling` the friction
// force's blocks (header). `hold`: kStatusNone (the return mapping decides), kStatusStick or
// kStatusSlip (that branch).
inline ContactLawResult contactLawSplit(const Vec3& dN, const Vec3& dT, const ContactLawState& s,
                                        const ContactLawParams& p, bool symmetrised,
                                        std::uint8_t hold = kStatusNone) {
  ContactLawResult out;
  const Vec3& N = s.normal;
  out.normal = N;
  out.gap = dN.dot(N);
  double dR;
  penaltyForce(out.gap, p.penalty, p.pReg, out.normalForce, dR);
  const double R = out.normalForce;
  out.force = R * N;
  out.stiffness = -dR * N * N.transpose();
  if (p.mu > 0 && R > 0) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - N * N.transpose();
    const Vec3 trial = s.gRev0 + P * (dT - s.d0);
    const double t = trial.norm();
    Eigen::Matrix3d dgRev = P;
    out.gRev = trial;
    out.trialRatio = t / p.gMax;
    const bool slip = hold == kStatusNone ? t > p.gMax : hold == kStatusSlip && t > 0;
    if (slip) {
      out.slip = true;
      const Vec3 u = trial / t;
      out.gRev = p.gMax * u;
      dgRev = p.gMax / t * (P - u * u.transpose());
    }
    const double c = p.mu / p.gMax;
    out.force -= c * R * out.gRev;
    out.frictionStiffness = c * R * dgRev;
    if (!symmetrised) out.coupling = c * out.gRev * dR * N.transpose();
  }
  return out;
}

// One pair of particles for both (eqs. 11-16): d = x^I - x^J, S = -df/dd.
inline ContactLawResult contactLaw(const Vec3& d, const ContactLawState& s,
                                   const ContactLawParams& p, bool symmetrised,
                                   std::uint8_t hold = kStatusNone) {
  ContactLawResult out = contactLawSplit(d, d, s, p, symmetrised, hold);
  out.stiffness += out.frictionStiffness + out.coupling;
  out.frictionStiffness.setZero();
  out.coupling.setZero();
  return out;
}

// Sizes a force store for n elements (values are overwritten by the law systems).
// The normal's Jacobians stay empty: the fibre law sizes them when it linearises the normal.
inline void resizeContactForces(ContactForceStore& f, Index n) {
  resizeColumns(f, n);
  f.normalJacobian.clear();
  for (auto* side : {&f.facingI, &f.facingJ, &f.rollingI, &f.rollingJ}) side->clear();
  f.facing.clear();
  f.frictionStiffness.clear();
  f.coupling.clear();
}

// Element e's entries of a force store.
inline void storeContactLaw(const ContactLawResult& r, Index e, ContactForceStore& f) {
  f.gap[e] = r.gap;
  f.normalForce[e] = r.normalForce;
  f.normal[e] = r.normal;
  f.force[e] = r.force;
  f.stiffness[e] = r.stiffness;
  f.gRev[e] = r.gRev;
  f.slip[e] = r.slip;
}

}  // namespace fibra
