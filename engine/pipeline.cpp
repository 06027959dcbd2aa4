#include "engine/pipeline.h"

#include "engine/world_state.h"
#include "systems/beam_evaluation.h"
#include "systems/beam_scatter.h"
#include "systems/boundary.h"
#include "systems/broadphase.h"
#include "systems/clear_system.h"
#include "systems/contact_cliques.h"
#include "systems/contact_detection.h"
#include "systems/contact_elements.h"
#include "systems/contact_normals.h"
#include "systems/contact_particles.h"
#include "systems/contact_scatter.h"
#include "systems/crossing_follow.h"
#include "systems/face_follow.h"
#include "systems/fibre_contact_law.h"
#include "systems/friction_history.h"
#include "systems/friction_reference.h"
#include "systems/penalty_adapter.h"
#include "systems/stabilisation.h"
#include "systems/tool_contact.h"
#include "systems/tool_detection.h"
#include "systems/tool_normals.h"
#include "systems/zone_builder.h"
#include "systems/zone_identity.h"
#include "systems/zone_penalty.h"

#include <sstream>

namespace fibra {
namespace {

void nameStores(WorldState& w, StoreNames& n) {
  n.add(w.materials, "materials");
  n.add(w.fibres, "fibres");
  n.addPart(w.fibres.q, "fibres.q", w.fibres);
  n.add(w.beams, "beams");
  n.add(w.groups, "groups");
  n.add(w.loads, "loads");
  n.add(w.tools, "tools");
  n.add(w.stabilisation, "stabilisation");
  n.add(w.contact, "contact params");
  n.add(w.input, "input");
  n.add(w.beamForces, "beam forces");
  n.add(w.system, "linear system");
  n.add(w.fibreStats, "fibre loop stats");
  n.add(w.toolStats, "tool loop stats");
  n.add(w.trial.zones, "zones");
  n.add(w.trial.elements, "contact elements");
  n.add(w.trial.forces, "contact forces");
  n.add(w.trial.frictionStatus, "friction status");
  n.add(w.trial.toolZones, "tool zones");
  n.add(w.trial.toolElements, "tool elements");
  n.add(w.trial.toolForces, "tool forces");
  n.add(w.trial.toolFrictionStatus, "tool friction status");
  n.add(w.trial.history, "friction history");
  n.add(w.cache.centrelines, "centrelines");
  n.add(w.cache.broadphase, "broadphase cache");
  n.add(w.cache.zones, "zone scratch");
  n.add(w.cache.builtZones, "built zones");
  n.add(w.cliques, "contact cliques");
  n.add(w.cancel, "cancel");
}

void buildDetect(WorldState& w, TaskGraph& g) {
  ContactState& s = w.trial;
  ContactCache& c = w.cache;
  Trace*& trace = w.def.trace;
  if (w.contact.fibres) {
    g.add("broadphase", updateBroadphase, w.fibres, w.fibres.q, w.contact, c.centrelines,
          c.broadphase, trace, w.cancel);
    g.add("zone builder", buildZones, w.fibres, w.contact, c.centrelines, c.broadphase, c.zones,
          c.builtZones, trace, w.cancel);
    g.add("zone identity", matchZones, w.fibres, w.contact, s.zones, c.zones, c.builtZones, trace);
    g.add("zone penalties", carryZonePenalties, w.fibres, w.materials, w.contact, s.zones,
          c.builtZones);
    g.add("adopt zones", adoptZones, c.builtZones, s.zones);
    g.add("contact elements", generateContactElements, w.fibres, w.fibres.q, w.contact,
          c.centrelines, s.zones, s.elements, trace, w.cancel);
    g.add("contact particles", bindContactParticles, w.fibres, s.elements);
    g.add("contact cliques", bindContactCliques, w.fibres, w.contact, s.elements, w.cliques,
          w.system);
  }
  if (w.contact.tools)
    g.add("tool detection", detectToolContacts, w.fibres, w.tools, w.contact, w.input,
          s.toolElements);
}

void buildReference(WorldState& w, TaskGraph& g) {
  ContactState& s = w.trial;
  g.add("friction reference", setFrictionReference, w.fibres, w.tools, s.history, w.input,
        s.elements, s.toolElements);
}

void buildDetectAndReference(WorldState& w, TaskGraph& g) {
  buildDetect(w, g);
  if (hasFriction(w)) buildReference(w, g);
}

void buildNormals(WorldState& w, TaskGraph& g) {
  ContactState& s = w.trial;
  if (w.contact.fibres && w.contact.followCrossings)
    g.add("crossing follow", followCrossings, w.fibres, w.fibres.q, w.contact, s.zones,
          s.elements, w.fibreStats);
  if (w.contact.fibres)
    g.add("face follow", followEndFaces, w.fibres, w.fibres.q, w.contact, s.zones, s.elements,
          w.fibreStats);
  if (w.contact.fibres)
    g.add("contact normals", updateNormalsAndGaps, w.fibres, w.fibres.q, w.contact, s.elements,
          w.fibreStats, w.def.trace);
  if (w.contact.tools)
    g.add("tool normals", updateToolNormals, w.fibres, w.tools, w.input, s.toolElements,
          w.toolStats);
}

void buildAdapt(WorldState& w, TaskGraph& g) {
  ContactState& s = w.trial;
  if (w.contact.fibres)
    g.add("zone penalty adapter", adaptZonePenalties, w.contact, s.elements, s.forces, s.zones,
          w.fibreStats);
  if (w.contact.tools)
    g.add("tool penalty adapter", adaptToolZonePenalties, w.contact, s.toolElements, s.toolForces,
          s.toolZones, w.toolStats);
  if (hasFriction(w))
    g.add("friction history", recordFrictionHistory, w.fibres, s.elements, s.forces,
          s.toolElements, s.toolForces, s.history);
}

// Evaluations first (they write their own stores and run side by side), then the scatter into
// the linear system, which every scatter writes: a chain in this order.
void buildAssemble(WorldState& w, TaskGraph& g) {
  ContactState& s = w.trial;
  g.add("beam evaluation", evaluateBeams, w.fibres, w.beams, w.input, w.beamForces);
  if (w.contact.fibres)
    g.add("fibre contact law", evaluateFibreContacts, w.fibres, w.contact, s.zones, s.elements,
          w.input, s.frictionStatus, s.forces);
  if (w.contact.tools)
    g.add("tool contact law", evaluateToolContacts, w.fibres, w.tools, s.toolZones, w.contact,
          s.toolElements, w.input, s.toolFrictionStatus, s.toolForces);
  g.add("clear", clearSystem, w.fibres, w.input, w.system);
  g.add("beam scatter", scatterBeams, w.fibres, w.beams, w.beamForces, w.input, w.system);
  g.add("loads", assembleLoads, w.fibres, w.loads, w.groups, w.input, w.system);
  if (w.contact.fibres)
    g.add("fibre contact scatter", scatterFibreContacts, s.elements, s.forces, w.cliques, w.input,
          w.system);
  if (w.contact.tools)
    g.add("tool contact scatter", scatterToolContacts, s.toolElements, s.toolForces, w.input,
          w.system);
  if (w.stabilisation.active)
    g.add("stabilisation", assembleStabilisation, w.fibres, w.stabilisation, w.input, w.system);
}

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : ", ") + s;
  return out.empty() ? "-" : out;
}

