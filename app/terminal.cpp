#include "app/terminal.h"

#include "core/format.h"
#include "engine/contact_setup.h"
#include "engine/free_spin.h"
#include "engine/torqued_strings.h"
#include "systems/contact_params.h"
#include "systems/contact_queries.h"
#include "systems/interpolation.h"
#include "systems/linear_solver.h"
#include "systems/tool_detection.h"
#include "fibra/version.h"

#include <tbb/info.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <numbers>

namespace fibra::terminal {
namespace {

std::string format(const char* fmt, auto... args) {
  char line[512];
  std::snprintf(line, sizeof line, fmt, args...);
  return line;
}

double degrees(double rad) { return rad * 180 / std::numbers::pi; }

// Penalty bounds as multiples of the zone's section stiffness E R.
std::string penaltyBounds(double lo, double hi) { return format("penalty %g .. %g x E R", lo, hi); }

// The laws' settings common to every pair (per pair class: pairLines).
std::string lawLine(const ContactParams& c) {
  const std::string initial = std::isfinite(c.initialPenalty)
                                  ? format("%g N/mm", c.initialPenalty)
                                  : std::string("E R");
  std::string out = format("  contact law: %s, initial penalty %s, change <= x%g, p_reg %g p_max, "
                           "step limit %g p_max, g_T,max %g mm, friction tangent %s",
                           penaltyBounds(c.pairs.penaltyMin[0], c.pairs.penaltyMax[0]).c_str(),
                           initial.c_str(), c.penaltyChange, c.pRegRatio, c.stepPenetration, c.gMax,
                           c.symmetrised ? "symmetrised" : "consistent");
  if (c.fibres) out += format(", element placement %s, normals %s",
                              c.placement == ElementPlacement::Weighted
                                  ? "weighted (Lobatto in the zones the acceptance refines)"
                              : c.placement == ElementPlacement::Lobatto ? "lobatto"
                                                                         : "paper",
                              c.newtonNormals && !c.newtonFrictionlessOnly ? "linearised in Newton"
                                                                           : "updated by loop B");
  if (c.fibres && (!c.newtonNormals || c.newtonFrictionlessOnly))
    out += c.normalMemory > 0 ? format(" (Anderson memory %d when unstable)", c.normalMemory)
                              : std::string(" (plain)");
  if (c.fibres && c.newtonFrictionlessOnly)
    out += ", frictionless parallel normals linearised in Newton once loop B diverges";
  if (c.fibres && c.escalateNormals)
    out += ", every fibre normal linearised after a failed attempt (retried) or a slow loop B "
           "(kept while it converges; a failed linearised attempt goes back to loop B for the "
           "step)";
  if (c.mu > 0 || c.tools)  // friction is possible (tools carry their own mu)
    out += c.frictionFlips > 0 ? format(", stick/slip held after %d changes (tolerance %g)",
                                        c.frictionFlips, c.frictionTolerance)
                               : std::string(", stick/slip never held");
  return out + "\n";
}

// The fibres' contact classes in order of first appearance, with their fibre counts; "" when
// every fibre is in the default class.
std::string classesLine(const SceneDef& s) {
  std::vector<std::pair<std::string, int>> classes;
  for (const FibreDef& f : s.fibres) {
    auto it = std::find_if(classes.begin(), classes.end(),
                           [&](const auto& c) { return c.first == f.contactClass; });
    if (it == classes.end()) it = classes.insert(classes.end(), {f.contactClass, 0});
    ++it->second;
  }
  if (classes.size() == 1 && classes[0].first.empty()) return "";
  std::string out = "  contact classes:";
  for (size_t i = 0; i < classes.size(); ++i)
    out += format("%s %s (%d fibres)", i ? "," : "",
                  classes[i].first.empty() ? "(default)" : classes[i].first.c_str(),
                  classes[i].second);
  return out + "\n";
}

// One line per rule of contact.pairs with the values it resolves to (pair class i + 1).
std::string pairLines(const SceneDef& s, const ContactClasses& c) {
  if (s.contact.pairs.empty()) return "";
  std::string out = "  contact pairs (other pairs: the section's mu, p_max and penalty above):\n";
  for (size_t i = 0; i < s.contact.pairs.size(); ++i) {
    const ContactPairDef& r = s.contact.pairs[i];
    const std::string who = r.rule == PairRule::Within    ? "within"
                            : r.rule == PairRule::Between ? "between"
                                                          : "[" + r.classes[0] + ", " +
                                                                r.classes[1] + "]";
    out += format("    %s: mu %g, p_max %g mm, %s\n", who.c_str(), c.mu[i + 1], c.pMax[i + 1],
                  penaltyBounds(c.penaltyMin[i + 1], c.penaltyMax[i + 1]).c_str());
  }
  return out;
}

// The spread of the fibres' nodal centres along the unit direction d at the current state, mm.
double spreadAlong(const FibreStore& fs, const Vec3& d) {
  double lo = INFINITY, hi = -INFINITY;
  for (Index n = 0; n < fs.nodes(); ++n) {
    const double h = d.dot(Vec3(fs.q.segment<3>(kNodeDofs * n)));
    lo = std::min(lo, h), hi = std::max(hi, h);
  }
  return fs.nodes() > 0 ? hi - lo : 0;
}

// Warnings on the first step's forced normals at the scene's start, "" for any other state or
// scene (S the centres' spread along D, H = S + 2 max R the fibres' height, a bound on any
// pair's overlap along D):
// - an allowance A > H leaves the first min(n - 1, floor(n (A - H) / A)) of n increments
//   nothing to push out;
// - S beyond the proximity distance: a pair in the wrong order further apart than Delta_prox is
//   not detected until it comes within it, at a penetration of up to 2R + Delta_prox - A at once
//   (docs/RESULTS.md "Forced normals with an allowance: thick yarns").
std::string forcedStartWarnings(const World& world, const ContactParams& c) {
  const SceneDef& s = world.scene();
  if (!c.fibres || s.steps.empty() || s.steps[0].forcedNormal.squaredNorm() == 0 ||
      world.time() != 0)
    return "";
  const StepDef& st = s.steps[0];
  const FibreStore& fs = world.fibres();
  const double spread = spreadAlong(fs, st.forcedNormal);  // a unit vector (validated)
  double r = 0, prox = 0;
  for (Index f = 0; f < fs.fibres(); ++f)
    r = std::max(r, fs.radius[f]), prox = std::max(prox, proximityDistance(c, f, f));
  const double a = st.forcedAllowance, h = spread + 2 * r;
  const int n = st.increments;
  // The last increment ends at the plain forced gap, so at most n - 1 are idle.
  const int idle = a > h ? std::min(n - 1, int(std::floor(n * (a - h) / a))) : 0;
  std::string out;
  if (idle > 0)
    out += format("    warning: the allowance %g mm exceeds the fibres' whole height along the "
                  "direction at the start, %.3g mm (their centres' spread and 2 R): no overlap "
                  "can be that deep, and the step's first %s (of %d) %s nothing to do (give "
                  "about the deepest overlap of the start, at most %.3g mm)\n",
                  a, h, idle == 1 ? "increment" : counted(idle, "increment").c_str(), n,
                  idle == 1 ? "has" : "have", h);
  if (spread > prox)
    out += format("    warning: the fibres' centres spread %.3g mm along the direction, more than "
                  "the proximity distance %.3g mm: a pair in the wrong order further apart is "
                  "not detected until it comes within it, and then at up to %.3g mm of "
                  "penetration at once (2 R + the proximity distance), less the allowance left; "
                  "a `proximity_distance` of at least %.3g mm sees every pair from the start "
                  "(a bound from all the centres: check that the direction is normal to the "
                  "layers it separates)\n",
                  spread, prox, 2 * r + prox, spread);
  return out;
}

// The steps whose contact normals are forced, and the first step's warnings at the start.
std::string forcedLines(const World& world, const ContactParams& c) {
  const SceneDef& s = world.scene();
  std::string out;
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const Vec3& d = s.steps[i].forcedNormal;
    const double a = s.steps[i].forcedAllowance;
    if (d.squaredNorm() == 0) continue;
    out += format("  forced normals: step %zu%s along [%g, %g, %g]%s\n", i + 1,
                  s.steps[i].name.empty() ? "" : (" (" + s.steps[i].name + ")").c_str(), d.x(),
                  d.y(), d.z(),
                  a > 0 ? format(", allowance %g mm released over the step", a).c_str() : "");
    if (i == 0) out += forcedStartWarnings(world, c);
  }
  return out;
}

// A line when tool t overlaps the fibres by more than kToolStartOverlap p_max at the scene's start
// (a tool placed inside the fibres, which the first increment must push out at once); "" otherwise,
// and on a resumed run (whose tools may be in contact).
std::string toolStartWarning(const World& world, Index t) {
  const ToolStore& tools = world.tools();
  const FibreStore& fs = world.fibres();
  if (world.time() != 0) return "";
  const ToolOverlap o = toolOverlap(fs, fs.q, tools, t, 0);
  if (o.depth <= kToolStartOverlap * tools.pMax[t]) return "";
  const Index f = fs.elementFibre[o.element];
  return format("    warning: %s overlaps the fibres by %.3g mm (%.3g p_max) at the start, deepest "
                "at s = %.4g mm along fibre '%s': the first increment has to push it out at once "
                "(place the tool clear of the fibres and move it in)\n",
                tools.name[t].c_str(), o.depth, o.depth / tools.pMax[t],
                arcLength(fs, o.element, o.z), fs.name[f].c_str());
}

// Each tool's kind, friction, p_max and the contact points it takes per fibre element (the
// range over the fibres: systems/tool_detection.h toolPointsPerElement).
std::string toolLines(const World& world) {
  const ToolStore& tools = world.tools();
  const FibreStore& fs = world.fibres();
  std::string out = format("  tools: %d\n", tools.size());
  for (Index t = 0; t < tools.size(); ++t) {
    const double rho = toolCurvatureRadius(tools, t);
    int fewest = kMaxToolPoints, most = 0;
    double sagitta = 0;  // the largest sagitta bound where the cap is reached, mm
    for (Index f = 0; f < fs.fibres(); ++f) {
      const double h = elementLength(fs, f);
      const int n = toolPointsPerElement(h, rho, tools.pMax[t], fs.order[f]);
      fewest = std::min(fewest, n), most = std::max(most, n);
      if (n == kMaxToolPoints) sagitta = std::max(sagitta, toolSagittaBound(h, rho, n));
    }
    if (most == 0) fewest = 0;  // no fibres
    const std::string points = fewest == most ? format("%d", most) : format("%d-%d", fewest, most);
    out += format("    %s: %s, mu %g, p_max %g mm, %s points per fibre element\n",
                  tools.name[t].c_str(), tools.kind[t] == ToolKind::Plane ? "plane" : "cylinder",
                  tools.friction[t], tools.pMax[t], points.c_str());
    if (sagitta > 0.25 * tools.pMax[t])
      out += format("    note: %s caps at %d points per element: a fibre across it may be "
                    "overlapped by up to %.3g p_max between two points (finer elements or a "
                    "larger p_max bring it to 0.25)\n",
                    tools.name[t].c_str(), kMaxToolPoints, sagitta / tools.pMax[t]);
    out += toolStartWarning(world, t);
  }
  return out;
}

// "N fibre(s) (a, b, c, d, ...)": the count and the first four names of fibres (indices).
std::string fibreList(const World& world, const std::vector<Index>& fibres) {
  std::string list;
  for (size_t i = 0; i < fibres.size() && i < 4; ++i)
    list += (i ? ", " : "") + world.scene().fibres[fibres[i]].name;
  if (fibres.size() > 4) list += ", ...";
  return format("%zu fibre%s (%s)", fibres.size(), fibres.size() == 1 ? "" : "s", list.c_str());
}

// The resolved self-contact separation (components/contact_params.h selfSeparation), "" with
// self-contact off: once in mm when every fibre has the same, else each value (as printed) with
// the fibres that have it, or the range over the fibres when there are more than four values.
std::string selfSeparationLine(const World& world, const ContactParams& c) {
  if (!c.fibres || !c.selfContact || c.selfSeparation.empty()) return "";
  std::vector<std::pair<std::string, std::vector<Index>>> values;  // in order of first fibre
  for (Index f = 0; f < Index(c.selfSeparation.size()); ++f) {
    const std::string v = format("%g", c.selfSeparation[f]);
    auto it = std::find_if(values.begin(), values.end(), [&](const auto& e) { return e.first == v; });
    if (it == values.end()) it = values.insert(values.end(), {v, {}});
    it->second.push_back(f);
  }
  if (values.size() == 1) return "  self-contact separation: " + values[0].first + " mm\n";
  if (values.size() > 4)
    return format("  self-contact separation: %g .. %g mm over the fibres\n",
                  *std::min_element(c.selfSeparation.begin(), c.selfSeparation.end()),
                  *std::max_element(c.selfSeparation.begin(), c.selfSeparation.end()));
  std::string out = "  self-contact separation:";
  for (size_t i = 0; i < values.size(); ++i)
    out += format("%s %s mm for %s", i ? "," : "", values[i].first.c_str(),
                  fibreList(world, values[i].second).c_str());
  return out + "\n";
}

// The contact choices that change results: the section's values (pair class 0), the laws, the
// classes and every pair rule's resolved values, forced normals, tools.
std::string contactLines(const World& world) {
  const SceneDef& s = world.scene();
  if (!s.contact.enabled && s.tools.empty()) return "  contact: none\n";
  const ContactParams c = resolveContact(world.fibres(), s);
  std::string out;
  if (c.fibres)
    out += format("  contact: fibre-fibre, p_max %g mm, mu %g, theta_cross %g deg, "
                  "theta_parallel %g deg, self-contact %s, loops A <= %d, B <= %d%s%s\n",
                  c.pairs.pMax[0], c.pairs.mu[0], degrees(c.thetaCross), degrees(c.thetaParallel),
                  c.selfContact ? "on" : "off", c.maxDetectionLoops, c.maxNormalLoops,
                  c.followCrossings ? ", crossings follow the closest points" : "",
                  c.facingParticles
                      ? ", normal forces on facing particles (friction on material ones)"
                      : ", normal forces on material particles (the paper's)");
  out += selfSeparationLine(world, c) + lawLine(c);
  if (c.fibres) out += classesLine(s) + pairLines(s, c.pairs) + forcedLines(world, c);
  if (c.tools) out += toolLines(world);
  return out;
}

// The fibres whose spin only friction holds (engine/free_spin.h), as a note.
std::string freeSpinLine(const World& world) {
  const std::vector<Index> fibres = freeSpinFibres(world);
  if (fibres.empty()) return "";
  const char* its = fibres.size() == 1 ? "its" : "their";
  return format("  note: %s can spin freely: only friction holds %s spin about %s axis, none "
                "once all %s contacts slip; if Newton stagnates, hold at an end a director "
                "component the spin turns (docs/METHOD.md \"Free spin\")\n",
                fibreList(world, fibres).c_str(), its, its, its);
}

// The strings whose sections are twisted (engine/torqued_strings.h), as a note: the fibre whose
// torque is the largest against its radius (the straight string's limit is about T R), its
// torque and radius.
std::string torquedStringLine(const World& world) {
  const std::vector<TorquedString> strings = torquedStrings(world);
  if (strings.empty()) return "";
  std::vector<Index> fibres;
  const TorquedString* worst = &strings.front();
  for (const TorquedString& t : strings) {
    fibres.push_back(t.fibre);
    if (t.torque / t.radius > worst->torque / worst->radius) worst = &t;
  }
  const bool one = strings.size() == 1;
  return format("  note: %s without bending stiffness %s twisted about %s axis, up to %.3g N mm "
                "of torque (%s, R = %.3g mm): a string holds its straight state only up to about "
                "T R (Greenhill's limit with the tension's own bending stiffness T R^2 / 4; T the "
                "tension), beyond which it zigzags from node to node and contact misses the "
                "kinks; a smaller torsion_factor lowers the torque (docs/METHOD.md \"Strings "
                "under torque\")\n",
                fibreList(world, fibres).c_str(), one ? "is" : "are", one ? "its" : "their",
                worst->torque, world.scene().fibres[worst->fibre].name.c_str(), worst->radius);
}

// The fibres on a law other than Saint Venant-Kirchhoff (materials' `law`), as a line.
std::string materialLawLine(const World& world) {
  std::vector<Index> fibres;
  for (Index f = 0; f < world.fibres().fibres(); ++f)
    if (world.scene().materials[world.fibres().material[f]].law != MaterialLaw::SaintVenantKirchhoff)
      fibres.push_back(f);
  if (fibres.empty()) return "";
  return format("  sections: neo-Hookean for %s (integrated point by point at every iteration, "
                "enhanced transverse strains)\n",
                fibreList(world, fibres).c_str());
}

// The steps with a viscous continuation, and when it acts, as a line.
std::string continuationLine(const SceneDef& s) {
  std::string list;
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const StepDef& st = s.steps[i];
    if (!(st.damping > 0)) continue;
    list += format("%sstep %zu damping %g %s", list.empty() ? "" : ", ", i + 1, st.damping,
                   st.dampingFrom == DampingFrom::Start ? "from its start"
                                                        : "from its first failed increment");
  }
  return list.empty() ? "" : "  viscous continuation: " + list + "\n";
}

