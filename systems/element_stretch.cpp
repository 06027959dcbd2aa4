#include "systems/element_stretch.h"

#include "systems/interpolation.h"

#include <Eigen/Geometry>

namespace fibra {

namespace {

// The frame (dx0/dz, g1, g2) of element e at z in the state q.
struct Frame {
  Vec3 tangent, g1, g2;
};

Frame frameAt(const FibreStore& fs, const Eigen::VectorXd& q, Index e, int order, double z) {
  double N[3], dN[3];
  lagrangeShape(order, z, N, dN);
  Frame f{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (int a = 0; a <= order; ++a) {
    const Index n = fs.elementFirstNode[e] + a;
    f.tangent += dN[a] * x0Of(q, n);
    f.g1 += N[a] * g1Of(q, n);
    f.g2 += N[a] * g2Of(q, n);
  }
  return f;
}

double volume(const Frame& f) { return f.tangent.dot(f.g1.cross(f.g2)); }

}  // namespace

StretchCheck smallestStretch(const FibreStore& fs, const Eigen::VectorXd& q) {
  StretchCheck c;
  const auto lower = [&c](double value, Index e, bool isVolume) {
    if (c.element < 0 || value < c.smallest) c.smallest = value, c.element = e, c.volume = isVolume;
  };
  for (Index e = 0; e < fs.elements(); ++e) {
    const int order = fs.order[fs.elementFibre[e]];
    const Vec3 mid = frameAt(fs, q, e, order, 0).tangent;
    const double length = mid.norm();
    for (const double z : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
      const Frame now = frameAt(fs, q, e, order, z), ref = frameAt(fs, fs.qRef, e, order, z);
      lower(length > 0 ? now.tangent.dot(mid) / length / ref.tangent.norm() : 0.0, e, false);
      lower(volume(now) / volume(ref), e, true);
    }
  }
  return c;
}

}  // namespace fibra
