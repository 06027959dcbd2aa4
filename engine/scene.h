// The scene description: what a user asks fibra to solve. Plain Def structs with defaults; a
// scene file (docs/SCENE.md) is parsed into a SceneDef, and an embedding program may also fill
// one directly. Units are consistent throughout: mm, N, MPa (so stresses in N/mm^2, moments in
// N mm, energies in N mm); angles in radians.
#pragma once

#include "components/beam_store.h"
#include "components/boundary.h"
#include "components/contact_params.h"
#include "components/solver_settings.h"
#include "components/tools.h"
#include "core/errors.h"
#include "core/table.h"

#include <Eigen/Core>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibra {

struct MaterialDef {
  std::string name;
  double youngModulus = 0;    // E, MPa
  double poissonRatio = 0.3;  // nu
  double bendingFactor = 1;   // scales EI (paper Table 1: 0.12)
  double torsionFactor = 1;   // scales GJ
  MaterialLaw law = MaterialLaw::SaintVenantKirchhoff;  // the sections' hyperelastic law
};

enum class GeometryKind { Line, Polyline, Helix };

// When a step's viscous continuation (`damping`) acts (StepDef::dampingFrom).
enum class DampingFrom { Start, Failure };

struct GeometryDef {
  GeometryKind kind = GeometryKind::Line;
  std::vector<Vec3> points;  // Line: start and end; Polyline: the vertices (mm)
  // Optional hint for the first director G1 at the fibre's start (projected normal to the
  // tangent); when absent, a direction normal to the tangent is chosen. Line and Polyline only:
  // the directors are transported along the centreline without twist.
  Vec3 director = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  // Helix: x(phi) = origin + r (cos phi e1 + sin phi e2) + pitch phi / (2 pi) axis, phi from
  // phase over `turns` turns (negative turns: left-handed); e1 normal to the axis. G1 points
  // radially outwards, G2 = t x G1.
  Vec3 origin = Vec3::Zero();   // a point of the helix axis, mm
  Vec3 axis = Vec3::UnitZ();    // helix axis direction
  double helixRadius = 0;       // mm
  double pitch = 0;             // axial advance per turn, mm
  double turns = 0;             // number of turns (sign: handedness)
  double phase = 0;             // starting angle, rad
};

// A piece of a fibre's level table: from reference arc length `from` on (until the next piece)
// the fibre lies at `level` (dimensionless; only the order of two levels matters). Where two
// fibres of different contact classes cross during a step with forced normals, the one at the
// higher level goes over (docs/SCENE.md, "Forced normals").
struct LevelDef {
  double from = 0;   // reference arc length where the piece starts, mm (the first piece: 0)
  double level = 0;
};

struct FibreDef {
  std::string name;
  std::string material;  // a MaterialDef name
  double radius = 0;     // cross-section radius, mm
  int elements = 0;      // number of elements
  int order = 2;         // 1 linear, 2 quadratic
  GeometryDef geometry;
  BeamIntegration integration;
  std::string contactClass;        // contact class (a yarn's fibres share one); "": the default
  std::vector<LevelDef> levels;    // level table along the fibre (empty: level 0 everywhere)
};

// A named set of nodes. Every fibre F also has the groups "F.start", "F.end" and "F.all".
// Either nodes of one fibre (`fibre` and `nodes`) or, when `members` is not empty, the union of
// other groups (automatic ones or groups listed before this one; a node in several members
// counts once), which may span several fibres.
struct GroupDef {
  std::string name;
  std::string fibre;
  std::vector<int> nodes;             // node indices within the fibre, 0-based
  std::vector<std::string> members;   // union form: names of other groups
};

// Held DOFs of a group's nodes. Targets follow the reference and the motion:
//   x0 = c + R(t) (X0 - c) + d(t),  g_a = R(t) G_a,
// R(t) the rotation by angle(t) about `axis` through centre c, d(t) = displacement * table(t).
enum class BcKind { Clamp, Pin, Fix };
enum Dof { X, Y, Z, G1X, G1Y, G1Z, G2X, G2Y, G2Z };

