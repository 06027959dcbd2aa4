// Material particles of a fibre: a point (element, z) of the centreline and section
// coordinates (xi1, xi2). For a fixed particle its position
//   x = sum_a N_a(z) (x0_a + xi1 g1_a + xi2 g2_a)                                   (eq. 2)
// is linear in the element's DOFs with weights c[a][f] = N_a (1, xi1, xi2) on (x0, g1, g2), which
// is all a contact element needs to map a force on the particle to nodal forces and a 3x3
// stiffness to the DOFs. Header-only, used by the contact and tool systems.
#pragma once

#include "components/particle_weights.h"
#include "systems/interpolation.h"

namespace fibra {

inline ParticleWeights particleWeights(const FibreStore& fs, Index element, double z, double xi1,
                                       double xi2) {
  ParticleWeights w;
  w.element = element;
  w.firstNode = fs.elementFirstNode[element];
  w.nodes = fs.order[fs.elementFibre[element]] + 1;
  double N[3], dN[3];
  lagrangeShape(w.nodes - 1, z, N, dN);
  for (int a = 0; a < w.nodes; ++a) {
    w.c[a][0] = N[a];
    w.c[a][1] = N[a] * xi1;
    w.c[a][2] = N[a] * xi2;
  }
  return w;
}

inline Vec3 particlePosition(const Eigen::VectorXd& q, const ParticleWeights& w) {
  Vec3 x = Vec3::Zero();
  for (int a = 0; a < w.nodes; ++a)
    for (int f = 0; f < 3; ++f) x += w.c[a][f] * q.segment<3>(kNodeDofs * (w.firstNode + a) + 3 * f);
  return x;
}

// Section coordinates of the point of the outline |xi| = R whose position relative to the
// centre, xi1 g1 + xi2 g2, points along the projection of `dir` onto the section plane
// (paper Fig. 4): xi = R m / |m|, m = (G^T G)^-1 G^T dir with G = [g1 g2]. When `dir` is normal
// to the section (no projection), the particle is taken on g1.
inline Eigen::Vector2d outlinePoint(const Vec3& g1, const Vec3& g2, double R, const Vec3& dir) {
  Eigen::Matrix2d M;
  M << g1.dot(g1), g1.dot(g2), g1.dot(g2), g2.dot(g2);
  const Eigen::Vector2d m = M.inverse() * Eigen::Vector2d(g1.dot(dir), g2.dot(dir));
  const double n = m.norm();
  if (!(n > 1e-12 * dir.norm())) return {R, 0};
  return R * m / n;
}

}  // namespace fibra