void describeStage(std::ostringstream& out, const char* title, const TaskGraph& g) {
  out << "### " << title << "\n\n";
  if (g.size() == 0) {
    out << "(no systems in this scene)\n\n";
    return;
  }
  out << "| # | system | reads | writes | after |\n|---|---|---|---|---|\n";
  for (int i = 0; i < g.size(); ++i) {
    std::vector<std::string> after;
    for (int p : g.predecessors(i)) after.push_back(std::to_string(p));
    out << "| " << i << " | " << g.name(i) << " | " << joined(g.reads(i)) << " | "
        << joined(g.writes(i)) << " | " << joined(after) << " |\n";
  }
  out << "\n```mermaid\nflowchart LR\n";
  for (int i = 0; i < g.size(); ++i) out << "  s" << i << "[\"" << g.name(i) << "\"]\n";
  for (int i = 0; i < g.size(); ++i)
    for (int p : g.predecessors(i)) out << "  s" << p << " --> s" << i << "\n";
  out << "```\n\n";
}

}  // namespace

void buildPipeline(WorldState& w) {
  Pipeline& p = w.pipeline;
  nameStores(w, p.names);
  if (hasContact(w)) {
    buildDetectAndReference(w, p.detect);
    if (hasFriction(w)) buildReference(w, p.reference);
    buildNormals(w, p.normals);
    buildAdapt(w, p.adapt);
  }
  buildAssemble(w, p.assemble);
  w.arena->execute([&] {
    for (TaskGraph* g : {&p.detect, &p.reference, &p.normals, &p.adapt, &p.assemble}) g->build();
  });
}

std::string describePipeline(const Pipeline& p) {
  std::ostringstream out;
  describeStage(out, "detect (loop A)", p.detect);
  describeStage(out, "reference (a restarted loop A pass)", p.reference);
  describeStage(out, "normals (loop B)", p.normals);
  describeStage(out, "adapt (end of a loop A pass)", p.adapt);
  describeStage(out, "assemble (each Newton iteration)", p.assemble);
  return out.str();
}

}  // namespace fibra
