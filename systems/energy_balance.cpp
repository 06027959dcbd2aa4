#include "systems/energy_balance.h"

#include "systems/facing_particles.h"

namespace fibra {
namespace {

// Adds sign F at the particle `w` to the generalised forces f.
void addParticleForce(const ParticleWeights& w, const Vec3& F, double sign, Eigen::VectorXd& f) {
  for (int a = 0; a < w.nodes; ++a)
    for (int k = 0; k < 3; ++k)
      f.segment<3>(kNodeDofs * (w.firstNode + a) + 3 * k) += sign * w.c[a][k] * F;
}

void contactForces(const ContactState& c, EnergyForces& out) {
  const ContactElementStore& el = c.elements;
  for (Index e = 0; e < el.size() && e < c.forces.size(); ++e) {
    const Vec3 normal = c.forces.normalForce[e] * c.forces.normal[e];
    const Vec3 friction = c.forces.force[e] - normal;
    // the normal force on the particles it acted on (facing ones where it had them), friction
    // on the material particles its slip is measured between
    const ParticleWeights &I = forceParticle(el, c.forces, e, 0), &J = forceParticle(el, c.forces, e, 1);
    addParticleForce(I, normal, 1, out.normal);
    addParticleForce(J, normal, -1, out.normal);
    addParticleForce(el.sideI[e], friction, 1, out.friction);
    addParticleForce(el.sideJ[e], friction, -1, out.friction);
  }
  const ToolContactStore& tl = c.toolElements;
  for (Index i = 0; i < tl.size() && i < c.toolForces.size(); ++i) {
    const Vec3 normal = c.toolForces.normalForce[i] * c.toolForces.normal[i];
    addParticleForce(tl.side[i], normal, 1, out.tools);
    addParticleForce(tl.side[i], c.toolForces.force[i] - normal, 1, out.friction);
  }
}

}  // namespace

void energyForces(const FibreStore& fs, const ConstraintStore& constraints,
                  const LinearSystem& system, const ContactState* contact, EnergyForces& out) {
  const Index n = kNodeDofs * fs.nodes();
  for (Eigen::VectorXd* v : {&out.supports, &out.normal, &out.friction, &out.tools})
    v->setZero(n);
  out.external = system.fext.size() == n ? system.fext : Eigen::VectorXd::Zero(n);
  if (system.r.size() == n)
    for (const Index dof : constraints.dof) out.supports[dof] = system.r[dof];
  if (contact) contactForces(*contact, out);
}

void accumulateEnergy(const EnergyForces& last, const EnergyForces& now,
                      const Eigen::VectorXd& qLast, const Eigen::VectorXd& qNow,
                      const Eigen::VectorXd& stabilisationForce, double strain,
                      EnergyBalance& b) {
  const Eigen::VectorXd dq = qNow - qLast;
  const auto work = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& c) {
    return 0.5 * (a + c).dot(dq);
  };
  b.external += work(last.external, now.external);
  b.supports += work(last.supports, now.supports);
  b.contactNormal += work(last.normal, now.normal);
  b.friction += work(last.friction, now.friction);
  b.tools += work(last.tools, now.tools);
  if (stabilisationForce.size() == dq.size()) b.stabilisation -= 0.5 * stabilisationForce.dot(dq);
  b.strain = strain;
}

}  // namespace fibra
