#include "systems/contact_sections.h"

#include "systems/contact_geometry.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace fibra {

bool nearestSectionsInPlane(const FibreStore& fs, const CentrelineStore& cl, Index I, Index J,
                            const Vec3& xInt, const Vec3& t, const SectionWindows& w, double sep,
                            double& sI, double& sJ) {
  const double h = std::min(elementLength(fs, I), elementLength(fs, J));
  double uI = sI, uJ = sJ, lambda = 0;
  for (int it = 0; it < 20; ++it) {
    const CentrelinePoint cI = centrelineAt(fs, cl, I, uI), cJ = centrelineAt(fs, cl, J, uJ);
    const Vec3 d = cI.x - cJ.x, &tI = cI.dxds, &tJ = cJ.dxds;
    const Vec3 kI = centrelineSecond(fs, cl, I, uI), kJ = centrelineSecond(fs, cl, J, uJ);
    const Eigen::Vector2d gc(0.5 * tI.dot(t), 0.5 * tJ.dot(t));  // grad c
    const Eigen::Vector2d gf(d.dot(tI), -d.dot(tJ));             // grad f
    if (it == 0) lambda = -gf.dot(gc) / gc.squaredNorm();
    Eigen::Matrix2d H;  // Hessian of the Lagrangian f + lambda c
    H << tI.dot(tI) + d.dot(kI) + lambda * 0.5 * kI.dot(t), -tI.dot(tJ),
        -tI.dot(tJ), tJ.dot(tJ) - d.dot(kJ) + lambda * 0.5 * kJ.dot(t);
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    K.topLeftCorner<2, 2>() = H;
    K.block<2, 1>(0, 2) = gc;
    K.block<1, 2>(2, 0) = gc.transpose();
    const Eigen::Vector3d r(gf(0) + lambda * gc(0), gf(1) + lambda * gc(1),
                            (0.5 * (cI.x + cJ.x) - xInt).dot(t));
    const Eigen::Vector2d z(gc(1), -gc(0));  // c's tangent in (sI, sJ)
    if (!(z.dot(H * z) > 0)) return false;    // not a minimum along the plane
    Eigen::Vector3d step = K.partialPivLu().solve(-r);
    if (!step.allFinite()) return false;
    const double size = std::max(std::abs(step(0)), std::abs(step(1)));
    if (size > 0.25 * h) step *= 0.25 * h / size;
    uI += step(0), uJ += step(1), lambda += step(2);
    if (!(uI >= w.aI && uI <= w.bI && uJ >= w.aJ && uJ <= w.bJ)) return false;
    if (I == J && !(uJ - uI >= sep)) return false;
    if (size <= 1e-10 * h) {
      sI = uI, sJ = uJ;
      return true;
    }
  }
  return false;
}

bool closestSectionsNear(const FibreStore& fs, const CentrelineStore& cl, Index I, Index J,
                         const SectionWindows& w, double thetaParallel, double sep, double& sI,
                         double& sJ, double* curvature) {
  const double h = std::min(elementLength(fs, I), elementLength(fs, J));
  const double LI = fs.length[I], LJ = fs.length[J];
  double uI = sI, uJ = sJ;
  // A coordinate held at its fibre's end (the minimum lies past it): 0 free, -1 at s = 0, +1 at L.
  int endI = 0, endJ = 0;
  for (int it = 0; it < 20; ++it) {
    const CentrelinePoint cI = centrelineAt(fs, cl, I, uI), cJ = centrelineAt(fs, cl, J, uJ);
    const Vec3 d = cI.x - cJ.x, &tI = cI.dxds, &tJ = cJ.dxds;
    const double a11 = tI.dot(tI) + d.dot(centrelineSecond(fs, cl, I, uI));
    const double a22 = tJ.dot(tJ) - d.dot(centrelineSecond(fs, cl, J, uJ));
    const double a12 = -tI.dot(tJ), det = a11 * a22 - a12 * a12;
    const double f1 = d.dot(tI), f2 = -d.dot(tJ);
    // An end holds while the distance still falls past it (its gradient points outwards).
    if (endI && !(endI * f1 < 0)) endI = 0;
    if (endJ && !(endJ * f2 < 0)) endJ = 0;
    double dI = 0, dJ = 0;
    if (endI && endJ) {
    } else if (endJ) {
      if (!(a11 > 0)) return false;  // not a minimum along I
      dI = -f1 / a11;
    } else if (endI) {
      if (!(a22 > 0)) return false;
      dJ = -f2 / a22;
    } else {
      if (!(a11 > 0 && det > 0)) return false;  // not a minimum
      dI = -(a22 * f1 - a12 * f2) / det, dJ = -(a11 * f2 - a12 * f1) / det;
    }
    uI += dI, uJ += dJ;
    // Past a fibre's end (a window bound there): held at the end; past a window bound inside
    // the fibre: no minimum here.
    if (uI < w.aI && w.aI <= 0) uI = 0, endI = -1;
    if (uI > w.bI && w.bI >= LI) uI = LI, endI = 1;
    if (uJ < w.aJ && w.aJ <= 0) uJ = 0, endJ = -1;
    if (uJ > w.bJ && w.bJ >= LJ) uJ = LJ, endJ = 1;
    if (!(uI >= w.aI && uI <= w.bI && uJ >= w.aJ && uJ <= w.bJ)) return false;
    if (I == J && !(uJ - uI >= sep)) return false;  // self-contact: apart by the separation
    if (std::abs(dI) + std::abs(dJ) <= 1e-10 * h) {
      const Vec3 vI = centrelineAt(fs, cl, I, uI).dxds.normalized();
      const Vec3 vJ = centrelineAt(fs, cl, J, uJ).dxds.normalized();
      if (vI.cross(vJ).norm() <= std::sin(thetaParallel)) return false;
      sI = uI, sJ = uJ;
      if (curvature) *curvature = 0.5 * (a11 + a22) - std::hypot(0.5 * (a11 - a22), a12);
      return true;
    }
  }
  return false;
}

}  // namespace fibra
