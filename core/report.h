// What a step reports: its status, Newton's iterations, contact counts, timings; and the
// reaction of a boundary condition. Plain data, filled by the engine and its systems.
#pragma once

#include "core/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fibra {

enum class StepStatus {
  Converged,  // the increment converged; the world is at its end
  Failed,     // Newton failed even after the allowed cutbacks; the world is at the last
              // converged state (the increment's start, or the last sub-increment that
              // converged after a cutback; StepReport::time says which)
  Cancelled,  // the cancel callback asked to stop; the world is at the last converged state,
              // as for Failed
  Finished    // there was nothing left to solve
};

struct NewtonRecord {
  double residual;     // |r_free| / reference force, after the iteration
  double increment;    // |dq| of the iteration, mm (mixed DOFs: max-norm)
  double lineSearch;   // step length taken, in (0, 1]: < 1 where the contact step limit, a
                       // halving for a non-finite residual or the line search cut the step
};

struct Progress {
  int step;          // scene step index
  double time;       // pseudo-time being solved for
  double loadFactor; // fraction of the current step reached
  int iteration;     // Newton iteration within the attempt
  double residual;   // relative residual after that iteration
  double stepLength; // share of the Newton step taken, in (0, 1] (NewtonRecord::lineSearch)
  // the iteration's Krylov solve (all 0 for a direct one): the relative tolerance asked, the
  // relative residual |K dq + r| / |r| reached, GMRES iterations
  double tolerance, reached;
  int krylovIterations;
  // contact at the iterate (0 without contact): elements with a normal force, of them those
  // sliding (friction >= 99% of mu R_N), and the deepest penetration / p_max over all elements
  int activeElements, slidingElements;
  double deepest;
  // the free DOF with the largest residual (directors' moments / the length scale, as in the
  // relative residual): "fibre 'NAME' node N x" (N from 0 along the fibre; x, y, z or g1x ... g2z)
  std::string largest;
};

struct StepTimings {  // seconds of wall time in this increment, all attempts together
  double assemble = 0, factorise = 0, solve = 0, total = 0;
};

struct ContactReport {
  int detectionLoops = 0;      // loop A iterations of the accepted attempt
  int normalLoops = 0;         // loop B iterations, summed over loop A
  int normalMixes = 0;         // of them, normal updates replaced by the Anderson-mixed normals
  int restarts = 0;            // loop A passes restarted from the increment's start because the
                               // previous pass penetrated deeply where it had no element, or
                               // its loop B diverged ("newton_frictionless" then linearises)
  int normalRestarts = 0;      // of them, those after loop B diverged
  int zones = 0;               // proximity zones (fibre-fibre)
  int elements = 0;            // fibre-fibre contact elements
  int toolElements = 0;        // fibre-tool contact elements
  int active = 0;              // elements with a positive normal force
  int sliding = 0;             // elements whose friction is >= 99% of mu R_N (kSlidingShare)
  double maxPenetration = 0;   // over all elements, mm
  double maxPenetrationRatio = 0;  // max over zones of penetration / p_max
  double stabilisation = 0;    // |stabilisation forces| / F_ref at convergence
  int frictionHeld = 0;        // elements whose stick/slip status was held in the last pass
                               // (systems/friction_status.h)
  double frictionExcess = 0;   // largest relative distance of a held element past the slip
                               // circle on the wrong side for its branch (friction force error
                               // <= this x mu R_N); 0 when every held status is consistent
  // the contact set at acceptance, against a detection from the accepted state
  // (engine/contact_loops.h, systems/contact_queries.h)
  bool loopCapped = false;     // loop A stopped at its cap without meeting its exit test
  double maxOverlap = 0;       // true overlap w_I + w_J - centre distance at the closest
                               // sections (w: half-widths along the line of centres,
                               // systems/contact_queries.h), max over the pairs found, mm
  double maxOverlapRatio = 0;  // the largest overlap / its element's p_max (its pair's)
  int overlapFibreI = -1, overlapFibreJ = -1;  // the fibres of that overlap (-1: none)
  double overlapSI = 0, overlapSJ = 0;         // its reference arc lengths on them, mm
  double falseClearance = 0;   // the fibres' clearance at an element that pushes (R_N > 0:
                               // a force no contact makes, systems/contact_queries.h
                               // falseForce), max over the set's elements, mm; 0: none
  double falseClearanceRatio = 0;  // the largest such clearance / its element's p_max
  int falseFibreI = -1, falseFibreJ = -1;  // the fibres of that clearance (-1: none)
  double falseSI = 0, falseSJ = 0;         // its reference arc lengths on them, mm
  int redetectZoneChanges = 0; // zones that appear, vanish or change their element count
  double redetectGapChange = 0;     // max |g_N new - g_N used| / p_max over paired elements
  double redetectParticleShift = 0; // max particle shift (arc length and section) / R, same
  // detection, in the last attempt
  int consistencyPasses = 0;   // passes added at acceptance because the set was inconsistent
  int refinedZones = 0;        // zones of the accepted set with Lobatto elements because an
                               // acceptance found the fibres overlapping between their elements
                               // (ZoneStore::refined; carried from increment to increment)
  int newlyRefinedZones = 0;   // of them, refined by the acceptance of this attempt (in a
                               // StepReport: of the increment's converged attempts)
  int detections = 0;          // detection passes (loop A passes of every attempt)
  int broadphaseRebuilds = 0;  // of them, those that rebuilt the broadphase's candidate set
  int candidatePairs = 0;      // candidate element pairs of the last detection
};

