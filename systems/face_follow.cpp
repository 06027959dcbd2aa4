#include "systems/face_follow.h"

#include "systems/contact_geometry.h"
#include "systems/interpolation.h"
#include "systems/particle.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

// Element parameters stay this far inside [-1, 1]: the arc length maps back to the same element.
constexpr double kInside = 1e-9;
constexpr int kRounds = 20;

// The closest point of element e's centreline to x by Newton on g(z) = (x0(z) - x) . x0'(z)
// from z; false when it leaves the element or does not settle (|dz| <= 1e-13) in 30 steps.
bool closestInElement(const FibreStore& fs, const Eigen::VectorXd& q, Index e, const Vec3& x,
                      double& z) {
  const double dzds = 2 / elementLength(fs, fs.elementFibre[e]);
  for (int it = 0; it < 30; ++it) {
    const Section S = sectionAt(fs, q, {e, z});
    const Vec3 t = S.dx0ds / dzds;  // dx0/dz
    const double step = -(S.x0 - x).dot(t) / t.dot(t);
    z += step;
    if (std::abs(z) >= 1 - kInside) return false;
    if (std::abs(step) <= 1e-13) return true;
  }
  return false;
}

// Moves element e's face point and the other section; how far they moved (mm).
double follow(const FibreStore& fs, const Eigen::VectorXd& q, ContactElementStore& el, Index e) {
  const bool onI = el.fallback[e] & kEndFaceI;
  const Index f = onI ? el.fibreI[e] : el.fibreJ[e], o = onI ? el.fibreJ[e] : el.fibreI[e];
  const double s = onI ? el.sI[e] : el.sJ[e], so = onI ? el.sJ[e] : el.sI[e];
  const FibrePoint face = locate(fs, f, s), other = locate(fs, o, so);
  const Section S = sectionAt(fs, q, face);
  const double R = fs.radius[f];
  Eigen::Vector2d m = onI ? Eigen::Vector2d(el.xiI1[e], el.xiI2[e])
                          : Eigen::Vector2d(el.xiJ1[e], el.xiJ2[e]);
  double z = std::clamp(other.z, -1 + kInside, 1 - kInside);
  const Eigen::Vector2d m0 = m;
  for (int round = 0; round < kRounds; ++round) {
    const Section O = sectionAt(fs, q, {other.element, z});
    const Eigen::Vector2d next = discPointNearestLine(S, R, O.x0, O.dx0ds.normalized(), m);
    double zn = z;
    if (!closestInElement(fs, q, other.element, S.x0 + next(0) * S.g1 + next(1) * S.g2, zn))
      return 0;  // the next detection finds it
    const bool still = (next - m).norm() <= 1e-12 * R && std::abs(zn - z) <= 1e-12;
    m = next, z = zn;
    if (still) break;
  }
  const Vec3 x = S.x0 + m(0) * S.g1 + m(1) * S.g2;
  const Section O = sectionAt(fs, q, {other.element, z});
  const Vec3 radial = (x - O.x0) - (x - O.x0).dot(O.dx0ds.normalized()) * O.dx0ds.normalized();
  if (radial.norm() < kFaceClearance * fs.radius[o]) return 0;  // the other axis reached
  double xiO[2];
  if (!outlinePoint(O.g1, O.g2, fs.radius[o], x - O.x0, xiO)) return 0;
  const double sNew = arcLength(fs, other.element, z);
  const double shift = std::max(std::abs(sNew - so), (m - m0).norm());
  if (onI) {
    el.sJ[e] = sNew;
    el.xiI1[e] = m(0), el.xiI2[e] = m(1);
    el.xiJ1[e] = xiO[0], el.xiJ2[e] = xiO[1];
  } else {
    el.sI[e] = sNew;
    el.xiJ1[e] = m(0), el.xiJ2[e] = m(1);
    el.xiI1[e] = xiO[0], el.xiI2[e] = xiO[1];
  }
  const FibrePoint pI = onI ? face : FibrePoint{other.element, z};
  const FibrePoint pJ = onI ? FibrePoint{other.element, z} : face;
  el.sideI[e] = particleWeights(fs, pI.element, pI.z, el.xiI1[e], el.xiI2[e]);
  el.sideJ[e] = particleWeights(fs, pJ.element, pJ.z, el.xiJ1[e], el.xiJ2[e]);
  return shift;
}

}  // namespace

void followEndFaces(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
                    const ZoneStore& zones, ContactElementStore& el, ContactLoopStats& stats) {
  stats.faceShift = tbb::parallel_reduce(
      tbb::blocked_range<Index>(0, el.size()), 0.0,
      [&](const tbb::blocked_range<Index>& r, double shift) {
        for (Index e = r.begin(); e < r.end(); ++e)
          if ((el.fallback[e] & (kEndFaceI | kEndFaceJ)) && !el.forced[e] &&
              !(zones.friction[el.zone[e]] * p.frictionFactor > 0) &&
              !(el.gap[e] > zones.pMax[el.zone[e]]))
            shift = std::max(shift, follow(fs, q, el, e));
        return shift;
      },
      [](double a, double b) { return std::max(a, b); });
}

}  // namespace fibra
