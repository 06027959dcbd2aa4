#include "systems/element_stretch.h"

#include "systems/interpolation.h"

namespace fibra {

StretchCheck smallestStretch(const FibreStore& fs, const Eigen::VectorXd& q) {
  StretchCheck c;
  c.smallest = INFINITY;
  for (Index e = 0; e < fs.elements(); ++e) {
    const int order = fs.order[fs.elementFibre[e]];
    for (const double z : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
      double N[3], dN[3];
      lagrangeShape(order, z, N, dN);
      Vec3 dx = Vec3::Zero(), dX = Vec3::Zero();
      for (int a = 0; a <= order; ++a) {
        dx += dN[a] * x0Of(q, fs.elementFirstNode[e] + a);
        dX += dN[a] * x0Of(fs.qRef, fs.elementFirstNode[e] + a);
      }
      // Signed: the current tangent against the reference one (a fold turns it back).
      const double lambda = dx.dot(dX) >= 0 ? dx.norm() / dX.norm() : -dx.norm() / dX.norm();
      if (lambda < c.smallest) c.smallest = lambda, c.element = e;
    }
  }
  if (c.element < 0) c.smallest = 1;
  return c;
}

}  // namespace fibra