struct BcDef {
  BcKind kind = BcKind::Clamp;  // Clamp: all 9 DOFs; Pin: x0; Fix: the `dofs` listed
  std::string group;
  std::array<bool, 9> dofs{};            // Fix only
  Vec3 displacement = Vec3::Zero();      // mm, scaled by displacementTable
  Table displacementTable{{0.0, 1.0}, {0.0, 1.0}};
  bool rotates = false;
  Vec3 axis = Vec3::UnitZ();             // rotation axis (normalised when used)
  Vec3 centre = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // default: node's X0
  Table angle;                        // rad
};

// Dead loads. Force: F (N) on each node of the group, adding -F.x0 to the energy. Moment: M
// (N mm) on each node, a torque |M| about the fixed axis M/|M|, adding -|M| phi, phi the rotation
// of the section about that axis measured on the directors' projections (conservative,
// symmetric). LineForce: w (N/mm) per unit reference length on every element whose nodes all
// belong to the group, distributed consistently (f_a = w int N_a ds).
struct LoadDef {
  LoadKind kind = LoadKind::Force;
  std::string group;
  Vec3 vector = Vec3::Zero();  // N or N mm per node, or N/mm along the fibre; scaled by table
  Table table{{0.0, 1.0}, {0.0, 1.0}};
};

struct StepDef {
  // Upper bounds the validation enforces, so that a mistyped value (1e9) cannot run for hours:
  // the stagnation test stops a stuck attempt long before 10000 iterations, and 50 cuts (each a
  // half or a quarter) bring an attempt below 1e-15 of its size, past the round-off stop.
  static constexpr int kMaxIterations = 10000;
  static constexpr int kMaxCutbacks = 50;
  // Each increment writes a history row and a checkpoint (and a frame every output_every-th):
  // a million per step is past any scene's need and bounds a mistyped 2e9.
  static constexpr int kMaxIncrements = 1000000;

  std::string name;
  double endTime = 1;              // pseudo-time at the end of the step (steps follow each other)
  int increments = 1;              // equal increments of pseudo-time
  int maxIterations = 30;          // Newton iterations per increment before a cutback
  double forceTolerance = 1e-8;    // |r_free| <= tol * max(|f_ext|, |reactions|, 1e-4 E A)
  double incrementTolerance = 1e-10;  // remaining correction: |dx0| <= tol * R_max, |dg| <= tol
  int maxCutbacks = 8;             // failed attempts of an increment before the step fails
  bool lineSearch = false;         // non-monotone line search in Newton (systems/newton.h)
  // Secant predictor: an attempt after the step's first converged one starts from
  // q_n + dt (q_n - q_{n-1}) / dt_{n-1} on the free DOFs (engine/step_driver.cpp).
  bool predictor = true;
  double damping = 0;              // viscous continuation c, N/mm x pseudo-time per node (0: off)
  // When the continuation acts: from the step's start, or from the first increment that fails
  // without it after its cutbacks to the step's end (load control until then).
  DampingFrom dampingFrom = DampingFrom::Start;
  int outputEvery = 1;             // write output every n converged increments (and the last)
  // Forced normals (paper section 5.2.1): unit direction D; zero: the normal rules (eq. 10).
  // During the step, between fibres of different contact classes whose levels differ at the
  // element, N = +D when I's level is the higher, else -D (docs/SCENE.md).
  Vec3 forcedNormal = Vec3::Zero();
  // Gradual push-apart of the forced pairs, mm, >= 0 (`forced_normals.allowance`): a forced
  // element's gap is widened by A (t_end - t) / (t_end - t_start) at the attempt's end time t, so
  // that the step removes an overlap of A in equal parts instead of all in its first increment.
  double forcedAllowance = 0;
  // Factor on every friction coefficient (fibre pairs and tools) during the step, >= 0: 0 turns
  // friction off (a forced-normals step), 1 the scene's values.
  double frictionFactor = 1;
};

struct ProbeDef {
  std::string name;
  std::string fibre;
  int node = 0;  // node index within the fibre
};

enum class VtuEncoding { Binary, Ascii };  // zlib-compressed appended data, or XML text

// A picture drawn at the end of a run (io/plot.h): history columns y against column x, as the
// PNG `file` in the output directory (a plain file name ending in .png).
struct PlotDef {
  std::string x;
  std::vector<std::string> y;
  std::string file;
  std::string title;  // "" for none
};

