#include "engine/world.h"

#include "engine/world_state.h"
#include "systems/boundary.h"
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
const ConstraintStore& World::constraints() const { return s_->constraints; }
Eigen::VectorXd World::residual() const { return s_->system.r; }

Vec3 World::toolReaction(Index tool) const { return s_->tools.reaction[tool]; }
const ZoneStore& World::zones() const { return s_->zones; }
const ContactElementStore& World::contactElements() const { return s_->elements; }
const ContactMechanicsStore& World::contactMechanics() const { return s_->mechanics; }
const ToolContactStore& World::toolContacts() const { return s_->toolContacts; }

ContactSnapshot World::contactSnapshot() const {
  const WorldState& w = *s_;
  ContactSnapshot c;
  const auto add = [&c](const Vec3& xI, const Vec3& xJ, const Vec3& N, double g, double RN,
                        const Vec3& friction, bool slip, bool tool, Index I, Index J) {
    c.particleI.push_back(xI), c.particleJ.push_back(xJ), c.normal.push_back(N);
    c.gap.push_back(g), c.normalForce.push_back(RN), c.friction.push_back(friction);
    c.slip.push_back(slip), c.tool.push_back(tool), c.fibreI.push_back(I), c.fibreJ.push_back(J);
  };
  const ContactMechanicsStore& m = w.mechanics;
  for (Index e = 0; e < m.size(); ++e)
    add(particlePosition(w.fibres.q, m.sideI[e]), particlePosition(w.fibres.q, m.sideJ[e]),
        m.normal[e], m.gap[e], m.normalForce[e], m.force[e] - m.normalForce[e] * m.normal[e],
        sliding(m.normalForce[e], m.gRev[e], w.contact.gMax), false, w.elements.fibreI[e],
        w.elements.fibreJ[e]);
  const ToolContactStore& t = w.toolContacts;
  for (Index i = 0; i < t.size(); ++i) {
    const Vec3 x = particlePosition(
        w.fibres.q, particleWeights(w.fibres, t.element[i], t.z[i], t.xi1[i], t.xi2[i]));
    const double mu = w.tools.friction[t.tool[i]];
    const Vec3 friction = mu > 0 ? Vec3(-mu * t.normalForce[i] / w.contact.gMax * t.gRev[i])
                                 : Vec3::Zero();
    add(x, x - t.gap[i] * t.normal[i], t.normal[i], t.gap[i], t.normalForce[i], friction,
        sliding(t.normalForce[i], t.gRev[i], w.contact.gMax), true,
        w.fibres.elementFibre[t.element[i]], t.tool[i]);
  }
  return c;
}

Reaction World::reaction(Index bc) const {
  return reactionOf(s_->constraints, s_->fibres.q, s_->system.r, bc, s_->scene.output.momentPoint);
}

}  // namespace fibra