// The scene's linear solver settings (a WorldDef may override the strategy: engine/world.h).
std::string solverLine(const SceneDef& s) {
  const SolverDef& v = s.solver;
  std::string strategy = strategyName(v.strategy);
  if (v.strategy == LinearStrategy::Auto)
    strategy += format(" (direct below %d free equations, from there mumps, or schwarz where "
                       "MUMPS's analysis estimates >= %g flops per non-zero)",
                       int(kMumpsFromEquations), kSchwarzFromFlopsPerEntry);
  std::string out = format("  linear solver: %s, ordering %s", strategy.c_str(),
                           v.ordering == Ordering::Auto  ? "auto"
                           : v.ordering == Ordering::Amd ? "amd"
                                                         : "metis");
  if (v.krylov.blrTolerance > 0) out += format(", block low-rank %g", v.krylov.blrTolerance);
  if (v.strategy != LinearStrategy::Schwarz)
    out += v.krylov.patternSlack > 0
               ? format(", on K's non-zeros (pattern slack %g)", v.krylov.patternSlack)
               : std::string(", on K's stored pattern");
  const bool schwarz = v.strategy == LinearStrategy::Schwarz || v.strategy == LinearStrategy::Auto;
  if (schwarz)
    out += format(", schwarz's coarse level of %d segment%s per fibre, rotations %s",
                  v.krylov.coarseSegments, v.krylov.coarseSegments == 1 ? "" : "s",
                  v.krylov.coarseRotations == CoarseRotations::On    ? "on"
                  : v.krylov.coarseRotations == CoarseRotations::Off ? "off"
                                                                     : "auto");
  const bool krylov = v.strategy == LinearStrategy::Krylov || v.strategy == LinearStrategy::KrylovLu ||
                      schwarz || v.krylov.blrTolerance > 0;
  if (krylov)
    out += format(", GMRES to %g (restart %d, <= %d iterations)", v.krylov.tolerance,
                  v.krylov.restart, v.krylov.maxIterations);
  if (krylov && v.krylov.forcingMax > 0)
    out += format(", inexact Newton (forcing term <= %g)", v.krylov.forcingMax);
  return out + "\n";
}

}  // namespace

