// Scene loader: time tables, boundary conditions, loads, rigid tools, contact and
// stabilisation. Tables are resolved here (SceneDef holds them inline).
#include "io/json_reader.h"
#include "io/scene_sections.h"
#include "io/scene_validate.h"

#include <numbers>

namespace fibra::scene_sections {
namespace {

using namespace json_reader;

Table readTablePoints(const Json& j, const std::string& path) {
  if (!j.is_array()) fail(path, typeMismatch("a table [[t, v], ...] or a table name", j));
  Table table;
  forEachItem(j, path, [&](const Json& p, const std::string& at) {
    if (!p.is_array() || p.size() != 2) fail(at, typeMismatch("a point [t, v]", p));
    table.t.push_back(asNumber(p[0], at + "[0]"));
    table.v.push_back(asNumber(p[1], at + "[1]"));
  });
  validateTable(table, path);
  return table;
}

// A table given by name (from `tables`) or inline.
Table readTable(const Json& j, const std::string& path, const Tables& tables) {
  if (!j.is_string()) return readTablePoints(j, path);
  const std::string name = j.get<std::string>();
  if (const auto it = tables.find(name); it != tables.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& [n, t] : tables) names.push_back(n);
  const std::string close = closestKey(name, names);
  fail(path,
       "unknown table '" + shown(name) + "'" + (close.empty() ? "" : " (did you mean '" + close + "'?)"));
}

const std::vector<std::string> kMotionKeys = {"displacement", "table", "rotation"};

// Prescribed rigid motion of a boundary condition or a tool: displacement * table and a rotation
// {axis, centre, angle (rad table)}.
template <class Def>
void readMotion(const Fields& f, Def& d, const Tables& tables) {
  d.displacement = f.vec3("displacement", d.displacement);
  if (f.has("table")) {
    if (!f.has("displacement")) fail(f.path("table"), "scales \"displacement\", which is missing");
    d.displacementTable = readTable(f.at("table"), f.path("table"), tables);
  }
  if (!f.has("rotation")) return;
  const Fields r(f.at("rotation"), f.path("rotation"), {"axis", "centre", "angle"});
  d.rotates = true;
  d.axis = r.vec3("axis", d.axis);
  d.centre = r.vec3("centre", d.centre);
  d.angle = readTable(r.at("angle"), r.path("angle"), tables);
}

std::vector<std::string> withMotion(std::vector<std::string> keys) {
  keys.insert(keys.end(), kMotionKeys.begin(), kMotionKeys.end());
  return keys;
}

// DOF names of a "fix": components, or the three of a block.
void readDofs(const Json& j, const std::string& path, std::array<bool, 9>& dofs) {
  static const std::pair<const char*, std::vector<int>> kNames[] = {{"x", {X}},
                                                                    {"y", {Y}},
                                                                    {"z", {Z}},
                                                                    {"g1x", {G1X}},
                                                                    {"g1y", {G1Y}},
                                                                    {"g1z", {G1Z}},
                                                                    {"g2x", {G2X}},
                                                                    {"g2y", {G2Y}},
                                                                    {"g2z", {G2Z}},
                                                                    {"x0", {X, Y, Z}},
                                                                    {"g1", {G1X, G1Y, G1Z}},
                                                                    {"g2", {G2X, G2Y, G2Z}}};
  forEachItem(j, path, [&](const Json& item, const std::string& at) {
    const std::string name = asString(item, at);
    for (const auto& [n, components] : kNames)
      if (name == n) {
        for (int c : components) dofs[c] = true;
        return;
      }
    fail(at, "unknown DOF \"" + shown(name) +
                 "\" (expected x, y, z, g1x, g1y, g1z, g2x, g2y, g2z, x0, g1 or g2)");
  });
}

}  // namespace

Tables readTables(const Json& j, const std::string& path) {
  if (!j.is_object()) fail(path, typeMismatch("an object {\"name\": [[t, v], ...], ...}", j));
  Tables tables;
  for (const auto& item : j.items()) {
    if (item.key().empty()) fail(path, "a table needs a non-empty name");
    tables[item.key()] = readTablePoints(item.value(), join(path, item.key()));
  }
  return tables;
}

BcDef readBc(const Json& j, const std::string& path, const Tables& tables) {
  const Fields f(j, path, withMotion({"type", "group", "dofs"}));
  BcDef b;
  b.kind = f.choice<BcKind>("type",
                            {{"clamp", BcKind::Clamp}, {"pin", BcKind::Pin}, {"fix", BcKind::Fix}});
  b.group = f.string("group");
  if (b.kind == BcKind::Fix) {
    if (!f.has("dofs")) fail(f.path("dofs"), "required field missing for type \"fix\"");
    readDofs(f.at("dofs"), f.path("dofs"), b.dofs);
  } else if (f.has("dofs")) {
    fail(f.path("dofs"), "only for type \"fix\" (clamp holds all nine DOFs, pin the three of x0)");
  }
  readMotion(f, b, tables);
  return b;
}

LoadDef readLoad(const Json& j, const std::string& path, const Tables& tables) {
  const Fields f(j, path, {"type", "group", "vector", "table"});
  LoadDef l;
  l.kind = f.choice<LoadKind>("type", {{"force", LoadKind::Force},
                                       {"moment", LoadKind::Moment},
                                       {"line_force", LoadKind::LineForce}});
  l.group = f.string("group");
  l.vector = f.vec3("vector");
  if (f.has("table")) l.table = readTable(f.at("table"), f.path("table"), tables);
  return l;
}

ToolDef readTool(const Json& j, const std::string& path, const Tables& tables) {
  const std::vector<std::string> common = {"name", "type", "point", "friction", "max_penetration"};
  std::vector<std::string> all = withMotion(common);
  all.insert(all.end(), {"normal", "axis", "radius", "inside"});
  ToolDef t;
  t.kind =
      Fields(j, path, all)
          .choice<ToolKind>("type", {{"plane", ToolKind::Plane}, {"cylinder", ToolKind::Cylinder}});
  std::vector<std::string> keys = withMotion(common);
  if (t.kind == ToolKind::Plane)
    keys.push_back("normal");
  else
    keys.insert(keys.end(), {"axis", "radius", "inside"});
  const Fields f(j, path, keys, t.kind == ToolKind::Plane ? "a plane" : "a cylinder");
  t.name = f.string("name");
  t.point = f.vec3("point", t.point);
  if (t.kind == ToolKind::Plane) {
    t.direction = f.vec3("normal");
  } else {
    t.direction = f.vec3("axis");
    t.radius = f.number("radius");
    t.inside = f.boolean("inside", t.inside);
  }
  t.friction = f.number("friction", t.friction);
  t.maxPenetration = f.number("max_penetration", t.maxPenetration);
  readMotion(f, t, tables);
  return t;
}

ContactDef readContact(const Json& j, const std::string& path) {
  const Fields f(
      j, path,
      {"enabled", "proximity_distance", "test_point_spacing", "theta_cross_deg",
       "theta_parallel_deg", "self_contact", "self_contact_separation", "skin", "max_penetration",
       "regularisation", "initial_penalty", "penalty_change", "penalty_min", "penalty_max",
       "step_penetration", "friction", "max_reversible_slip",
       "friction_tangent", "max_detection_loops", "max_normal_loops", "element_placement",
       "friction_hold_after", "friction_hold_tolerance", "normal_update", "normal_acceleration",
       "follow_crossings", "facing_particles", "pairs"});
  constexpr double kRad = std::numbers::pi / 180;
  ContactDef c;
  c.enabled = f.boolean("enabled", true);  // a contact section means contact unless it says not
  c.proximityDistance = f.number("proximity_distance", c.proximityDistance);
  c.testPointSpacing = f.number("test_point_spacing", c.testPointSpacing);
  c.thetaCross = f.number("theta_cross_deg", c.thetaCross / kRad) * kRad;
  c.thetaParallel = f.number("theta_parallel_deg", c.thetaParallel / kRad) * kRad;
  c.selfContact = f.boolean("self_contact", c.selfContact);
  c.selfContactSeparation = f.number("self_contact_separation", c.selfContactSeparation);
  c.skin = f.number("skin", c.skin);
  c.maxPenetration = f.number("max_penetration", c.maxPenetration);
  c.regularisation = f.number("regularisation", c.regularisation);
  c.initialPenalty = f.number("initial_penalty", c.initialPenalty);
  c.penaltyChange = f.number("penalty_change", c.penaltyChange);
  c.penaltyMin = f.number("penalty_min", c.penaltyMin);
  c.penaltyMax = f.number("penalty_max", c.penaltyMax);
  c.stepPenetration = f.number("step_penetration", c.stepPenetration);
  c.friction = f.number("friction", c.friction);
  c.maxReversibleSlip = f.number("max_reversible_slip", c.maxReversibleSlip);
  c.frictionTangent = f.choice(
      "friction_tangent",
      {{"consistent", FrictionTangent::Consistent}, {"symmetrised", FrictionTangent::Symmetrised}},
      c.frictionTangent);
  c.maxDetectionLoops = f.integer("max_detection_loops", c.maxDetectionLoops);
  c.maxNormalLoops = f.integer("max_normal_loops", c.maxNormalLoops);
  c.elementPlacement = f.choice(
      "element_placement",
      {{"weighted", ElementPlacement::Weighted},
       {"lobatto", ElementPlacement::Lobatto},
       {"paper", ElementPlacement::Paper}},
      c.elementPlacement);
  c.frictionHoldAfter = f.integer("friction_hold_after", c.frictionHoldAfter);
  c.frictionHoldTolerance = f.number("friction_hold_tolerance", c.frictionHoldTolerance);
  c.normalUpdate = f.choice("normal_update",
                            {{"newton", NormalUpdate::Newton},
                             {"loop", NormalUpdate::Loop},
                             {"newton_frictionless", NormalUpdate::NewtonFrictionless},
                             {"auto", NormalUpdate::Auto}},
                            c.normalUpdate);
  c.normalAcceleration = f.integer("normal_acceleration", c.normalAcceleration);
  c.followCrossings = f.boolean("follow_crossings", c.followCrossings);
  c.facingParticles = f.boolean("facing_particles", c.facingParticles);
  if (f.has("pairs"))
    forEachItem(f.at("pairs"), f.path("pairs"), [&](const Json& p, const std::string& at) {
      c.pairs.push_back(readContactPair(p, at));
    });
  return c;
}

StabilisationDef readStabilisation(const Json& j, const std::string& path) {
  const Fields f(j, path, {"stiffness", "fibres"});
  StabilisationDef s;
  s.stiffness = f.number("stiffness");
  if (f.has("fibres"))
    forEachItem(f.at("fibres"), f.path("fibres"),
                [&](const Json& n, const std::string& at) { s.fibres.push_back(asString(n, at)); });
  return s;
}

SolverDef readSolver(const Json& j, const std::string& path) {
  const Fields f(j, path, {"strategy", "ordering", "krylov_tolerance", "krylov_restart",
                           "krylov_max_iterations", "refactor_above", "blr_tolerance",
                           "coarse_segments", "coarse_rotations", "forcing_max", "pattern_slack",
                           "cycle_damping"});
  SolverDef s;
  s.strategy = f.choice("strategy",
                        {{"auto", LinearStrategy::Auto}, {"direct", LinearStrategy::Direct},
                         {"umfpack", LinearStrategy::Umfpack}, {"krylov", LinearStrategy::Krylov},
                         {"krylov-lu", LinearStrategy::KrylovLu}, {"mumps", LinearStrategy::Mumps},
                         {"schwarz", LinearStrategy::Schwarz}},
                        s.strategy);
  s.ordering = f.choice("ordering",
                        {{"auto", Ordering::Auto}, {"amd", Ordering::Amd}, {"metis", Ordering::Metis}},
                        s.ordering);
  s.krylov.tolerance = f.number("krylov_tolerance", s.krylov.tolerance);
  s.krylov.restart = f.integer("krylov_restart", s.krylov.restart);
  s.krylov.maxIterations = f.integer("krylov_max_iterations", s.krylov.maxIterations);
  s.krylov.refactorAbove = f.integer("refactor_above", s.krylov.refactorAbove);
  s.krylov.blrTolerance = f.number("blr_tolerance", s.krylov.blrTolerance);
  s.krylov.coarseSegments = f.integer("coarse_segments", s.krylov.coarseSegments);
  s.krylov.coarseRotations = f.choice("coarse_rotations",
                                      {{"auto", CoarseRotations::Auto}, {"on", CoarseRotations::On},
                                       {"off", CoarseRotations::Off}},
                                      s.krylov.coarseRotations);
  s.krylov.forcingMax = f.number("forcing_max", s.krylov.forcingMax);
  s.krylov.patternSlack = f.number("pattern_slack", s.krylov.patternSlack);
  s.cycleDamping = f.boolean("cycle_damping", s.cycleDamping);
  return s;
}

}  // namespace fibra::scene_sections
