// The world's state: every store of one scene, the contact state as committed and trial
// instances, the caches, the stages of an iteration, and the step bookkeeping. Internal to the
// engine (the public API is engine/world.h); tests and benches may reach in.
#pragma once

#include "components/beam_forces.h"
#include "components/beam_store.h"
#include "components/boundary.h"
#include "components/contact_cache.h"
#include "components/contact_cliques.h"
#include "components/contact_params.h"
#include "components/contact_state.h"
#include "components/energy.h"
#include "components/fibres.h"
#include "components/iteration.h"
#include "components/linear_system.h"
#include "components/stabilisation.h"
#include "components/tools.h"
#include "core/cancel.h"
#include "engine/pipeline.h"
#include "engine/world.h"
#include "systems/linear_solver.h"

#include <tbb/task_arena.h>

#include <memory>

namespace fibra {

struct WorldState {
  SceneDef scene;
  WorldDef def;

  // Stores of the scene (resolved once).
  MaterialStore materials;
  FibreStore fibres;                 // q: the state being solved for
  BeamStore beams;
  GroupStore groups;
  ConstraintStore constraints;
  LoadStore loads;
  ToolStore tools;
  StabilisationStore stabilisation;
  ContactParams contact;             // every contact parameter, resolved in one place

  // Stores an iteration writes.
  IterationInput input;              // what the next stage runs for (time, tangent)
  BeamForceStore beamForces;
  LinearSystem system;
  ContactLoopStats fibreStats, toolStats;

  // Contact: the last converged state and the attempt in progress (components/contact_state.h);
  // an attempt starts from trial = committed, acceptance swaps them.
  ContactState committed, trial;
  ContactCache cache;                // detection caches (candidates, scratch)
  ContactCliqueStore cliques;        // contact blocks of the tangent's pattern

  // The last converged state besides contact: what the world shows after a failed or cancelled
  // attempt (the residual and external load assembled there).
  struct {
    Eigen::VectorXd q, r, fext;
  } converged;
  EnergyStore energy;                // forces of the converged state, balance since t = 0

  // Solver.
  LinearSolver solver;
  Pipeline pipeline;                 // the stages, each a task graph of systems
  Cancel cancel;                     // WorldDef::cancel, latched for the workers
  std::unique_ptr<tbb::task_arena> ownArena;
  tbb::task_arena* arena = nullptr;
  double lengthScale = 1;    // mm: largest fibre radius, scales position increments
  double forceFloor = 0;     // N: F_ref floor for unloaded states

  // Progress through the scene's steps.
  double time = 0;           // pseudo-time of the converged state
  int step = 0;              // scene step of the next increment
  int increment = 0;         // increments of `step` already converged
  double dt = 0;             // pseudo-time of the next attempt (0: the step's nominal increment)
  // Secant predictor (engine/step_driver.cpp): the rate of the last converged attempt,
  // (q_n - q_{n-1}) / (t_n - t_{n-1}), mm (or director units) per unit pseudo-time, per DOF;
  // it serves the attempts of `rateStep` only (-1: none yet).
  Eigen::VectorXd rate;
  int rateStep = -1;
  bool predict = false;      // whether the attempt in progress starts from the predictor
  // contact normal_update "auto" (engine/step_driver.cpp): the step whose attempts linearise
  // every fibre normal (one of its attempts failed with the loop's normals and converged
  // linearised, or converged slowly with them), the step where a linearised retry failed (no
  // more retries there), and the step where a kept linearised attempt failed (no more retries
  // nor switches there); -1: none.
  int linearisedStep = -1, escalationFailedStep = -1, linearisedFailedStep = -1;
  // Step `damping_from` "failure": the step whose viscous continuation is on (an increment of it
  // failed without), -1: none.
  int dampedStep = -1;
};

inline bool hasContact(const WorldState& w) { return w.contact.tools || w.contact.fibres; }

// Friction between fibres or with a tool: a non-symmetric tangent, and the friction reference
// and history stages.
inline bool hasFriction(const WorldState& w) {
  bool any = w.contact.fibres && w.contact.mu > 0;
  for (double mu : w.tools.friction) any = any || mu > 0;
  return any;
}

// Whether the tangent is symmetric (its upper triangle stored, CHOLMOD): no friction (or its
// symmetrised tangent) and no linearised normal (contact normal_update "newton"; with
// "newton_frictionless" only once loop B diverged in the attempt, ContactParams::unstableNormals).
bool symmetricTangent(const WorldState& w);

// Sets LinearSystem::symmetric; a change rebuilds the pattern at the next detection.
void setSymmetric(WorldState& w, bool symmetric);

// Builds every store from a scene (throws SceneError on unresolved names or bad geometry).
void buildWorld(WorldState& w);

// Runs one stage at pseudo-time t (in the world's arena).
void runStage(WorldState& w, TaskGraph& stage, double t, bool withTangent = true);

// Assembles the residual (and so the reactions) of the current state at pseudo-time t.
void assembleResidual(WorldState& w, double t);

// The checkpoint of the last converged state (World::saveCheckpoint, engine/checkpoint.cpp).
void saveCheckpoint(const WorldState& w, std::ostream& out);
void restoreCheckpoint(WorldState& w, std::istream& in);

// The start of an attempt from the converged state at w.time to tTry: the free DOFs moved by the
// secant predictor where the step has it, the held DOFs to their targets (engine/step_driver.cpp).
void startAttempt(WorldState& w, double tTry);

// Solves the next increment with cutbacks (engine/step_driver.cpp).
StepReport advance(WorldState& w);

}  // namespace fibra