std::string describeProblem(const World& world, const std::string& scene, int threads) {
  const SceneDef& s = world.scene();
  const FibreStore& f = world.fibres();
  int increments = 0;
  for (const StepDef& st : s.steps) increments += st.increments;
  std::string out = format("fibra %s: %s\n", FIBRA_VERSION_STRING, scene.c_str());
  out += format("  %d fibres, %d nodes, %d elements, %d DOFs\n", f.fibres(), f.nodes(),
                f.elements(), 9 * f.nodes());
  out += format("  %zu steps, %d increments, t = 0 .. %g\n", s.steps.size(), increments,
                s.steps.empty() ? 0.0 : s.steps.back().endTime);
  out += materialLawLine(world);
  out += continuationLine(s);
  out += contactLines(world);
  out += freeSpinLine(world);
  out += torquedStringLine(world);
  out += solverLine(s);
  if (threads >= 0)
    out += format("  threads: %d\n", threads > 0 ? threads : tbb::info::default_concurrency());
  return out;
}

std::string startWarnings(const World& world) {
  std::string out;
  for (Index t = 0; t < world.tools().size(); ++t) out += toolStartWarning(world, t);
  if (world.scene().contact.enabled)
    out += forcedStartWarnings(world, resolveContact(world.fibres(), world.scene()));
  return out;
}