struct OutputDef {
  bool vtu = true;                      // ParaView series
  VtuEncoding vtuEncoding = VtuEncoding::Binary;
  bool history = true;                  // CSV history
  bool finalState = true;               // every node's x0, g1, g2 at the end
  bool checkpoint = true;               // the last converged state at every increment, so that
                                        // `fibra run --resume` can go on from it
  Vec3 momentPoint = Vec3::Zero();      // reactions' moments are taken about this point, mm
  std::vector<ProbeDef> probes;
  std::vector<PlotDef> plots;           // PNGs of history columns, drawn at the end
};

// Contact parameters. Detection (paper section 3) and mechanics (section 4). NaN means "derive
// the default" (docs/SCENE.md gives the rules, which use the radii and element lengths).
enum class FrictionTangent { Consistent, Symmetrised };
// How fibre-fibre normals follow the state: recomputed at every Newton assembly with their
// derivative in the tangent (Newton), or fixed per Newton pass and updated by loop B (Loop), or
// Loop until loop B diverges in an increment, which then starts again with the normals of its
// frictionless parallel elements as Newton (NewtonFrictionless; docs/CONTACT.md section 1.5), or
// NewtonFrictionless where it converges and, once an attempt fails, that attempt again with every
// fibre normal as Newton, kept for the rest of the step where it converges (Auto).
enum class NormalUpdate { Newton, Loop, NewtonFrictionless, Auto };
// The largest Anderson memory of loop B (contact `normal_acceleration`).
inline constexpr int kMaxNormalAcceleration = 10;
// Bounds of ContactDef::stepPenetration (x p_max): below 1 an element could not reach its own
// p_max in one step; above 1000 the limit no longer acts.
inline constexpr double kStepPenetrationMin = 1, kStepPenetrationMax = 1000;

// Settings of the fibre pairs of one pair class, overriding the contact section's (NaN: that
// value): friction, p_max and the penalty bounds. A rule names two contact classes (the same
// twice: pairs within that class), or is the keyword rule `within` (pairs of one class) or
// `between` (pairs of two different classes); a named pair overrides a keyword rule, which
// overrides the contact section.
enum class PairRule { Named, Within, Between };

struct ContactPairDef {
  PairRule rule = PairRule::Named;
  std::array<std::string, 2> classes;  // Named: the two classes (order free)
  double friction = std::numeric_limits<double>::quiet_NaN();        // mu
  double maxPenetration = std::numeric_limits<double>::quiet_NaN();  // p_max, mm
  double penaltyMin = std::numeric_limits<double>::quiet_NaN();  // floor, x section stiffness
  double penaltyMax = std::numeric_limits<double>::quiet_NaN();  // ceiling, x section stiffness
};

struct ContactDef {
  bool enabled = false;
  // --- detection ---
  double proximityDistance = std::numeric_limits<double>::quiet_NaN();  // Delta_prox, mm
  double testPointSpacing = std::numeric_limits<double>::quiet_NaN();   // l_zp, mm
  double thetaCross = std::numeric_limits<double>::quiet_NaN();         // rad
  double thetaParallel = std::numeric_limits<double>::quiet_NaN();      // rad
  bool selfContact = false;                                            // contact on one fibre
  double selfContactSeparation = std::numeric_limits<double>::quiet_NaN();  // min |s1 - s2|, mm
  double skin = std::numeric_limits<double>::quiet_NaN();  // broadphase rebuild distance, mm
  // --- mechanics ---
  double maxPenetration = std::numeric_limits<double>::quiet_NaN();  // p_max per zone, mm
  double regularisation = 0.5;        // p_reg / p_max (eq. 12)
  double initialPenalty = std::numeric_limits<double>::quiet_NaN();  // k of a new zone, N/mm
  double penaltyChange = 10;          // bound on k_new / k_old (and its inverse) per update
  double penaltyMin = 1;              // k >= this x the zone's section stiffness (E R, N/mm)
  double penaltyMax = 1e4;            // k <= this x the zone's section stiffness
  double stepPenetration = 10;        // Newton's step limit, x each zone's p_max: no element
                                      // closes deeper than this in one step nor, already
                                      // closed, by more (docs/METHOD.md "A step limit ...")
  double friction = 0;                // mu between fibres
  double maxReversibleSlip = std::numeric_limits<double>::quiet_NaN();  // g_T,max, mm
  FrictionTangent frictionTangent = FrictionTangent::Consistent;
  int maxDetectionLoops = 3;          // n_A: contact elements fixed point
  int maxNormalLoops = 3;             // n_B: normals fixed point
  ElementPlacement elementPlacement = ElementPlacement::Weighted;  // components/contact_params.h
  int frictionHoldAfter = 2;          // stick/slip changes of an element in a Newton pass before
                                      // its status is held for the pass (0: never; <= 255)
  double frictionHoldTolerance = 0.01;  // a held status is consistent within this relative
                                        // distance of the slip circle (friction force error)
  NormalUpdate normalUpdate = NormalUpdate::Auto;
  int normalAcceleration = 3;         // Anderson memory of loop B on the normals, passes (0: the
                                      // plain update; <= 10)
  bool followCrossings = false;       // frictionless crossings' sections follow the closest
                                      // points in loop B (systems/crossing_follow.h)
  bool facingParticles = true;        // the normal force acts on the outlines' points extremal
                                      // along N, friction on the material particles
                                      // (systems/facing_particles.h)
  std::vector<ContactPairDef> pairs;  // per pair class overrides of friction, p_max, bounds
};

