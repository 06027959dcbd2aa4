// Scene build: SceneDef -> stores. Resolves names (materials, fibres, groups) into indices,
// generates the fibres' nodes and reference frames, the held DOFs, the beam reference data, the
// equation numbering and the tangent pattern, the contact parameters and tools, and the stages
// of an iteration (engine/pipeline.h).
#include "engine/contact_setup.h"
#include "engine/fibre_builder.h"
#include "engine/group_order.h"
#include "engine/world_state.h"
#include "systems/beam_evaluation.h"
#include "systems/beam_section.h"
#include "systems/boundary.h"
#include "systems/contact_params.h"
#include "systems/energy_balance.h"
#include "systems/sparse_pattern.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace fibra {
namespace {

template <class Def>
std::map<std::string, Index> indexByName(const std::vector<Def>& defs) {
  std::map<std::string, Index> m;
  for (size_t i = 0; i < defs.size(); ++i) m.emplace(defs[i].name, Index(i));
  return m;
}

std::string at(const char* list, size_t i) { return std::string(list) + "[" + std::to_string(i) + "]"; }

void buildMaterials(WorldState& w) {
  for (const MaterialDef& m : w.scene.materials) {
    w.materials.name.push_back(m.name);
    w.materials.youngModulus.push_back(m.youngModulus);
    w.materials.poissonRatio.push_back(m.poissonRatio);
    w.materials.bendingFactor.push_back(m.bendingFactor);
    w.materials.torsionFactor.push_back(m.torsionFactor);
    w.materials.law.push_back(m.law);
  }
}

void buildFibres(WorldState& w) {
  const auto materials = indexByName(w.scene.materials);
  for (size_t i = 0; i < w.scene.fibres.size(); ++i) {
    const FibreDef& f = w.scene.fibres[i];
    const auto m = materials.find(f.material);
    if (m == materials.end())
      throw SceneError(at("fibres", i) + ".material: unknown material '" + f.material + "'");
    addFibre(w.fibres, f, m->second, at("fibres", i));
  }
}

void addGroup(GroupStore& g, const std::string& name, Index firstNode, const std::vector<Index>& nodes) {
  g.name.push_back(name);
  g.first.push_back(Index(g.members.size()));
  g.count.push_back(Index(nodes.size()));
  for (Index n : nodes) g.members.push_back(firstNode + n);
}

// A union group: the global nodes of its members (groups already in the store: automatic ones
// and scene groups resolved before it, engine/group_order.h), each once.
void addUnion(GroupStore& g, const GroupDef& def, const std::string& path) {
  std::map<std::string, Index> known;
  for (Index i = 0; i < g.size(); ++i) known.emplace(g.name[i], i);
  std::vector<Index> nodes;
  std::vector<bool> seen;
  for (size_t k = 0; k < def.members.size(); ++k) {
    const auto m = known.find(def.members[k]);
    if (m == known.end())
      throw SceneError(path + ".union[" + std::to_string(k) + "]: unknown group '" +
                       def.members[k] + "'");
    for (Index j = g.first[m->second]; j < g.first[m->second] + g.count[m->second]; ++j) {
      const Index node = g.members[j];
      if (node >= Index(seen.size())) seen.resize(node + 1, false);
      if (!seen[node]) nodes.push_back(node);
      seen[node] = true;
    }
  }
  addGroup(g, def.name, 0, nodes);
}

void buildGroups(WorldState& w) {
  const FibreStore& fs = w.fibres;
  for (Index f = 0; f < fs.fibres(); ++f) {
    std::vector<Index> all(fs.nodeCount[f]);
    for (Index n = 0; n < fs.nodeCount[f]; ++n) all[n] = n;
    addGroup(w.groups, fs.name[f] + ".start", fs.firstNode[f], {0});
    addGroup(w.groups, fs.name[f] + ".end", fs.firstNode[f], {fs.nodeCount[f] - 1});
    addGroup(w.groups, fs.name[f] + ".all", fs.firstNode[f], all);
  }
  const auto fibres = indexByName(w.scene.fibres);
  for (size_t i : groupResolutionOrder(w.scene.groups)) {  // unions after their members
    const GroupDef& g = w.scene.groups[i];
    if (!g.members.empty()) {
      addUnion(w.groups, g, at("groups", i));
      continue;
    }
    const auto f = fibres.find(g.fibre);
    if (f == fibres.end())
      throw SceneError(at("groups", i) + ".fibre: unknown fibre '" + g.fibre + "'");
    std::vector<Index> nodes;
    for (size_t k = 0; k < g.nodes.size(); ++k) {
      if (g.nodes[k] < 0 || g.nodes[k] >= fs.nodeCount[f->second])
        throw SceneError(at("groups", i) + ".nodes[" + std::to_string(k) + "]: node " +
                         std::to_string(g.nodes[k]) + " outside 0.." +
                         std::to_string(fs.nodeCount[f->second] - 1));
      nodes.push_back(g.nodes[k]);
    }
    addGroup(w.groups, g.name, fs.firstNode[f->second], nodes);
  }
}

Index groupIndex(const GroupStore& g, const std::string& name, const std::string& path) {
  for (Index i = 0; i < g.size(); ++i)
    if (g.name[i] == name) return i;
  throw SceneError(path + ".group: unknown group '" + name + "'");
}

void buildConstraints(WorldState& w) {
  ConstraintStore& cs = w.constraints;
  std::map<Index, Index> heldBy;  // DOF -> BC
  for (size_t b = 0; b < w.scene.bcs.size(); ++b) {
    const BcDef& def = w.scene.bcs[b];
    const std::string path = at("boundary_conditions", b);
    const Index g = groupIndex(w.groups, def.group, path);
    cs.motion.push_back(motionOf(def));
    cs.group.push_back(g);
    for (Index k = w.groups.first[g]; k < w.groups.first[g] + w.groups.count[g]; ++k)
      for (int c = 0; c < kNodeDofs; ++c) {
        const bool held = def.kind == BcKind::Clamp || (def.kind == BcKind::Pin && c < 3) ||
                          (def.kind == BcKind::Fix && def.dofs[c]);
        if (!held) continue;
        const Index dof = kNodeDofs * w.groups.members[k] + c;
        if (auto [it, fresh] = heldBy.emplace(dof, Index(b)); !fresh)
          throw SceneError(path + ": holds a DOF of node " + std::to_string(w.groups.members[k]) +
                           " already held by " + at("boundary_conditions", it->second));
      }
  }
  for (const auto& [dof, bc] : heldBy) {
    cs.dof.push_back(dof);
    cs.owner.push_back(bc);
  }
}

void buildLoads(WorldState& w) {
  LoadStore& ls = w.loads;
  ls.elementFirst.assign(1, 0);
  for (size_t l = 0; l < w.scene.loads.size(); ++l) {
    const Index g = groupIndex(w.groups, w.scene.loads[l].group, at("loads", l));
    const LoadDef& def = w.scene.loads[l];
    ls.kind.push_back(def.kind);
    ls.vector.push_back(def.vector);
    ls.table.push_back(def.table);
    ls.group.push_back(g);
    if (w.scene.loads[l].kind == LoadKind::LineForce) {
      std::vector<bool> in(w.fibres.nodes(), false);
      for (Index k = w.groups.first[g]; k < w.groups.first[g] + w.groups.count[g]; ++k) in[w.groups.members[k]] = true;
      for (Index e = 0; e < w.fibres.elements(); ++e) {
        bool all = true;
        for (int a = 0; a <= w.fibres.order[w.fibres.elementFibre[e]]; ++a) all = all && in[w.fibres.elementFirstNode[e] + a];
        if (all) ls.elements.push_back(e);
      }
    }
    ls.elementFirst.push_back(Index(ls.elements.size()));
  }
}

// The stabilisation springs of the listed fibres (all when none is listed).
void buildStabilisation(WorldState& w) {
  const StabilisationDef& st = w.scene.stabilisation;
  StabilisationStore& s = w.stabilisation;
  s.stiffness.assign(w.fibres.nodes(), 0.0);
  for (Index f = 0; f < w.fibres.fibres(); ++f) {
    const bool listed = st.fibres.empty() ||
                        std::find(st.fibres.begin(), st.fibres.end(), w.fibres.name[f]) != st.fibres.end();
    if (!listed) continue;
    for (Index n = 0; n < w.fibres.nodeCount[f]; ++n) s.stiffness[w.fibres.firstNode[f] + n] = st.stiffness;
  }
  s.active = st.stiffness > 0 || anyStepDamped(w.scene);
  s.qStart = w.fibres.q;
}

// The contact parameters, in one place, and the tools with their zones.
void buildContact(WorldState& w) {
  w.contact = resolveContact(w.fibres, w.scene);
  buildTools(w.scene, w.fibres, w.materials, w.contact, w.tools, w.committed.toolZones);
  w.trial = w.committed;
}

// torsion_factor 0 leaves the twist of a straight fibre's sections about its centreline without
// stiffness, a zero pivot of the first tangent: the fibre needs the stabilisation's springs, or
// damping in every step.
void checkTorsionFree(const SceneDef& s) {
  const auto damped = [&] {
    for (const StepDef& st : s.steps)
      if (!(st.damping > 0)) return false;
    return true;
  };
  for (const FibreDef& f : s.fibres) {
    size_t m = 0;
    while (m < s.materials.size() && s.materials[m].name != f.material) ++m;
    if (m == s.materials.size()) continue;  // reported by buildMaterials
    if (s.materials[m].torsionFactor != 0 || damped()) continue;
    const std::vector<std::string>& held = s.stabilisation.fibres;
    if (s.stabilisation.stiffness > 0 &&
        (held.empty() || std::find(held.begin(), held.end(), f.name) != held.end()))
      continue;
    throw SceneError(at("materials", m) + ".torsion_factor: 0 leaves the twist of fibre '" +
                     f.name + "' about its centreline without stiffness: give it the "
                     "stabilisation (stabilisation.stiffness > 0) or damping in every step "
                     "(docs/SCENE.md, Materials)");
  }
}

}  // namespace

