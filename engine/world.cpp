#include "engine/world.h"

#include "engine/world_state.h"
#include "systems/boundary.h"
#include "systems/contact_queries.h"
#include "systems/facing_particles.h"
#include "systems/particle.h"

namespace fibra {

World::World(const SceneDef& scene, const WorldDef& def) : s_(std::make_unique<WorldState>()) {
  s_->scene = scene;
  s_->def = def;
  buildWorld(*s_);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

StepReport World::step() { return advance(*s_); }
bool World::finished() const { return s_->step >= int(s_->scene.steps.size()); }
double World::time() const { return s_->time; }
int World::currentStep() const { return s_->step; }
const SceneDef& World::scene() const { return s_->scene; }
const FibreStore& World::fibres() const { return s_->fibres; }
const MaterialStore& World::materials() const { return s_->materials; }
const GroupStore& World::groups() const { return s_->groups; }
const ToolStore& World::tools() const { return s_->tools; }
const ConstraintStore& World::constraints() const { return s_->constraints; }
Eigen::VectorXd World::residual() const { return s_->system.r; }
std::string World::describe() const { return describePipeline(s_->pipeline); }

Vec3 World::toolReaction(Index tool) const {
  const ContactState& c = s_->committed;
  Vec3 r = Vec3::Zero();
  for (Index i = 0; i < c.toolElements.size(); ++i)
    if (c.toolElements.tool[i] == tool) r -= c.toolForces.force[i];
  return r;
}

const ContactState& World::contact() const { return s_->committed; }

ContactSnapshot World::contactSnapshot() const {
  const WorldState& w = *s_;
  const ContactState& s = w.committed;
  const double gMax = w.contact.gMax;
  ContactSnapshot c;
  const auto add = [&c](const Vec3& xI, const Vec3& xJ, const Vec3& N, const ContactForceStore& f,
                        Index e, double length, const Vec3& friction, bool slip, bool tool, Index I,
                        Index J) {
    c.particleI.push_back(xI), c.particleJ.push_back(xJ), c.normal.push_back(N);
    c.length.push_back(length);
    c.gap.push_back(f.gap[e]), c.normalForce.push_back(f.normalForce[e]);
    c.friction.push_back(friction), c.slip.push_back(slip), c.tool.push_back(tool);
    c.fibreI.push_back(I), c.fibreJ.push_back(J);
  };
  const ContactElementStore& el = s.elements;
  const ContactForceStore& f = s.forces;
  for (Index e = 0; e < el.size(); ++e) {
    add(particlePosition(w.fibres.q, forceParticle(el, f, e, 0)),
        particlePosition(w.fibres.q, forceParticle(el, f, e, 1)),
        el.normal[e], f, e, el.length[e], f.force[e] - f.normalForce[e] * el.normal[e],
        sliding(f.normalForce[e], f.gRev[e], gMax), false, el.fibreI[e], el.fibreJ[e]);
    c.zone.push_back(el.zone[e]);
    c.refined.push_back(s.zones.refined[el.zone[e]]);
  }
  const ToolContactStore& t = s.toolElements;
  const ContactForceStore& tf = s.toolForces;
  for (Index i = 0; i < t.size(); ++i) {
    const Vec3 x = particlePosition(w.fibres.q, t.side[i]);
    const double mu = w.tools.friction[t.tool[i]];
    const Vec3 friction = mu > 0 ? Vec3(-mu * tf.normalForce[i] / gMax * tf.gRev[i]) : Vec3::Zero();
    add(x, x - tf.gap[i] * t.normal[i], t.normal[i], tf, i, t.length[i], friction,
        sliding(tf.normalForce[i], tf.gRev[i], gMax), true, w.fibres.elementFibre[t.element[i]],
        t.tool[i]);
    c.zone.push_back(-1);
    c.refined.push_back(0);
  }
  return c;
}

Reaction World::reaction(Index bc) const {
  return reactionOf(s_->constraints, s_->fibres.q, s_->system.r, bc, s_->scene.output.momentPoint);
}

}  // namespace fibra
