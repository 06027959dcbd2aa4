// Scene validation: ranges, names and cross-references of a whole SceneDef. Field paths use the
// scene file's names (docs/SCENE.md), so a message reads the same for a file and for a SceneDef
// built in code. Code-only representations are reported in file terms: contact angles in
// degrees, a tool's direction as its "normal" or "axis".
#include "io/scene_validate.h"

#include "engine/fibre_builder.h"
#include "engine/group_order.h"
#include "io/json_reader.h"
#include "io/validate_checks.h"

#include <sys/resource.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

namespace fibra {
namespace {

using namespace validate_checks;

void checkName(const std::string& name, const std::string& path) {
  if (name.empty()) fail(path, "must not be empty");
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      fail(path, "'" + json_reader::shown(name) + "' contains '" + std::string(1, c) +
                     "'; names use letters, digits, '_', '-' and '.'");
}

using Names = std::map<std::string, size_t>;

// Valid, unique names of one list -> index.
template <class Def>
Names uniqueNames(const std::vector<Def>& defs, const std::string& list) {
  Names names;
  for (size_t i = 0; i < defs.size(); ++i) {
    checkName(defs[i].name, at(list, i) + ".name");
    if (auto [it, fresh] = names.emplace(defs[i].name, i); !fresh)
      fail(at(list, i) + ".name",
           "duplicate name '" + defs[i].name + "' (also " + at(list, it->second) + ")");
  }
  return names;
}

// Index of `name` in `names`, else an error suggesting the closest.
size_t resolve(const Names& names, const std::string& name, const char* what,
               const std::string& path) {
  if (const auto it = names.find(name); it != names.end()) return it->second;
  std::vector<std::string> known;
  for (const auto& [n, i] : names) known.push_back(n);
  const std::string close = json_reader::closestKey(name, known);
  std::string hint;
  if (!close.empty()) {
    hint = " (did you mean '" + close + "'?)";
  } else if (!known.empty() && known.size() <= 8) {
    for (const std::string& k : known) hint += (hint.empty() ? " (known: " : ", ") + k;
    hint += ")";
  }
  fail(path, std::string("unknown ") + what + " '" + json_reader::shown(name) + "'" + hint);
}

int nodeCount(const FibreDef& f) { return f.order * f.elements + 1; }

// --- materials, fibres, geometry ---

Names validateMaterials(const SceneDef& s) {
  const Names names = uniqueNames(s.materials, "materials");
  for (size_t i = 0; i < s.materials.size(); ++i) {
    const MaterialDef& m = s.materials[i];
    const std::string p = at("materials", i);
    positive(m.youngModulus, p + ".young_modulus");
    if (!(m.poissonRatio > -1 && m.poissonRatio < 0.5))
      fail(p + ".poisson_ratio", "must be in (-1, 0.5), got " + num(m.poissonRatio));
    nonNegative(m.bendingFactor, p + ".bending_factor");
    nonNegative(m.torsionFactor, p + ".torsion_factor");
  }
  return names;
}

void validatePoints(const GeometryDef& g, const std::string& p) {
  const size_t n = g.points.size();
  if (g.kind == GeometryKind::Line && n != 2)
    fail(p + ".points", "a line has 2 points (start and end), got " + std::to_string(n));
  if (g.kind == GeometryKind::Polyline && n < 2)
    fail(p + ".points", "a polyline has at least 2 points, got " + std::to_string(n));
  for (size_t k = 0; k < n; ++k) {
    withinScene(g.points[k], at(p + ".points", k));
    if (k > 0 && !((g.points[k] - g.points[k - 1]).norm() > 0))
      fail(at(p + ".points", k), "repeats the previous point");
  }
  if (g.director.array().isNaN().all()) return;  // absent: chosen by the fibre builder
  nonZero(g.director, p + ".director");
  const Vec3 t = (g.points[1] - g.points[0]).normalized();
  if (g.director.normalized().cross(t).norm() < 1e-8)
    fail(p + ".director", "is parallel to the fibre's first segment");
}

void validateGeometry(const GeometryDef& g, const std::string& p) {
  if (g.kind != GeometryKind::Helix) return validatePoints(g, p);
  withinScene(g.origin, p + ".origin");
  nonZero(g.axis, p + ".axis");
  positive(g.helixRadius, p + ".radius");
  withinScene(g.helixRadius, p + ".radius");
  withinScene(g.pitch, p + ".pitch");
  finite(g.turns, p + ".turns");
  if (g.turns == 0) fail(p + ".turns", "must not be 0");
  finite(g.phase, p + ".phase");
}

// A scene has at most this many beam elements (the generators' limit too, io/generator_fields.h;
// the paper's largest scene has 19 200).
constexpr double kMaxElements = 1e6;
// What building a scene takes per beam element, measured (about 19 kB with its assembly and
// contact structures), rounded up.
constexpr double kBytesPerElement = 24e3;

// The memory this process may use: its address-space limit or the machine's memory.
double memoryAvailable() {
  double bytes = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    bytes = std::min(bytes, double(limit.rlim_cur));
  return bytes;
}

// The elements of the fibres up to `i` (whose `elements` is named) within the limits on size and
// memory, checked before anything is allocated.
void checkElementTotal(double total, size_t i) {
  const std::string p = at("fibres", i) + ".elements";
  if (total > kMaxElements)
    fail(p, "brings the scene to " + num(total) + " beam elements, more than fibra takes (" +
                num(kMaxElements) + ")");
  const double need = total * kBytesPerElement, have = memoryAvailable();
  if (need > have)
    fail(p, "brings the scene to " + num(total) + " beam elements, which need about " +
                num(std::ceil(need / 1e8) / 10) + " GB, more than the " +
                num(std::floor(have / 1e8) / 10) + " GB this process may use");
}

Names validateFibres(const SceneDef& s, const Names& materials) {
  const Names names = uniqueNames(s.fibres, "fibres");
  double elements = 0;
  for (size_t i = 0; i < s.fibres.size(); ++i) {
    const FibreDef& f = s.fibres[i];
    const std::string p = at("fibres", i);
    const MaterialDef& m = s.materials[resolve(materials, f.material, "material", p + ".material")];
    if (m.law != MaterialLaw::SaintVenantKirchhoff && f.integration.section == SectionRule::Moments)
      fail(p + ".integration.section",
           "must be \"quadrature\" (the default): material '" + m.name +
               "' has law \"neo_hookean\", whose energy is integrated point by point over the section");
    positive(f.radius, p + ".radius");
    withinScene(f.radius, p + ".radius");
    atLeast(f.elements, 1, p + ".elements");
    checkElementTotal(elements += f.elements, i);
    if (f.order != 1 && f.order != 2)
      fail(p + ".order", "must be 1 or 2, got " + std::to_string(f.order));
    validateGeometry(f.geometry, p + ".geometry");
    if (f.integration.section == SectionRule::Quadrature) {
      const int rings = f.integration.rings;
      if (rings < 1 || rings > 4)
        fail(p + ".integration.rings", "must be 1 to 4, got " + std::to_string(rings));
      inRange(f.integration.sectors, 3, 360, p + ".integration.sectors");
    }
  }
  return names;
}

// --- groups ---

// A group's nodes as (fibre, node within the fibre) pairs, each once.
struct NodeSet {
  std::vector<std::pair<size_t, int>> nodes;
};
using Groups = std::map<std::string, NodeSet>;

NodeSet nodesOfFibre(size_t fibre, const std::vector<int>& nodes) {
  NodeSet set;
  for (int n : nodes) set.nodes.emplace_back(fibre, n);
  return set;
}

// The nodes of one fibre's group ("fibre" and "nodes").
NodeSet fibreGroup(const SceneDef& s, const GroupDef& g, const Names& fibres,
                   const std::string& p) {
  const size_t f = resolve(fibres, g.fibre, "fibre", p + ".fibre");
  if (g.nodes.empty()) fail(p + ".nodes", "must list at least one node");
  std::vector<bool> seen(nodeCount(s.fibres[f]), false);
  for (size_t k = 0; k < g.nodes.size(); ++k) {
    const int n = g.nodes[k];
    if (n < 0 || n >= int(seen.size()))
      fail(at(p + ".nodes", k), "node " + std::to_string(n) + " outside 0.." +
                                    std::to_string(seen.size() - 1) + " (fibre '" + g.fibre +
                                    "')");
    if (seen[n]) fail(at(p + ".nodes", k), "node " + std::to_string(n) + " listed twice");
    seen[n] = true;
  }
  return nodesOfFibre(f, g.nodes);
}

// A union's members, each once, known (automatic groups and the scene's groups, listed before
// or after it), not the union itself. Their nodes are gathered later, in resolution order.
void checkMembers(const GroupDef& g, const Groups& automatic, const Names& scene,
                  const std::string& p) {
  std::set<std::string> named;
  for (size_t k = 0; k < g.members.size(); ++k) {
    const std::string& m = g.members[k];
    const std::string mp = at(p + ".union", k);
    if (m == g.name) fail(mp, "a group cannot be a union of itself");
    if (!named.insert(m).second) fail(mp, "group '" + m + "' listed twice");
    if (automatic.count(m) || scene.count(m)) continue;
    Names names = scene;
    for (const auto& [n, unused] : automatic) names.emplace(n, 0);
    resolve(names, m, "group", mp);  // fails
  }
}

// The union of the groups `g.members` names (all resolved before it); a node in several members
// counts once.
NodeSet unionGroup(const GroupDef& g, const Groups& groups) {
  NodeSet set;
  std::set<std::pair<size_t, int>> seen;
  for (const std::string& m : g.members)
    for (const auto& node : groups.at(m).nodes)
      if (seen.insert(node).second) set.nodes.push_back(node);
  return set;
}

Groups automaticGroups(const SceneDef& s) {
  Groups groups;
  for (size_t i = 0; i < s.fibres.size(); ++i) {
    std::vector<int> all(nodeCount(s.fibres[i]));
    for (int n = 0; n < int(all.size()); ++n) all[n] = n;
    groups[s.fibres[i].name + ".start"] = nodesOfFibre(i, {0});
    groups[s.fibres[i].name + ".end"] = nodesOfFibre(i, {int(all.size()) - 1});
    groups[s.fibres[i].name + ".all"] = nodesOfFibre(i, all);
  }
  return groups;
}

// One form or the other, and a name of its own.
void checkGroupForm(const SceneDef& s, size_t i, const Groups& automatic, const Names& scene) {
  const GroupDef& g = s.groups[i];
  const std::string p = at("groups", i);
  if (automatic.count(g.name))
    fail(p + ".name", "'" + g.name + "' is an automatic group of fibre '" +
                          s.fibres[automatic.at(g.name).nodes[0].first].name + "'");
  if (!g.members.empty() && (!g.fibre.empty() || !g.nodes.empty()))
    fail(p, "give either 'union' or 'fibre' and 'nodes', not both");
  if (g.members.empty() && g.fibre.empty() && g.nodes.empty())
    fail(p, "give either 'fibre' and 'nodes' (nodes of one fibre) or 'union' (names of other "
            "groups)");
  if (!g.members.empty()) checkMembers(g, automatic, scene, p);
}

// Every group by name: the fibres' automatic ones, then the scene's, unions after the groups
// they name (engine/group_order.h).
Groups validateGroups(const SceneDef& s, const Names& fibres) {
  Groups groups = automaticGroups(s);
  const Names scene = uniqueNames(s.groups, "groups");
  for (size_t i = 0; i < s.groups.size(); ++i) checkGroupForm(s, i, groups, scene);
  for (size_t i : groupResolutionOrder(s.groups)) {
    const GroupDef& g = s.groups[i];
    groups[g.name] =
        g.members.empty() ? fibreGroup(s, g, fibres, at("groups", i)) : unionGroup(g, groups);
  }
  return groups;
}

// --- boundary conditions and loads ---

const char* const kDofNames[kNodeDofs] = {"x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z"};

bool holds(const BcDef& b, int dof) {
  return b.kind == BcKind::Clamp || (b.kind == BcKind::Pin && dof < 3) ||
         (b.kind == BcKind::Fix && b.dofs[dof]);
}

// Displacement * table and rotation of a boundary condition or a tool.
template <class Def>
void validateMotion(const Def& d, const std::string& p) {
  finite(d.displacement, p + ".displacement");
  validateTable(d.displacementTable, p + ".table");
  if (!d.rotates) return;
  nonZero(d.axis, p + ".rotation.axis");
  if (!d.centre.array().isNaN().all()) finite(d.centre, p + ".rotation.centre");
  validateTable(d.angle, p + ".rotation.angle");
}

const NodeSet& resolveGroup(const Groups& groups, const std::string& name,
                            const std::string& path) {
  if (const auto it = groups.find(name); it != groups.end()) return it->second;
  Names names;
  for (const auto& [n, set] : groups) names.emplace(n, 0);
  resolve(names, name, "group", path);  // fails
  return groups.at(name);
}

void validateBcs(const SceneDef& s, const Groups& groups) {
  std::vector<int> firstNode(s.fibres.size() + 1, 0);
  for (size_t f = 0; f < s.fibres.size(); ++f)
    firstNode[f + 1] = firstNode[f] + nodeCount(s.fibres[f]);
  std::vector<int> heldBy(size_t(kNodeDofs) * firstNode.back(), -1);  // DOF -> boundary condition
  for (size_t b = 0; b < s.bcs.size(); ++b) {
    const BcDef& bc = s.bcs[b];
    const std::string p = at("boundary_conditions", b);
    const NodeSet& set = resolveGroup(groups, bc.group, p + ".group");
    if (bc.kind == BcKind::Fix &&
        std::none_of(bc.dofs.begin(), bc.dofs.end(), [](bool d) { return d; }))
      fail(p + ".dofs", "a fix must hold at least one DOF");
    validateMotion(bc, p);
    for (const auto& [fibre, n] : set.nodes)
      for (int c = 0; c < kNodeDofs; ++c) {
        if (!holds(bc, c)) continue;
        int& owner = heldBy[size_t(kNodeDofs) * (firstNode[fibre] + n) + c];
        if (owner >= 0)
          fail(p, std::string("holds DOF ") + kDofNames[c] + " of node " + std::to_string(n) +
                      " of fibre '" + s.fibres[fibre].name + "', already held by " +
                      at("boundary_conditions", owner) + " (group '" + s.bcs[owner].group + "')");
        owner = int(b);
      }
  }
}

// Whether a group holds every node of at least one element of one of its fibres.
bool coversAnElement(const SceneDef& s, const NodeSet& set) {
  const std::set<std::pair<size_t, int>> in(set.nodes.begin(), set.nodes.end());
  std::set<size_t> fibres;
  for (const auto& node : set.nodes) fibres.insert(node.first);
  for (size_t fi : fibres) {
    const FibreDef& f = s.fibres[fi];
    for (int e = 0; e < f.elements; ++e) {
      bool all = true;
      for (int a = 0; a <= f.order; ++a) all = all && in.count({fi, f.order * e + a});
      if (all) return true;
    }
  }
  return false;
}

void validateLoads(const SceneDef& s, const Groups& groups) {
  for (size_t l = 0; l < s.loads.size(); ++l) {
    const LoadDef& load = s.loads[l];
    const std::string p = at("loads", l);
    const NodeSet& set = resolveGroup(groups, load.group, p + ".group");
    finite(load.vector, p + ".vector");
    validateTable(load.table, p + ".table");
    if (load.kind == LoadKind::LineForce && !coversAnElement(s, set))
      fail(p + ".group", "group '" + load.group + "' holds no whole element for a line force");
  }
}

// --- steps, contact, tools, stabilisation, output ---

void validateSteps(const SceneDef& s) {
  double previous = 0;
  Names names;
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const StepDef& st = s.steps[i];
    const std::string p = at("steps", i);
    if (!st.name.empty()) {
      checkName(st.name, p + ".name");
      if (auto [it, fresh] = names.emplace(st.name, i); !fresh)
        fail(p + ".name",
             "duplicate name '" + st.name + "' (also " + at("steps", it->second) + ")");
    }
    if (!(st.endTime > previous && std::isfinite(st.endTime)))
      fail(p + ".end_time", "must be after " +
                                std::string(i ? "the previous step's end, " : "the start, ") +
                                num(previous) + ", got " + num(st.endTime));
    previous = st.endTime;
    inRange(st.increments, 1, StepDef::kMaxIncrements, p + ".increments");
    inRange(st.maxIterations, 1, StepDef::kMaxIterations, p + ".max_iterations");
    positive(st.forceTolerance, p + ".force_tolerance");
    positive(st.incrementTolerance, p + ".increment_tolerance");
    inRange(st.maxCutbacks, 0, StepDef::kMaxCutbacks, p + ".max_cutbacks");
    nonNegative(st.damping, p + ".damping");
    if (st.dampingFrom == DampingFrom::Failure && !(st.damping > 0))
      fail(p + ".damping_from", "\"failure\" needs a `damping` > 0 on the step (the continuation "
                                "it turns on), got damping " + num(st.damping));
    nonNegative(st.frictionFactor, p + ".friction_factor");
    atLeast(st.outputEvery, 1, p + ".output_every");
  }
}

void validateAngle(double rad, const std::string& path) {
  const double deg = rad * 180 / std::numbers::pi;
  if (!std::isnan(rad) && !(deg >= 0 && deg <= 90))
    fail(path, "must be in [0, 90] degrees, got " + num(deg));
}

void validateContact(const ContactDef& c) {
  positiveOrDefault(c.proximityDistance, "contact.proximity_distance");
  positiveOrDefault(c.testPointSpacing, "contact.test_point_spacing");
  validateAngle(c.thetaCross, "contact.theta_cross_deg");
  validateAngle(c.thetaParallel, "contact.theta_parallel_deg");
  if (c.thetaParallel > c.thetaCross)
    fail("contact.theta_parallel_deg",
         "must not exceed theta_cross_deg (" + num(c.thetaCross * 180 / std::numbers::pi) + ")");
  positiveOrDefault(c.selfContactSeparation, "contact.self_contact_separation");
  if (!std::isnan(c.skin)) nonNegative(c.skin, "contact.skin");
  positiveOrDefault(c.maxPenetration, "contact.max_penetration");
  positive(c.regularisation, "contact.regularisation");
  positiveOrDefault(c.initialPenalty, "contact.initial_penalty");
  if (!(c.penaltyChange >= 1 && std::isfinite(c.penaltyChange)))
    fail("contact.penalty_change", "must be >= 1, got " + num(c.penaltyChange));
  positive(c.penaltyMin, "contact.penalty_min");
  if (!(c.penaltyMax >= c.penaltyMin && std::isfinite(c.penaltyMax)))
    fail("contact.penalty_max", "must be finite and >= penalty_min (" + num(c.penaltyMin) +
                                    "), got " + num(c.penaltyMax));
  if (!(c.stepPenetration >= kStepPenetrationMin && c.stepPenetration <= kStepPenetrationMax))
    fail("contact.step_penetration", "must be in [" + num(kStepPenetrationMin) + ", " +
                                         num(kStepPenetrationMax) + "], got " + num(c.stepPenetration));
  nonNegative(c.friction, "contact.friction");
  positiveOrDefault(c.maxReversibleSlip, "contact.max_reversible_slip");
  atLeast(c.maxDetectionLoops, 1, "contact.max_detection_loops");
  atLeast(c.maxNormalLoops, 1, "contact.max_normal_loops");
  if (c.frictionHoldAfter < 0 || c.frictionHoldAfter > 255)
    fail("contact.friction_hold_after", "must be in [0, 255], got " + std::to_string(c.frictionHoldAfter));
  if (!(c.frictionHoldTolerance > 0 && c.frictionHoldTolerance <= 1))
    fail("contact.friction_hold_tolerance", "must be in (0, 1], got " + num(c.frictionHoldTolerance));
  if (c.normalAcceleration < 0 || c.normalAcceleration > kMaxNormalAcceleration)
    fail("contact.normal_acceleration", "must be in [0, " + std::to_string(kMaxNormalAcceleration) +
                                            "], got " + std::to_string(c.normalAcceleration));
}

// The self-contact separation, when given: only with self-contact on (off, it would have no
// effect: a likely mistake), and below the shortest fibre's length (self-contact pairs points of
// one fibre at least the separation apart along it, so a fibre no longer than it never touches
// itself: a loop would pass through itself unseen).
void validateSelfContact(const SceneDef& s) {
  const ContactDef& c = s.contact;
  const double sep = c.selfContactSeparation;
  const std::string field = "contact.self_contact_separation";
  if (std::isnan(sep) || s.fibres.empty()) return;
  if (!c.selfContact)
    fail(field, "given (" + num(sep) + " mm) while self_contact is off (false, or absent: its "
                "default), where it has no effect; set \"self_contact\": true, or remove the "
                "separation");
  std::vector<double> lengths;
  for (const FibreDef& f : s.fibres) lengths.push_back(geometryLength(f.geometry));
  const size_t shortest = size_t(std::min_element(lengths.begin(), lengths.end()) - lengths.begin());
  const double L = lengths[shortest];
  if (!(sep < L))
    fail(field, "must be less than the shortest fibre's length, " + num(L) + " mm (fibre '" +
                    s.fibres[shortest].name + "'), got " + num(sep) +
                    ": with self-contact on, no two points of that fibre are that far apart along "
                    "it, so it would pass through itself unseen; give a separation below " +
                    num(L) + " mm, or leave it out for the derived default");
}

void validateTools(const SceneDef& s) {
  uniqueNames(s.tools, "tools");
  for (size_t i = 0; i < s.tools.size(); ++i) {
    const ToolDef& t = s.tools[i];
    const std::string p = at("tools", i);
    withinScene(t.point, p + ".point");
    nonZero(t.direction, p + (t.kind == ToolKind::Plane ? ".normal" : ".axis"));
    if (t.kind == ToolKind::Cylinder) positive(t.radius, p + ".radius");
    if (t.kind == ToolKind::Cylinder) withinScene(t.radius, p + ".radius");
    validateMotion(t, p);
    nonNegative(t.friction, p + ".friction");
    positiveOrDefault(t.maxPenetration, p + ".max_penetration");
  }
}

void validateStabilisation(const StabilisationDef& st, const Names& fibres) {
  nonNegative(st.stiffness, "stabilisation.stiffness");
  for (size_t i = 0; i < st.fibres.size(); ++i)
    resolve(fibres, st.fibres[i], "fibre", at("stabilisation.fibres", i));
}

// Plots: the columns exist only once the World is built (io/plot_outputs.h checks them).
void validatePlots(const OutputDef& o) {
  std::set<std::string> files;
  for (size_t i = 0; i < o.plots.size(); ++i) {
    const PlotDef& pl = o.plots[i];
    const std::string p = at("output.plots", i);
    if (!o.history) fail(p, "needs the history (output.history is false)");
    if (pl.x.empty()) fail(p + ".x", "must name a history column");
    if (pl.y.empty()) fail(p + ".y", "must name at least one history column");
    for (size_t k = 0; k < pl.y.size(); ++k)
      if (pl.y[k].empty()) fail(at(p + ".y", k), "must name a history column");
    const bool plain = pl.file.find('/') == std::string::npos && pl.file != ".png";
    if (!plain || !pl.file.ends_with(".png"))
      fail(p + ".file", "must be a file name ending in .png (no folder), got '" + pl.file + "'");
    if (!files.insert(pl.file).second) fail(p + ".file", "'" + pl.file + "' repeated");
  }
}

void validateOutput(const SceneDef& s, const Names& fibres) {
  finite(s.output.momentPoint, "output.moment_point");
  validatePlots(s.output);
  uniqueNames(s.output.probes, "output.probes");
  for (size_t i = 0; i < s.output.probes.size(); ++i) {
    const ProbeDef& pr = s.output.probes[i];
    const std::string p = at("output.probes", i);
    const FibreDef& f = s.fibres[resolve(fibres, pr.fibre, "fibre", p + ".fibre")];
    if (pr.node < 0 || pr.node >= nodeCount(f))
      fail(p + ".node", "node " + std::to_string(pr.node) + " outside 0.." +
                            std::to_string(nodeCount(f) - 1) + " (fibre '" + pr.fibre + "')");
  }
}

}  // namespace

