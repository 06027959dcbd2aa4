// Contact parameters: the scene's ContactDef resolved against the fibres, every NaN replaced by a
// default derived from the radii R and element lengths h (docs/CONTACT.md), once, by
// engine/contact_setup.h; every contact system reads them from here. No logic here.
//
// Detection:
//   Delta_prox(I, J) = reach_I + reach_J        reach_f = 1.5 R_f  (given Delta: Delta / 2)
//       a zone opens where the surface gap is below half the mean diameter; in a hexagonal
//       packing of equal fibres this keeps the 6 touching neighbours (2R) and drops the next
//       ring (2 sqrt(3) R = 3.46 R > 3 R).
//   l_zp(I, J) = min(h_I / 2, R_I + R_J), rounded down to h_I / m (m whole test-point intervals
//       per element): zone ends are resolved to one contact-element spacing (h / 2), and a
//       touching perpendicular crossing (zone length 2 sqrt(Delta^2 - (R_I + R_J)^2) =
//       2.24 (R_I + R_J) on I) holds at least two test points.
//   theta_parallel = 5 deg, theta_cross = 20 deg: below 5 deg the crossing normal t_I x t_J
//       amplifies tangent errors more than 11 times; above 20 deg (3 times) it is reliable, while
//       the centre-to-centre direction deviates from the common normal at the ends of any
//       crossing zone.
//   self-contact separation = max(2 Delta_prox(f, f), h_f) = max(6 R_f, h_f): on a straight or
//       gently bent fibre the closest allowed point stays farther than Delta_prox; at least one
//       element, so that an element is never tested against itself.
//   skin = R_min / 2: candidate boxes are reused while no node moved more than R_min / 4.
// Laws and loops (paper section 4; docs/METHOD.md):
//   p_max = 0.005 R_min, g_T,max = 0.005 R_min; a new zone's penalty k0 = min(E_I R_I, E_J R_J)
//   (a tool zone's: E_f R_f); eq. 13 aims the deepest penetration of a zone at 0.9 p_max and
//   changes k by at most a factor 10 per update, within 1 ... 1e4 x min(E_I R_I, E_J R_J)
//   (systems/penalty_adapter.h gives the reasons).
#pragma once

#include "core/types.h"

#include <vector>

namespace fibra {

// Contact classes of the fibres, the settings of each pair class, and the fibres' level tables
// (docs/SCENE.md: `class`, `levels`, contact `pairs`, forced normals). Resolved once by
// engine/contact_classes.cpp; looked up per zone (systems/zone_penalty.h) and per element under
// forced normals (systems/contact_params.h). No logic here.
struct ContactClasses {
  // --- per fibre ---
  std::vector<int> classOf;          // contact class index (0: the default class "")
  std::vector<Index> firstLevel;     // fibre f's pieces are [firstLevel[f], firstLevel[f + 1])
  // --- per level piece (fibre by fibre, increasing `from`) ---
  std::vector<double> levelFrom;     // reference arc length where the piece starts, mm
  std::vector<double> level;         // the fibre's level on the piece
  // --- per (class a, class b) ---
  int classes = 1;                   // number of classes
  std::vector<int> pairOf;           // pair-class index of classes (a, b): pairOf[a * classes + b]
  // --- per pair class ---
  std::vector<double> mu;            // friction coefficient between fibres
  std::vector<double> pMax;          // p_max of the pair class's zones, mm
  std::vector<double> penaltyMin;    // penalty bounds of its zones, multiples of the zone's
  std::vector<double> penaltyMax;    //   section stiffness (ZoneStore::stiffness)
};

// Where a line contact's elements sit (systems/contact_elements.h, docs/CONTACT.md 1.4):
// Weighted: the two Gauss points of each piece between both fibres' element ends, weighted by
// length (a uniform line load carried as a uniform line force); Lobatto: the pieces' ends and
// midpoints with Simpson's weights (three-point Gauss-Lobatto; also a uniform line force), so the
// element ends of either fibre carry one, cut finer where the gap curves; Paper: equally spaced
// with equal weights (eq. 7).
enum class ElementPlacement : std::uint8_t { Weighted, Lobatto, Paper };

struct ContactParams {
  // --- per fibre ---
  std::vector<double> reach;           // half of its share of Delta_prox, mm
  std::vector<double> selfSeparation;  // min |s' - s| for self-contact (>= h_f), mm
  // --- global ---
  double testPointSpacing = 0;  // l_zp, mm; NaN: per-pair default min(h_I / 2, R_I + R_J)
  double thetaCross = 0;        // rad
  double thetaParallel = 0;     // rad, <= thetaCross
  bool selfContact = false;
  double skin = 0;              // broadphase skin, mm (0: rebuild on any motion)

