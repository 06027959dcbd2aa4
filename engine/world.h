// The world: owns every store of one scene and advances it increment by increment.
//
//   fibra::World world(scene, {.threads = 2});
//   while (!world.finished()) {
//     fibra::StepReport r = world.step();
//     if (r.status != fibra::StepStatus::Converged) break;
//   }
//
// No global state: two worlds may run side by side in one process. Threading: step() runs its
// parallel work in the caller's task arena when WorldDef::arena is set, else in an arena of
// WorldDef::threads threads that the world owns. The callbacks are invoked on the thread that
// called step(), never concurrently with each other; they must not call back into the world.
#pragma once

#include "components/beam_store.h"
#include "components/boundary.h"
#include "components/contact.h"
#include "components/contact_mechanics.h"
#include "components/contact_snapshot.h"
#include "systems/linear_solver.h"
#include "components/tools.h"
#include "components/fibres.h"
#include "engine/scene.h"
#include "engine/trace.h"

#include <tbb/task_arena.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibra {

enum class StepStatus {
  Converged,  // the increment converged; the world is at its end
  Failed,     // Newton failed even after the allowed cutbacks; the world is at the last
              // converged state
  Cancelled,  // the cancel callback asked to stop; the world is at the last converged state
  Finished    // there was nothing left to solve
};

struct NewtonRecord {
  double residual;     // |r_free| / reference force, after the iteration
  double increment;    // |dq| of the iteration, mm (mixed DOFs: max-norm)
  double lineSearch;   // step length taken
};

struct Progress {
  int step;          // scene step index
  double time;       // pseudo-time being solved for
  double loadFactor; // fraction of the current step reached
  int iteration;     // Newton iteration within the attempt
  double residual;   // relative residual after that iteration
};

struct StepTimings {  // seconds of wall time in this increment, all attempts together
  double assemble = 0, factorise = 0, solve = 0, total = 0;
};

struct ContactReport {
  int detectionLoops = 0;      // loop A iterations of the accepted attempt
  int normalLoops = 0;         // loop B iterations, summed over loop A
  int restarts = 0;            // loop A passes restarted from the increment's start because the
                               // previous pass penetrated deeply where it had no element
  int zones = 0;               // proximity zones (fibre-fibre)
  int elements = 0;            // fibre-fibre contact elements
  int toolElements = 0;        // fibre-tool contact elements
  int active = 0;              // elements with a positive normal force
  int sliding = 0;             // elements whose friction is >= 99% of mu R_N (kSlidingShare)
  double maxPenetration = 0;   // over all elements, mm
  double maxPenetrationRatio = 0;  // max over zones of penetration / p_max
  double stabilisation = 0;    // |stabilisation forces| / F_ref at convergence
};

struct StepReport {
  StepStatus status = StepStatus::Finished;
  int step = -1;            // scene step index
  int increment = 0;        // increment within the step, 1-based
  double time = 0;          // pseudo-time reached
  double loadFactor = 0;    // fraction of the step reached
  int iterations = 0;       // Newton iterations of the accepted attempt
  int totalIterations = 0;  // Newton iterations of all attempts (cutbacks included)
  int cutbacks = 0;         // bisections needed
  double residual = 0;      // final relative residual
  std::vector<NewtonRecord> history;  // the accepted attempt's iterations
  StepTimings timings;
  ContactReport contact;    // when the scene has contact or tools
  std::string message;      // why a cutback or failure happened
};

struct WorldDef {
  int threads = 0;                      // 0: all cores
  tbb::task_arena* arena = nullptr;     // the caller's arena (threads is then ignored)
  std::function<void(const Progress&)> progress;  // after every Newton iteration
  std::function<bool()> cancel;         // polled between iterations; true stops the step
  Trace* trace = nullptr;               // records the systems' spans when set (engine/trace.h)
  LuSolver luSolver = LuSolver::EigenSparseLu;  // non-symmetric tangents (friction); see
                                                // docs/RESULTS.md for the measurement
};

// Net reaction of a boundary condition: sum of -r over its held DOFs.
struct Reaction {
  Vec3 force = Vec3::Zero();   // N
  Vec3 moment = Vec3::Zero();  // N mm, about OutputDef::momentPoint
};

struct WorldState;

class World {
 public:
  explicit World(const SceneDef& scene, const WorldDef& def = {});  // throws SceneError
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  StepReport step();  // solve the next increment
  bool finished() const;

  double time() const;     // pseudo-time of the current (converged) state
  int currentStep() const; // scene step of the next increment (steps().size() when finished)
  const SceneDef& scene() const;
  const FibreStore& fibres() const;
  const MaterialStore& materials() const;
  const GroupStore& groups() const;
  const ConstraintStore& constraints() const;
  Reaction reaction(Index bc) const;      // of the current state
  Vec3 toolReaction(Index tool) const;    // force the fibres exert on a tool, N
  const ZoneStore& zones() const;                        // of the last contact detection
  const ContactElementStore& contactElements() const;    // their geometry
  const ContactMechanicsStore& contactMechanics() const; // their forces (last assembly)
  const ToolContactStore& toolContacts() const;
  ContactSnapshot contactSnapshot() const;  // all contact elements, flattened for output
  Eigen::VectorXd residual() const;      // r = f_int - f_ext of the current state, all DOFs

 private:
  std::unique_ptr<WorldState> s_;
};

}  // namespace fibra