void printIteration(const Progress& p) {
  std::string line = format("  step %d  t = %-10.6g load %5.1f%%  iteration %2d  residual %.3e",
                            p.step + 1, p.time, 100 * p.loadFactor, p.iteration, p.residual);
  if (p.stepLength < 1) line += format("  step x%.3g", p.stepLength);
  if (p.krylovIterations > 0)
    line += format("  gmres %d to %.1e (asked %.1e)", p.krylovIterations, p.reached, p.tolerance);
  if (p.activeElements > 0)
    line += format("  active %d, sliding %d, deepest %.3g p_max", p.activeElements,
                   p.slidingElements, p.deepest);
  if (!p.largest.empty()) line += "  largest at " + p.largest;
  std::fprintf(stderr, "%s\n", line.c_str());
}

void printNormalChanges(const StepReport& r, bool stepEnds, Explained& explained) {
  std::string line;
  bool linearised = false;
  for (const NormalChange c : r.normalChanges) {
    line += line.empty() ? "" : "; ";
    switch (c) {
      case NormalChange::RetryConverged:
        line += "an attempt that failed with loop B's normals converged with every fibre normal "
                "linearised";
        linearised = true;
        break;
      case NormalChange::RetryFailed:
        line += "an attempt that failed with loop B's normals failed again with every fibre "
                "normal linearised (no more such retries in this step)";
        linearised = false;
        break;
      case NormalChange::Switched:
        line += "an attempt converged slowly with loop B's normals";
        linearised = true;
        break;
      case NormalChange::BackToLoop:
        line += "an attempt with every fibre normal linearised failed and was tried again with "
                "loop B's normals";
        linearised = false;
        break;
    }
  }
  const NormalChange last = r.normalChanges.back();
  const char* rest = r.status == StepStatus::Failed ? "the increment failed"
                     : stepEnds ? "the step ends here"
                     : linearised
                         ? "the step goes on with every fibre normal linearised in Newton"
                     : last == NormalChange::BackToLoop
                         ? "the step goes on with loop B's normals to its end"
                         : "the step goes on with loop B's normals (a slow loop B may still switch)";
  std::fprintf(stderr, "  normals: %s; %s%s\n", line.c_str(), rest,
               explained.normalChanges ? ""
                                       : " (contact.normal_update \"auto\": a failed attempt is "
                                         "tried again linearised, a slow loop B switches, a failed "
                                         "linearised attempt goes back to loop B for the step; "
                                         "normal_retries in the history; docs/CONTACT.md 1.5)");
  explained.normalChanges = true;
}

