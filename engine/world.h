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
// WorldDef::threads threads that the world owns. The sparse factorisations (CHOLMOD, UMFPACK)
// spend their time in OpenBLAS, whose thread count is process-wide: the world sets it to its
// arena's concurrency before each factorisation, so that BLAS does not oversubscribe the
// cores the arena is given (two worlds running at once with different thread counts share that
// setting: each factorisation runs with the count set last). Results are bitwise the same for
// every thread count where no threaded BLAS is involved (Eigen's SparseLU, the default for
// friction); CHOLMOD's and UMFPACK's BLAS (and so the Krylov strategy, preconditioned by
// CHOLMOD) may sum in another order with another thread count, and are deterministic for one.
// The callbacks are invoked on the thread that called step(), never concurrently with each
// other; they must not call back into the world. The cancel callback is polled between Newton
// iterations and, during detection, once per chunk of work.
#pragma once

#include "components/beam_store.h"
#include "components/boundary.h"
#include "components/contact_snapshot.h"
#include "components/contact_state.h"
#include "components/fibres.h"
#include "components/tools.h"
#include "systems/linear_solver.h"
#include "engine/scene.h"
#include "core/report.h"
#include "core/trace.h"

#include <tbb/task_arena.h>

#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibra {

struct WorldDef {
  int threads = 0;                      // 0: all cores
  tbb::task_arena* arena = nullptr;     // the caller's arena (threads is then ignored)
  std::function<void(const Progress&)> progress;  // after every Newton iteration
  std::function<bool()> cancel;         // polled between iterations and per chunk of detection;
                                        // true stops the step
  Trace* trace = nullptr;               // records the systems' spans when set (engine/trace.h)
  LuSolver luSolver = LuSolver::EigenSparseLu;  // non-symmetric tangents (friction); see
                                                // docs/RESULTS.md for the measurement
  // The linear strategy; unset: the scene's solver.strategy (default auto: by size, and from
  // 7 000 equations by the fill MUMPS's analysis estimates, systems/linear_solver.h). The
  // measured choice is in docs/RESULTS.md ("Linear solves at paper scale", "Inside Newton").
  std::optional<LinearStrategy> linearStrategy;
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
  const ToolStore& tools() const;         // geometry at t = 0 and motions (systems/tool_geometry.h)
  Reaction reaction(Index bc) const;      // of the current state
  Vec3 toolReaction(Index tool) const;    // force the fibres exert on a tool, N
  // The contact state of the current (last converged) state: zones with their penalties,
  // fibre-fibre and fibre-tool contact elements with their forces, the friction history.
  const ContactState& contact() const;
  ContactSnapshot contactSnapshot() const;  // all contact elements, flattened for output
  Eigen::VectorXd residual() const;      // r = f_int - f_ext of the current state, all DOFs

  // The last converged state as a binary checkpoint (engine/checkpoint.cpp): positions, the
  // committed contact state (zones with their identities and penalties, contact elements,
  // stick/slip statuses, the friction history), the converged residual, the energy balance, the
  // progress through the steps. A world built from the same scene and restored from it goes on
  // bitwise as the saved one goes on (docs/SCENE.md "Resuming a run"). For the same fibra version
  // on the same kind of machine. save: std::runtime_error when the stream fails. restore: a
  // CheckpointError (core/errors.h) for a stream that is not a whole checkpoint of this scene by
  // this version, and the world is then unchanged; call between steps.
  void saveCheckpoint(std::ostream& out) const;
  void restoreCheckpoint(std::istream& in);

  // The stages of an iteration for this scene as Markdown: per stage, every system with the
  // stores it reads and writes (from its signature) and the systems it waits for, and a Mermaid
  // graph (engine/pipeline.h; docs/ARCHITECTURE.md shows one).
  std::string describe() const;

 private:
  std::unique_ptr<WorldState> s_;
};

}  // namespace fibra