void validateTable(const Table& table, const std::string& path) {
  if (table.t.size() != table.v.size())
    fail(path, std::to_string(table.t.size()) + " times but " + std::to_string(table.v.size()) +
                   " values");
  if (table.t.empty()) fail(path, "must have at least one point [t, v]");
  for (size_t i = 0; i < table.t.size(); ++i) {
    finite(table.t[i], at(path, i) + "[0]");
    finite(table.v[i], at(path, i) + "[1]");
    if (i > 0 && !(table.t[i] > table.t[i - 1]))
      fail(at(path, i), "time " + num(table.t[i]) + " does not follow " + num(table.t[i - 1]) +
                            " (times must increase strictly)");
  }
}

// Contact lengths against the fibres' radii: a proximity distance (centre to centre) below two
// radii never finds touching fibres; a tiny test-point spacing or a huge skin or proximity
// costs memory or time without bound (or overflows the broadphase's single-precision boxes).
void validateContactScale(const SceneDef& s) {
  const ContactDef& c = s.contact;
  if (!c.enabled || s.fibres.empty()) return;
  double rMin = s.fibres[0].radius, rMax = rMin;
  for (const FibreDef& f : s.fibres) rMin = std::min(rMin, f.radius), rMax = std::max(rMax, f.radius);
  if (std::isfinite(c.proximityDistance) && !(c.proximityDistance > 2 * rMax))
    fail("contact.proximity_distance",
         "must exceed the sum of two touching fibres' radii (2 x " + num(rMax) + " mm), got " +
             num(c.proximityDistance) + ": closer fibres would not be sought for contact");
  if (std::isfinite(c.proximityDistance) && c.proximityDistance > kLongest)
    fail("contact.proximity_distance", "must be at most " + num(kLongest) + " mm, got " +
                                           num(c.proximityDistance));
  if (std::isfinite(c.skin) && c.skin > kLongest)
    fail("contact.skin", "must be at most " + num(kLongest) + " mm, got " + num(c.skin));
  if (std::isfinite(c.testPointSpacing) && c.testPointSpacing < 1e-3 * rMin)
    fail("contact.test_point_spacing", "must be at least 1e-3 x the smallest radius (" +
                                           num(1e-3 * rMin) + " mm), got " +
                                           num(c.testPointSpacing));
}

void validateScene(const SceneDef& s) {
  if (s.units != "mm-N-MPa") fail("units", "must be \"mm-N-MPa\", got \"" + s.units + "\"");
  const Names materials = validateMaterials(s);
  const Names fibres = validateFibres(s, materials);
  const Groups groups = validateGroups(s, fibres);
  validateBcs(s, groups);
  validateLoads(s, groups);
  validateSteps(s);
  validateContact(s.contact);
  validateContactScale(s);
  validateSelfContact(s);
  validateTools(s);
  validateStabilisation(s.stabilisation, fibres);
  validateSolver(s.solver);
  validateOutput(s, fibres);
}

}  // namespace fibra