bool symmetricTangent(const WorldState& w) {
  const bool linearised = w.contact.fibres && normalsInNewton(w.contact);
  return !linearised && (!hasFriction(w) || w.contact.symmetrised);
}

void setSymmetric(WorldState& w, bool symmetric) {
  if (w.system.symmetric == symmetric) return;
  w.system.symmetric = symmetric;
  w.cliques.colourFirst.clear();  // the next detection rebuilds the pattern (a new analysis)
}

void buildWorld(WorldState& w) {
  if (w.scene.units != "mm-N-MPa")
    throw SceneError("units: only \"mm-N-MPa\" is supported, got \"" + w.scene.units + "\"");
  w.solver.setLuSolver(w.def.luSolver);
  w.solver.setStrategy(w.def.linearStrategy.value_or(w.scene.solver.strategy));
  w.solver.setKrylov(w.scene.solver.krylov);
  w.solver.setOrdering(w.scene.solver.ordering);
  w.solver.setTrace(w.def.trace);
  w.solver.setFibres(&w.fibres);
  if (w.def.arena) {
    w.arena = w.def.arena;
  } else {
    w.ownArena = std::make_unique<tbb::task_arena>(w.def.threads > 0 ? w.def.threads
                                                                     : int(tbb::task_arena::automatic));
    w.arena = w.ownArena.get();
  }
  w.solver.setBlasThreads(w.arena->max_concurrency());
  buildMaterials(w);
  checkTorsionFree(w.scene);
  buildFibres(w);
  buildGroups(w);
  buildConstraints(w);
  buildLoads(w);

  std::vector<BeamIntegration> integration;
  for (const FibreDef& f : w.scene.fibres) integration.push_back(f.integration);
  try {
    w.arena->execute([&] { buildBeamReference(w.fibres, w.materials, integration, w.beams); });
  } catch (const FoldedSectionError& e) {
    char span[96];
    std::snprintf(span, sizeof span, "%.6g and %.6g mm", e.s1, e.s2);
    throw SceneError(at("fibres", std::size_t(e.fibre)) +
                     ".geometry: the reference section folds between s = " + span +
                     ": the centreline bends there tighter than the radius (a polyline corner "
                     "inside an element is interpolated by such a curve: put the corner on a node, "
                     "at a multiple of the element length, or round it)");
  }

  double maxRadius = 0, maxArea = 0, maxE = 0;
  for (Index f = 0; f < w.fibres.fibres(); ++f) {
    maxRadius = std::max(maxRadius, w.fibres.radius[f]);
    maxArea = std::max(maxArea, w.fibres.radius[f] * w.fibres.radius[f] * 3.141592653589793);
    maxE = std::max(maxE, w.materials.youngModulus[w.fibres.material[f]]);
  }
  w.lengthScale = maxRadius > 0 ? maxRadius : 1;
  // The residual's roundoff, measured on a rigidly moved 20-element beam 10 mm from the origin,
  // is 7e-14 E A, and it grows with the coordinates and the number of DOFs: the floor (the force
  // that strains the stiffest fibre by 1e-4) keeps the default relative tolerance above it.
  w.forceFloor = 1e-4 * maxE * maxArea;

  buildContact(w);
  buildStabilisation(w);
  // A linearised normal makes the fibre-fibre tangent non-symmetric (and, on an unstable
  // equilibrium, indefinite): sparse LU (systems/linear_solver.h). The step driver sets it again
  // at every attempt; the contact loops clear it when they linearise ("newton_frictionless").
  w.system.symmetric = symmetricTangent(w);

  numberEquations(w.fibres, w.constraints, w.system);
  w.arena->execute([&] { buildPattern(w.fibres, beamCliques(w.fibres), w.system); });
  w.system.r.setZero(w.fibres.q.size());
  w.system.fext.setZero(w.fibres.q.size());
  buildPipeline(w);
  applyConstraints(w.fibres, w.constraints, w.groups, 0.0, w.fibres.q);
  assembleResidual(w, 0.0);
  w.converged = {w.fibres.q, w.system.r, w.system.fext};
  energyForces(w.fibres, w.constraints, w.system, hasContact(w) ? &w.committed : nullptr,
               w.energy.last);
  w.energy.strainAtStart = beamEnergy(w.fibres, w.beams, w.fibres.q);
}

}  // namespace fibra
