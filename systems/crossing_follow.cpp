#include "systems/crossing_follow.h"

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
// Gauss-Newton steps at most. Without the curvature terms it converges linearly, at a rate of
// about |d| / rho (centre distance over the centrelines' radius of curvature): 0.045 per step
// on the crimped plain weave, whose crossings then need 6-7 steps to 1e-10.
constexpr int kSteps = 20;

// Gauss-Newton on the element parameters (zI, zJ) towards the closest centreline points; false
// when the fibres are within theta_parallel of each other there (no well-posed pair), when the
// closest points leave either element (the next detection finds them; the particle weights and
// the matrix pattern are bound to these elements), or without convergence (steps in z summing
// to <= 1e-10) in kSteps steps.
bool closestInElements(const FibreStore& fs, const Eigen::VectorXd& q, Index eI, Index eJ,
                       double hI, double hJ, double sinParallel, double& zI, double& zJ) {
  for (int it = 0; it < kSteps; ++it) {
    const Section I = sectionAt(fs, q, {eI, zI}), J = sectionAt(fs, q, {eJ, zJ});
    const Vec3 tI = 0.5 * hI * I.dx0ds, tJ = 0.5 * hJ * J.dx0ds, d = I.x0 - J.x0;
    const double a11 = tI.dot(tI), a22 = tJ.dot(tJ), a12 = -tI.dot(tJ);
    if (tI.cross(tJ).norm() <= sinParallel * std::sqrt(a11 * a22)) return false;
    const double det = a11 * a22 - a12 * a12, f1 = d.dot(tI), f2 = -d.dot(tJ);
    const double dI = -(a22 * f1 - a12 * f2) / det, dJ = -(a11 * f2 - a12 * f1) / det;
    zI += dI, zJ += dJ;
    if (std::abs(zI) >= 1 - kInside || std::abs(zJ) >= 1 - kInside) return false;
    if (std::abs(dI) + std::abs(dJ) <= 1e-10) return true;
  }
  return false;
}

// Moves element e's sections; how far they moved (the larger of the two, mm).
double follow(const FibreStore& fs, const Eigen::VectorXd& q, double sinParallel,
              ContactElementStore& el, Index e) {
  const Index fI = el.fibreI[e], fJ = el.fibreJ[e];
  const FibrePoint pI = locate(fs, fI, el.sI[e]), pJ = locate(fs, fJ, el.sJ[e]);
  double zI = std::clamp(pI.z, -1 + kInside, 1 - kInside);
  double zJ = std::clamp(pJ.z, -1 + kInside, 1 - kInside);
  if (!closestInElements(fs, q, pI.element, pJ.element, elementLength(fs, fI),
                         elementLength(fs, fJ), sinParallel, zI, zJ))
    return 0;
  const Section I = sectionAt(fs, q, {pI.element, zI}), J = sectionAt(fs, q, {pJ.element, zJ});
  const Vec3 d = J.x0 - I.x0;
  double xiI[2], xiJ[2];
  if (!outlinePoint(I.g1, I.g2, fs.radius[fI], d, xiI) ||
      !outlinePoint(J.g1, J.g2, fs.radius[fJ], -d, xiJ))
    return 0;  // the centres coincide: the particles stay
  const double sI = arcLength(fs, pI.element, zI), sJ = arcLength(fs, pJ.element, zJ);
  const double shift = std::max(std::abs(sI - el.sI[e]), std::abs(sJ - el.sJ[e]));
  el.sI[e] = sI;
  el.sJ[e] = sJ;
  el.xiI1[e] = xiI[0], el.xiI2[e] = xiI[1];
  el.xiJ1[e] = xiJ[0], el.xiJ2[e] = xiJ[1];
  el.sideI[e] = particleWeights(fs, pI.element, zI, xiI[0], xiI[1]);
  el.sideJ[e] = particleWeights(fs, pJ.element, zJ, xiJ[0], xiJ[1]);
  return shift;
}

}  // namespace

void followCrossings(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
                     const ZoneStore& zones, ContactElementStore& el, ContactLoopStats& stats) {
  stats.crossingShift = 0;
  if (!p.followCrossings) return;
  const double sinParallel = std::sin(p.thetaParallel);
  stats.crossingShift = tbb::parallel_reduce(
      tbb::blocked_range<Index>(0, el.size()), 0.0,
      [&](const tbb::blocked_range<Index>& r, double shift) {
        for (Index e = r.begin(); e < r.end(); ++e)
          if (el.crossing[e] && !(zones.friction[el.zone[e]] * p.frictionFactor > 0))
            shift = std::max(shift, follow(fs, q, sinParallel, el, e));
        return shift;
      },
      [](double a, double b) { return std::max(a, b); });
}

}  // namespace fibra
