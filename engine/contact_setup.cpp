#include "engine/contact_setup.h"

#include "core/format.h"

#include "engine/contact_classes.h"

#include <algorithm>
#include <numbers>
#include <string>

namespace fibra {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr double kReachPerRadius = 1.5;
constexpr double kDefaultThetaParallel = 5 * kDegree;
constexpr double kDefaultThetaCross = 20 * kDegree;

// The given value, or `fallback` when NaN; throws for a negative one, naming `field` as the scene
// file does (docs/SCENE.md).
double orDefault(double given, double fallback, const char* field) {
  if (std::isnan(given)) return fallback;
  if (!(given >= 0) || !std::isfinite(given))
    throw SceneError(std::string("contact.") + field + ": must be a finite value >= 0");
  return given;
}

}  // namespace

ContactParams resolveContactParams(const FibreStore& fs, const ContactDef& def) {
  ContactParams p;
  const Index n = fs.fibres();
  double rMin = n > 0 ? fs.radius[0] : 0;
  for (Index f = 0; f < n; ++f) rMin = std::min(rMin, fs.radius[f]);

  const double delta = orDefault(def.proximityDistance, std::nan(""), "proximity_distance");
  p.reach.resize(n);
  for (Index f = 0; f < n; ++f)
    p.reach[f] = std::isnan(delta) ? kReachPerRadius * fs.radius[f] : delta / 2;

  p.testPointSpacing = std::nan("");
  if (!std::isnan(def.testPointSpacing)) {
    p.testPointSpacing = orDefault(def.testPointSpacing, 0, "test_point_spacing");
    if (!(p.testPointSpacing > 0)) throw SceneError("contact.test_point_spacing: must be > 0");
  }
  p.thetaParallel = orDefault(def.thetaParallel, kDefaultThetaParallel, "theta_parallel_deg");
  p.thetaCross = orDefault(def.thetaCross, kDefaultThetaCross, "theta_cross_deg");
  if (p.thetaParallel > p.thetaCross)
    throw SceneError("contact.theta_parallel_deg: must not exceed theta_cross_deg");
  if (p.thetaCross > std::numbers::pi / 2)
    throw SceneError("contact.theta_cross_deg: must not exceed 90 degrees");

  p.selfContact = def.selfContact;
  const double sep = orDefault(def.selfContactSeparation, std::nan(""), "self_contact_separation");
  p.selfSeparation.resize(n);
  for (Index f = 0; f < n; ++f) {
    const double h = fs.length[f] / fs.elementCount[f];
    const double s = std::isnan(sep) ? 2 * (p.reach[f] + p.reach[f]) : sep;
    p.selfSeparation[f] = std::max(s, h);
  }
  p.skin = orDefault(def.skin, rMin / 2, "skin");
  p.pairs = defaultContactClasses(
      n, {def.friction, std::isfinite(def.maxPenetration) ? def.maxPenetration : 0.005 * rMin,
          def.penaltyMin, def.penaltyMax});
  return p;
}

ContactParams resolveContact(const FibreStore& fs, const SceneDef& scene) {
  const ContactDef& def = scene.contact;
  ContactParams p = def.enabled ? resolveContactParams(fs, def) : ContactParams{};
  double R = fs.fibres() ? fs.radius[0] : 1;
  for (double r : fs.radius) R = std::min(R, r);
  p.fibres = def.enabled;
  p.tools = !scene.tools.empty();
  p.pMax = std::isfinite(def.maxPenetration) ? def.maxPenetration : 0.005 * R;
  p.pRegRatio = def.regularisation;
  p.mu = def.friction;
  p.gMax = std::isfinite(def.maxReversibleSlip) ? def.maxReversibleSlip : 0.005 * R;
  p.symmetrised = def.frictionTangent == FrictionTangent::Symmetrised;
  p.placement = def.elementPlacement;
  if (def.frictionHoldAfter < 0 || def.frictionHoldAfter > 255)
    throw SceneError("contact.friction_hold_after: must be in [0, 255], got " +
                     std::to_string(def.frictionHoldAfter));
  if (!(def.frictionHoldTolerance > 0 && def.frictionHoldTolerance <= 1))
    throw SceneError("contact.friction_hold_tolerance: must be in (0, 1], got " +
                     number(def.frictionHoldTolerance));
  if (def.normalAcceleration < 0 || def.normalAcceleration > kMaxNormalAcceleration)
    throw SceneError("contact.normal_acceleration: must be in [0, " +
                     std::to_string(kMaxNormalAcceleration) + "], got " +
                     std::to_string(def.normalAcceleration));
  if (!(def.stepPenetration >= kStepPenetrationMin && def.stepPenetration <= kStepPenetrationMax))
    throw SceneError("contact.step_penetration: must be in [" + number(kStepPenetrationMin) + ", " +
                     number(kStepPenetrationMax) + "], got " + number(def.stepPenetration));
  p.stepPenetration = def.stepPenetration;
  p.frictionFlips = def.frictionHoldAfter;
  p.frictionTolerance = def.frictionHoldTolerance;
  p.newtonNormals = def.normalUpdate != NormalUpdate::Loop;
  p.newtonFrictionlessOnly = def.normalUpdate == NormalUpdate::NewtonFrictionless ||
                             def.normalUpdate == NormalUpdate::Auto;
  p.escalateNormals = def.normalUpdate == NormalUpdate::Auto;
  p.followCrossings = def.followCrossings;
  p.facingParticles = def.facingParticles;
  p.toolProximity = def.proximityDistance;  // NaN: per fibre, systems/tool_detection.h
  p.initialPenalty = def.initialPenalty;
  p.penaltyChange = def.penaltyChange;
  p.penaltyMin = def.penaltyMin;
  p.penaltyMax = def.penaltyMax;
  p.maxDetectionLoops = def.maxDetectionLoops;
  p.maxNormalLoops = def.maxNormalLoops;
  p.normalMemory = def.normalAcceleration;
  p.pairs = resolveContactClasses(scene, {p.mu, p.pMax, p.penaltyMin, p.penaltyMax});
  p.mu = *std::max_element(p.pairs.mu.begin(), p.pairs.mu.end());
  return p;
}

void buildTools(const SceneDef& scene, const FibreStore& fs, const MaterialStore& materials,
                const ContactParams& params, ToolStore& tools, ToolZoneStore& zones) {
  for (const ToolDef& t : scene.tools) {
    tools.name.push_back(t.name);
    tools.kind.push_back(t.kind);
    tools.point.push_back(t.point);
    tools.direction.push_back(t.direction);
    tools.radius.push_back(t.radius);
    tools.inside.push_back(t.inside);
    tools.motion.push_back(motionOf(t));
    tools.friction.push_back(t.friction);
    tools.pMax.push_back(std::isfinite(t.maxPenetration) ? t.maxPenetration : params.pMax);
    for (Index f = 0; f < fs.fibres(); ++f) {
      const double ER = materials.youngModulus[fs.material[f]] * fs.radius[f];
      zones.penalty.push_back(std::isfinite(params.initialPenalty) ? params.initialPenalty : ER);
      zones.pMax.push_back(tools.pMax.back());
      zones.stiffness.push_back(ER);
      zones.penaltyMin.push_back(params.penaltyMin);
      zones.penaltyMax.push_back(params.penaltyMax);
    }
  }
}

}  // namespace fibra
