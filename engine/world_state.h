// The world's state: every store of one scene, the solver's caches and the step bookkeeping.
// Internal to the engine (the public API is engine/world.h).
#pragma once

#include "components/beam_store.h"
#include "components/boundary.h"
#include "components/contact.h"
#include "components/contact_cache.h"
#include "components/contact_mechanics.h"
#include "components/fibres.h"
#include "components/friction_history.h"
#include "components/linear_system.h"
#include "components/tools.h"
#include "engine/task_graph.h"
#include "engine/world.h"
#include "systems/contact_params.h"
#include "systems/linear_solver.h"

#include <tbb/task_arena.h>

#include <map>
#include <memory>

namespace fibra {

// The report counts an element as sliding when its friction force is at least this share of
// the Coulomb limit mu R_N (a re-detected element starts a little inside the limit: its
// reversible slip is interpolated from the recorded history).
inline constexpr double kSlidingShare = 0.99;
inline bool sliding(double normalForce, const Vec3& gRev, double gMax) {
  return normalForce > 0 && gRev.norm() >= kSlidingShare * gMax;
}

// Contact parameters resolved from the scene (defaults derived from the radii).
struct ContactSettings {
  bool tools = false;              // the scene has tools
  bool fibres = false;             // fibre-fibre contact is on
  double pMax = 0;                 // p_max of fibre-fibre zones, mm
  int maxDetectionLoops = 3;       // n_A
  int maxNormalLoops = 3;          // n_B
  double pRegRatio = 0.5;          // p_reg / p_max
  double penaltyChange = 10;       // bound on k_new / k_old per update
  double penaltyTarget = 0.9;      // eq. 13 aims the deepest penetration at this x p_max
  double gMax = 0;                 // reversible slip g_T,max, mm
  double toolProximity = 0;        // tool contacts are made within R + this, mm (NaN: default)
  bool symmetrised = false;        // friction tangent without its non-symmetric part
  double normalTolerance = 1e-3;   // rad: loop B stops when no normal turns more
  double particleTolerance = 1e-3; // x R: loop A stops when no centreline moved more
  double penaltyTolerance = 0.1;   // loop A stops when no penalty changes by more
  double stepPenetration = 10;     // x p_max: deepest closing of an element in one Newton step
};

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

  // Contact.
  ContactSettings contact;
  ContactParams detection;             // resolved detection parameters
  ContactCache cache;                  // broadphase candidates, zone identities
  ZoneStore zones;
  ContactElementStore elements;
  ContactMechanicsStore mechanics;
  std::map<std::uint64_t, double> zonePenalty;  // k by zone id, carried across calls, N/mm
  std::map<std::pair<Index, Index>, Index> contactClique;  // (element I, element J) -> clique
  ToolStore tools;
  ToolContactStore toolContacts;
  FrictionHistoryStore history;        // at the reference state of the current contact loop
  std::vector<double> stabilisation;   // spring stiffness per node, N/mm
  Eigen::VectorXd qStart;              // state at the start of the increment

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

inline bool hasContact(const WorldState& w) { return w.contact.tools || w.contact.fibres; }

// The motion of a boundary condition's held DOFs, of a tool.
PrescribedMotion motionOf(const BcDef& def);
PrescribedMotion motionOf(const ToolDef& def);

// Builds every store from a scene (throws SceneError on unresolved names or bad geometry).
void buildWorld(WorldState& w);

// Assembles the residual (and so the reactions) of the current state at pseudo-time t.
void assembleResidual(WorldState& w, double t);

// Solves the next increment with cutbacks (engine/step_driver.cpp).
StepReport advance(WorldState& w);

}  // namespace fibra
