#include "systems/facing_particles.h"

#include "systems/particle.h"

#include <cmath>

namespace fibra {

bool facingSide(const Eigen::VectorXd& q, const ParticleWeights& material, double R,
                const Vec3& out, FacingSide& side) {
  Vec3 x0 = Vec3::Zero(), g1 = Vec3::Zero(), g2 = Vec3::Zero();
  for (int a = 0; a < material.nodes; ++a) {
    const Index base = kNodeDofs * (material.firstNode + a);
    const double Na = material.c[a][0];
    x0 += Na * q.segment<3>(base);
    g1 += Na * q.segment<3>(base + 3);
    g2 += Na * q.segment<3>(base + 6);
  }
  const double a1 = g1.dot(out), a2 = g2.dot(out), rho = std::hypot(a1, a2);
  if (!(rho > 1e-9 * out.norm())) return false;
  const double u1 = a1 / rho, u2 = a2 / rho, roll = std::sqrt(R / rho);
  side.particle = material;
  side.rolling = material;
  for (int a = 0; a < material.nodes; ++a) {
    const double Na = material.c[a][0];
    side.particle.c[a][1] = Na * R * u1;
    side.particle.c[a][2] = Na * R * u2;
    side.rolling.c[a][0] = 0;
    side.rolling.c[a][1] = -Na * roll * u2;
    side.rolling.c[a][2] = Na * roll * u1;
  }
  side.position = x0 + R * (u1 * g1 + u2 * g2);
  return true;
}

}  // namespace fibra