void printIncrement(const StepReport& r, const SceneDef& scene, Verbosity v, Explained& explained) {
  if (v == Verbosity::Quiet) return;
  const StepDef& st = scene.steps[r.step];
  // "1 iteration " keeps the column of "2 iterations".
  std::string line = format("step %d/%zu  increment %d/%d  t = %-8.6g %2d iteration%s  "
                            "residual %.2e",
                            r.step + 1, scene.steps.size(), r.increment, st.increments, r.time,
                            r.iterations, r.iterations == 1 ? " " : "s", r.residual);
  if (r.cutbacks > 0) line += "  " + counted(r.cutbacks, "cutback");
  if (r.dampedSteps > 0) line += "  " + counted(r.dampedSteps, "damped step");
  const bool contact = scene.contact.enabled || !scene.tools.empty();
  const ContactReport& c = r.contact;
  if (contact)
    line += format("  contact %d+%d (%d sliding), penetration %.2f p_max", c.elements,
                   c.toolElements, c.sliding, c.maxPenetrationRatio);
  if (contact && c.restarts > 0) line += "  " + counted(c.restarts, "loop restart");
  if (contact && c.loopCapped) line += "  loop A capped";
  std::fprintf(stderr, "%s  %.3g s\n", line.c_str(), r.timings.total);
  // Each failed attempt as "<what followed it> at t = <its end>: <why it failed>".
  if (r.cutbacks + r.predictorRetries + r.normalRetries > 0)
    std::fprintf(stderr, "  failed attempts (what followed at t: why): %s\n", r.message.c_str());
  if (contact && c.consistencyPasses > 0)
    std::fprintf(stderr,
                 "  note: %d more pass(es) with a new detection at acceptance: the fibres "
                 "overlapped deeper than the contact elements reported (contact.max_overlap)\n",
                 c.consistencyPasses);
  if (contact && c.newlyRefinedZones > 0)
    std::fprintf(stderr,
                 "  note: %s where the fibres overlapped between the contact elements now "
                 "carry Lobatto elements (contact.refined_zones)\n",
                 counted(c.newlyRefinedZones, "zone").c_str());
  if (contact && c.loopCapped && !explained.loopCapped) {
    explained.loopCapped = true;
    std::fprintf(stderr,
                 "  note: loop A capped: the increment's last pass was solved with the elements of "
                 "its detection %d (contact.max_detection_loops) and the fibres still moved, or a "
                 "penalty still changed, after it; contact.loop_a_capped and contact.redetect_* "
                 "in the history say how far a fresh detection would differ (said once)\n",
                 scene.contact.maxDetectionLoops);
  }
  if (!r.normalChanges.empty())
    printNormalChanges(r, r.increment == st.increments, explained);
  if (contact && c.normalRestarts > 0)
    std::fprintf(stderr,
                 "  note: loop B's normal updates diverged: the increment restarted with the "
                 "frictionless parallel normals linearised in Newton (contact.normal_update)\n");
  if (r.dampedFrom >= 0)
    std::fprintf(stderr,
                 "  note: the increment failed without the viscous continuation; it acts from "
                 "t = %g to the step's end (damping_from \"failure\", damping %g)\n",
                 r.dampedFrom, st.damping);
  if (st.damping > 0 && r.increment == st.increments && r.viscousForce > 1e-2)
    std::fprintf(stderr,
                 "  note: the step ends %.3g of the reference force away from static equilibrium "
                 "(viscous_force); hold the loads in a step with damping to let the state settle\n",
                 r.viscousForce);
  if (v != Verbosity::Verbose) return;
  const LinearReport& l = r.linear;
  std::string linear = format("  linear solves: %d factorisations (%d analyses), %d solves",
                              l.factorisations, l.analyses, l.solves);
  if (l.fallbacks > 0) linear += format(", %d fallbacks", l.fallbacks);
  if (l.krylovIterations > 0 || l.krylovFailures > 0)
    linear += format(", GMRES %d iterations (at most %d in one solve), %d failures",
                     l.krylovIterations, l.maxKrylovIterations, l.krylovFailures);
  std::fprintf(stderr, "%s\n", linear.c_str());
  if (!contact) return;
  std::fprintf(stderr,
               "  contact: %d zones (%d refined), %d + %d tool elements (%d active, %d sliding), "
               "max penetration %.3g mm (%.2f p_max), loops A %d B %d, %d restarts; detection: "
               "%d passes, %d broadphase rebuilds, %d candidate pairs\n",
               c.zones, c.refinedZones, c.elements, c.toolElements, c.active, c.sliding, c.maxPenetration,
               c.maxPenetrationRatio, c.detectionLoops, c.normalLoops, c.restarts, c.detections,
               c.broadphaseRebuilds, c.candidatePairs);
  if (scene.contact.enabled)
    std::fprintf(stderr,
                 "  contact set at acceptance: true overlap %.3g mm; a new detection changes %d "
                 "zones, gaps by up to %.2f p_max, particles by up to %.3f R%s\n",
                 c.maxOverlap, c.redetectZoneChanges, c.redetectGapChange,
                 c.redetectParticleShift, c.loopCapped ? "; loop A stopped at its cap" : "");
}

}  // namespace fibra::terminal