// A rigid tool whose surface touches the fibres through the same contact-friction laws. Its
// motion is rigid: x -> c + R(t)(x - c) + d(t), as for held DOFs.
struct ToolDef {
  std::string name;
  ToolKind kind = ToolKind::Plane;
  Vec3 point = Vec3::Zero();        // plane: a point of it; cylinder: a point of its axis, mm
  Vec3 direction = Vec3::UnitZ();   // plane: normal, towards the fibres; cylinder: axis
  double radius = 0;                // cylinder radius, mm
  bool inside = false;              // cylinder: the fibres are inside it
  Vec3 displacement = Vec3::Zero();  // mm, scaled by displacementTable
  Table displacementTable{{0.0, 1.0}, {0.0, 1.0}};
  bool rotates = false;
  Vec3 axis = Vec3::UnitZ();        // rotation axis
  Vec3 centre = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // default: point
  Table angle;                   // rad
  double friction = 0;              // mu between the tool and the fibres
  double maxPenetration = std::numeric_limits<double>::quiet_NaN();  // default: the contact's
};

// Stabilisation of fibres held only by contact: a spring of `stiffness` from every free DOF of
// the listed fibres (all when empty) to its value at the start of the increment (x0: N/mm;
// directors: stiffness R^2, N mm). It vanishes only as the increments do, so its force at
// convergence is reported with every increment (StepReport::contact.stabilisation).
struct StabilisationDef {
  double stiffness = 0;  // N/mm; 0: off
  std::vector<std::string> fibres;
};

// The linear solver of the Newton systems (systems/linear_solver.h): its strategy and the
// Krylov settings. WorldDef::linearStrategy, when set, overrides `strategy`.
struct SolverDef {
  LinearStrategy strategy = LinearStrategy::Auto;  // auto: by size (docs/RESULTS.md)
  Ordering ordering = Ordering::Auto;               // auto: by size (docs/RESULTS.md)
  KrylovSettings krylov;
  // Newton's cycle damping (systems/newton.h): halved steps once the residuals repeat.
  bool cycleDamping = true;
};

// The prescribed motion of a boundary condition's held DOFs or of a tool (their motion fields).
template <class Def>
PrescribedMotion motionOf(const Def& d) {
  return {d.displacement, d.displacementTable, d.rotates, d.axis, d.centre, d.angle};
}

struct SceneDef {
  std::string units = "mm-N-MPa";
  std::vector<MaterialDef> materials;
  std::vector<FibreDef> fibres;
  std::vector<GroupDef> groups;
  std::vector<BcDef> bcs;
  std::vector<LoadDef> loads;
  std::vector<StepDef> steps;
  ContactDef contact;
  std::vector<ToolDef> tools;
  StabilisationDef stabilisation;
  SolverDef solver;
  OutputDef output;
};

// Whether some step of the scene has `damping` (the viscous continuation): the stabilisation
// store is active and a resume may change the damping only then.
inline bool anyStepDamped(const SceneDef& s) {
  for (const StepDef& st : s.steps)
    if (st.damping > 0) return true;
  return false;
}

}  // namespace fibra
