#include "engine/world.h"

#include "engine/world_state.h"
#include "systems/boundary.h"

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

Reaction World::reaction(Index bc) const {
  return reactionOf(s_->constraints, s_->fibres.q, s_->system.r, bc, s_->scene.output.momentPoint);
}

}  // namespace fibra
