// The world's state: every store of one scene, the solver's caches and the step bookkeeping.
// Internal to the engine (the public API is engine/world.h).
#pragma once

#include "components/beam_store.h"
#include "components/boundary.h"
#include "components/fibres.h"
#include "components/linear_system.h"
#include "engine/task_graph.h"
#include "engine/world.h"
#include "systems/linear_solver.h"

#include <tbb/task_arena.h>

#include <memory>

namespace fibra {

struct WorldState {
  SceneDef scene;
  WorldDef def;

  // Stores.
  MaterialStore materials;
  FibreStore fibres;
  BeamStore beams;
  GroupStore groups;
  ConstraintStore constraints;
  LoadStore loads;
  LinearSystem system;

  // Solver.
  LinearSolver solver;
  TaskGraph iteration;       // the systems of one Newton iteration
  bool withTangent = true;   // what the next run of `iteration` assembles
  std::unique_ptr<tbb::task_arena> ownArena;
  tbb::task_arena* arena = nullptr;
  double lengthScale = 1;    // mm: largest fibre radius, scales position increments
  double forceFloor = 0;     // N: F_ref floor for unloaded states

  // Progress through the scene's steps.
  double time = 0;           // pseudo-time of the converged state
  double solveTime = 0;      // pseudo-time the systems assemble for (the attempt's target)
  int step = 0;              // scene step of the next increment
  int increment = 0;         // increments of `step` already converged
};

// Builds every store from a scene (throws SceneError on unresolved names or bad geometry).
void buildWorld(WorldState& w);

// Assembles the residual (and so the reactions) of the current state at pseudo-time t.
void assembleResidual(WorldState& w, double t);

// Solves the next increment with cutbacks (engine/step_driver.cpp).
StepReport advance(WorldState& w);

}  // namespace fibra
