// The stages of an iteration, each a task graph of systems built from what the systems read and
// write (engine/task_graph.h), for the stores of one world. The step driver runs them as a list:
//
//   detect      loop A: broadphase, zones, identity, zone penalties, contact elements,
//               particles, cliques (fibre-fibre) beside the tool detection; then the friction
//               reference of every new element
//   reference   the friction reference alone (a loop A pass restarted from the increment start)
//   normals     loop B: normals and gaps at the current state (fibre-fibre beside fibre-tool)
//   adapt       end of a loop A pass: zone penalties (eq. 13, fibre-fibre beside fibre-tool) and
//               the friction history
//   assemble    one Newton iteration: beam evaluation, fibre-fibre and fibre-tool contact laws
//               side by side; then the scatter into the linear system, in a fixed order
//
// A scene pays only for what it needs: systems of contact it does not have (fibre-fibre, tools,
// friction) and the stabilisation when it is off are not in its graphs. docs/ARCHITECTURE.md is generated
// from these graphs (describePipeline).
#pragma once

#include "engine/task_graph.h"

#include <string>

namespace fibra {

struct WorldState;

struct Pipeline {
  StoreNames names;
  TaskGraph detect{&names}, reference{&names}, normals{&names}, adapt{&names}, assemble{&names};
};

// Builds the world's stages (after its stores are sized).
void buildPipeline(WorldState& w);

// The stages as Markdown: per stage, its systems with what they read and write and the systems
// they wait for, and a Mermaid graph of the edges.
std::string describePipeline(const Pipeline& p);

}  // namespace fibra
