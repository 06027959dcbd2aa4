#include "systems/element_stretch.h"

#include "systems/interpolation.h"

namespace fibra {

namespace {

// dx0/dz of element e at z in the state q.
Vec3 tangentAt(const FibreStore& fs, const Eigen::VectorXd& q, Index e, int order, double z) {
  double N[3], dN[3];
  lagrangeShape(order, z, N, dN);
  Vec3 d = Vec3::Zero();
  for (int a = 0; a <= order; ++a) d += dN[a] * x0Of(q, fs.elementFirstNode[e] + a);
  return d;
}

}  // namespace

StretchCheck smallestStretch(const FibreStore& fs, const Eigen::VectorXd& q) {
  StretchCheck c;
  for (Index e = 0; e < fs.elements(); ++e) {
    const int order = fs.order[fs.elementFibre[e]];
    const Vec3 mid = tangentAt(fs, q, e, order, 0);
    const double length = mid.norm();
    for (const double z : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
      const double lambda = length > 0 ? tangentAt(fs, q, e, order, z).dot(mid) / length /
                                             tangentAt(fs, fs.qRef, e, order, z).norm()
                                       : 0.0;
      if (c.element < 0 || lambda < c.smallest) c.smallest = lambda, c.element = e;
    }
  }
  return c;
}

}  // namespace fibra