  // --- which contact the scene has ---
  bool fibres = false;          // fibre-fibre contact is on
  bool tools = false;           // the scene has tools

  // --- contact law (eqs. 12-16) ---
  double pMax = 0;              // p_max of fibre-fibre zones, mm
  double pRegRatio = 0.5;       // p_reg / p_max
  double mu = 0;                // largest friction coefficient between fibres (per zone:
                                // ZoneStore::friction; tools: ToolStore)
  double gMax = 0;              // reversible slip g_T,max, mm
  bool symmetrised = false;     // friction tangent without its non-symmetric part
  int frictionFlips = 2;        // branch changes of an element within a Newton pass before its
                                // stick/slip status is held for the pass (0: never held)
  double frictionTolerance = 0.01;  // a held status is consistent within this relative distance
                                    // of the slip circle |t| = g_T,max (systems/friction_status.h)
  bool newtonNormals = false;   // fibre-fibre normals follow the state inside Newton, linearised
                                // (systems/normal_linearisation.h); false: fixed per pass, loop B
  bool newtonFrictionlessOnly = false;  // with newtonNormals: only the parallel elements (eq. 10
                                        // crossing weight 0) of frictionless pairs, once loop B
                                        // diverged (systems/normal_linearisation.h)
  bool escalateNormals = false;  // with newtonFrictionlessOnly (normal_update "auto"): a failed
                                 // attempt is tried again with allNormals (engine/step_driver.cpp)
  ElementPlacement placement = ElementPlacement::Weighted;  // line contacts' elements (above)
  bool followCrossings = false; // frictionless crossings' sections follow the closest points in
                                // loop B (systems/crossing_follow.h)
  bool facingParticles = false; // the normal force acts on the outlines' points extremal along
                                // N, taken anew at every evaluation; friction on the material
                                // particles
                                // (systems/facing_particles.h; a scene's default is true,
                                // ContactDef in engine/scene.h)
  double toolProximity = 0;     // tool elements are made within R + this, mm (NaN: per fibre,
                                // systems/tool_detection.h)

  // --- penalty per zone (eq. 13) ---
  double initialPenalty = 0;    // k of a new zone, N/mm (NaN: min(E_I R_I, E_J R_J))
  double penaltyChange = 10;    // bound on k_new / k_old (and its inverse) per update
  double penaltyTarget = 0.9;   // the deepest penetration of a zone is aimed at this x p_max
  double penaltyMin = 1;        // bounds on k as multiples of the zone's section stiffness
  double penaltyMax = 1e4;      // (ZoneStore::stiffness, min(E_I R_I, E_J R_J)); per pair class:
                                // ContactClasses, copied into each zone

  // --- nested loops (paper section 4.4) ---
  int maxDetectionLoops = 3;       // n_A
  int maxNormalLoops = 3;          // n_B
  double normalTolerance = 1e-3;   // rad: loop B stops when no normal turns more
  int normalMemory = 3;            // Anderson memory of loop B on the normals (0: plain update;
                                   // systems/normal_acceleration.h)
  double particleTolerance = 1e-3; // x R_min: loop A stops when no centreline moved more
  double penaltyTolerance = 0.1;   // loop A stops when no penalty changes by more
  double stepPenetration = 10;     // x p_max: deepest closing of an element in one Newton step

  // --- contact classes and pair classes ---
  ContactClasses pairs;
  // --- forced normals of the current step (StepDef::forcedNormal; set by the step driver) ---
  Vec3 forcedNormal = Vec3::Zero();  // unit; zero: the normal rules of eq. 10
  // mm, >= 0: the overlap a forced element's gap allows in the current attempt (the step's
  // StepDef::forcedAllowance released linearly to 0 at its end; set by the step driver)
  double forcedAllowance = 0;
  double frictionFactor = 1;  // the current step's factor on every mu (StepDef::frictionFactor)
  bool unstableNormals = false;  // loop B's update of the normals diverged in this attempt (set
                                 // by the contact loops, cleared by the step driver)
  bool allNormals = false;  // the attempt in progress linearises every linearisable fibre
                            // normal, as with "newton" (escalateNormals; set by the step driver
                            // before each attempt)
};

}  // namespace fibra