// Energy balance since t = 0, N mm (systems/energy_balance.h): the strain energy gained equals the
// work of every force on the fibres, up to the trapezoidal rule's error (`error`), which is of
// second order in the increment. Frictionless contact over a load cycle that returns: the normal
// forces' net work ~0 (they store and give back penalty energy, and do no spurious work).
struct EnergyBalance {
  double strain = 0;         // U(q) - U(q at t = 0)
  double external = 0;       // work of the dead loads (forces, moments, line forces)
  double supports = 0;       // work of the held DOFs' supports (prescribed displacements)
  double contactNormal = 0;  // work of the fibre-fibre normal contact forces
  double friction = 0;       // work of the friction forces, fibre-fibre and tools (-: dissipated
                             // or stored in reversible slip)
  double tools = 0;          // work of the tools' normal forces
  double stabilisation = 0;  // work of the stabilisation springs and continuation damping (<= 0)
  double error() const {
    return strain - (external + supports + contactNormal + friction + tools + stabilisation);
  }
};

// The linear solves of an increment, all attempts together (systems/linear_solver.h
// LinearSolveStats): counts only.
struct LinearReport {
  int analyses = 0;             // symbolic analyses (a new sparsity pattern)
  int factorisations = 0;       // numeric factorisations
  int solves = 0;               // right-hand sides solved
  int fallbacks = 0;            // LL^T -> LDL^T, or MUMPS -> direct
  int krylovIterations = 0;     // GMRES iterations, summed over the solves (Krylov strategies,
                                // or mumps with blr_tolerance > 0)
  int maxKrylovIterations = 0;  // most GMRES iterations of one solve
  int krylovFailures = 0;       // solves that missed krylov_tolerance even with a fresh factor
};

// A change of how the fibre normals enter Newton within a step (contact normal_update "auto",
// engine/step_driver.cpp retryNormals and slowNormalLoop).
enum class NormalChange : std::uint8_t {
  RetryConverged,  // a failed attempt retried with every fibre normal linearised converged: kept
  RetryFailed,     // that retry failed too: loop B's normals, no more retries in the step
  Switched,        // an attempt converged slowly with loop B's normals: the next ones linearise
  BackToLoop,      // a kept linearised attempt failed: retried with loop B's normals, kept
};

struct StepReport {
  StepStatus status = StepStatus::Finished;
  int step = -1;            // scene step index
  int increment = 0;        // increment within the step, 1-based
  double time = 0;          // pseudo-time reached
  double loadFactor = 0;    // fraction of the step reached
  int iterations = 0;       // Newton iterations of the last converged attempt
  int totalIterations = 0;  // Newton iterations of all attempts (cutbacks included)
  int cutbacks = 0;         // failed attempts (each cut the attempt size, engine/step_driver.cpp)
  int subIncrements = 0;    // converged attempts that make up this increment
  int predicted = 0;        // converged attempts that started from the secant predictor
  int predictorRetries = 0;  // predicted attempts that failed and were retried without it
  int normalRetries = 0;    // failed attempts tried again at the same size with the other normal
                            // update: every fibre normal linearised after loop B's, or loop B's
                            // after the linearised ones the step kept (normal_update "auto")
  bool normalsLinearised = false;  // the last converged attempt linearised every fibre normal
  bool normalsSwitched = false;    // an attempt of this increment converged with loop B's
                                   // normals, slowly (normal_update "auto": more than
                                   // max_iterations Newton iterations, more passes than
                                   // detections); the step's next attempts linearise them
  std::vector<NormalChange> normalChanges;  // normal_update "auto": what changed, in order
  int dampedSteps = 0;      // Newton steps the cycle damping halved, all attempts
                            // (systems/newton.h)
  double smallestIncrement = 0;  // pseudo-time size of the smallest converged attempt
  double residual = 0;      // final relative residual
  double viscousForce = 0;  // |viscous continuation force on the free DOFs| / F_ref at the end
  double dampedFrom = -1;   // damping_from "failure": the time from which the continuation acts,
                            // in the increment where it came on; -1 elsewhere
  std::vector<NewtonRecord> history;  // the accepted attempt's iterations
  StepTimings timings;
  ContactReport contact;    // when the scene has contact or tools
  LinearReport linear;      // the increment's linear solves
  EnergyBalance energy;     // since t = 0, at the state reached
  std::string message;      // why a cutback or failure happened
};

// Net reaction of a boundary condition: sum of -r over its held DOFs.
struct Reaction {
  Vec3 force = Vec3::Zero();   // N
  Vec3 moment = Vec3::Zero();  // N mm, about OutputDef::momentPoint
};

}  // namespace fibra
