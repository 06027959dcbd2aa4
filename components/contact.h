// Contact detection stores (paper section 3): the proximity zones of a detection call and the
// contact elements generated in them, with what the contact laws need of them (penalty per
// zone, particle weights and friction reference per element). Flat arrays, no logic; filled by
// the systems of systems/contact_detection.h, read by the contact laws (the forces live in
// components/contact_forces.h).
//
// Canonical order (identical for every thread count): zones sorted by (fibreI, fibreJ, sI1),
// elements grouped by zone in zone order, then by k (increasing zeta).
//
// Zone identity across detection calls (systems/zone_identity.h): a zone of this call matches a
// zone of the previous call when they have the same fibre pair and their intervals overlap, or
// nearly overlap (gap at most one test-point spacing), on BOTH fibres. `previous` is the
// best-overlapping match (-1: none). The previous zone's `id` goes to the one matching zone that
// overlaps it best; every other zone gets a fresh id. Hence a zone that splits keeps its id on
// its largest part, the other parts get new ids with `previous` pointing at the parent; zones
// that merge take the id of the part they overlap best; a zone with no match vanishes.
#pragma once

#include "components/fibres.h"
#include "components/particle_weights.h"

#include <cstdint>
#include <vector>

namespace fibra {

struct ZoneStore {
  // --- per zone ---
  std::vector<Index> fibreI;         // fibre carrying the test points (fibreI <= fibreJ)
  std::vector<Index> fibreJ;         // opposite fibre (== fibreI for self-contact)
  std::vector<double> sI1, sI2;      // reference arc length interval on I, sI1 <= sI2, mm
  std::vector<double> sJ1, sJ2;      // closest points on J of the test points sI1, sI2, mm
                                     // (paired with sI1, sI2: sJ1 > sJ2 when J runs backwards)
  std::vector<double> minDistance;   // smallest centreline distance over the zone's test points, mm
  std::vector<Index> testPoints;     // test points of I in the zone (>= 1)
  std::vector<std::uint64_t> id;     // persistent identity, kept across calls (> 0)
  std::vector<Index> previous;       // matching zone of the previous call's store, -1 if new
  std::vector<double> intermediateLength;  // L_int, length of the intermediate geometry, mm
  std::vector<Index> firstElement;   // first contact element of the zone (ContactElementStore)
  std::vector<Index> elementCount;   // Nc, contact elements of the zone (>= 1)
  std::vector<double> penalty;       // k of the zone's elements, N/mm (eq. 13; carried from the
                                     // `previous` zone, systems/zone_penalty.h)
  std::vector<double> pMax;          // p_max the zone's penalty aims at, mm (its pair class's)
  std::vector<double> friction;      // mu of the zone's elements (its pair class's)
  std::vector<double> penaltyMin;    // bounds on k, multiples of `stiffness` (its pair class's)
  std::vector<double> penaltyMax;
  std::vector<double> stiffness;     // section stiffness min(E_I R_I, E_J R_J), N/mm: the scale
                                     // of the penalty's bounds (ContactParams::penaltyMin/Max)
  std::vector<std::uint8_t> refined;  // 1: a line contact placed with Lobatto elements whatever
                                     // `element_placement` says: the acceptance found the fibres
                                     // overlapping between its elements (engine/contact_loops.cpp);
                                     // carried from the `previous` zone

  // --- per store ---
  std::uint64_t nextId = 1;          // next fresh zone id (ids below it were handed out)

  Index size() const { return Index(fibreI.size()); }
};

// Bits of ContactElementStore::fallback: which documented degenerate-case rule produced it.
enum ContactFallback : std::uint8_t {
  kFallbackSectionI = 1,     // eq. 8 ill-posed on I: section of I closest to J's section centre
  kFallbackSectionJ = 2,     // eq. 8 ill-posed on J: section of J closest to I's section centre
  kFallbackTangent = 4,      // intermediate tangent undefined: bisector of the fibre tangents
  kFallbackParticleI = 8,    // other centre on I's axis: particle I from the normal direction
  kFallbackParticleJ = 16,   // same on J
  kFallbackNormal = 32,      // centres coincide and fibres parallel: N from the particles
  kEndFaceI = 64,            // I's section is an end of I and J lies beyond it: I's particle on
                             // the flat end face, N normal to J's axis (systems/contact_elements.h)
  kEndFaceJ = 128,           // the same with I and J swapped
};

struct ContactElementStore {
  // --- per contact element ---
  std::vector<Index> zone;        // owning zone (ZoneStore index)
  std::vector<double> zeta;       // relative abscissa on the intermediate geometry, in [0, 1]
  std::vector<double> length;     // the element's share of the intermediate geometry, mm (its
                                  // line force is normal force / length)
  std::vector<double> weight;     // length / mean length over the zone's elements (mean 1): scales
                                  // the zone's penalty on this element
  // side I: the material particle (fibre, s, xi1, xi2); x = x0(s) + xi1 g1(s) + xi2 g2(s)
  std::vector<Index> fibreI;      // fibre of particle I
  std::vector<double> sI;         // reference arc length of the section of I, mm
  std::vector<double> xiI1, xiI2; // section coordinates of particle I, mm (|xi| = R_I)
  // side J
  std::vector<Index> fibreJ;
  std::vector<double> sJ;         // mm
  std::vector<double> xiJ1, xiJ2; // mm (|xi| = R_J)
  // eqs. 10-11 at the state of the last normal update
  std::vector<Vec3> normal;        // N, unit, from J to I: N . (x0I - x0J) >= 0
  std::vector<double> gap;         // gN = (xI - xJ) . N, mm (negative: penetration)
  std::vector<double> theta;       // angle between the centreline tangents, rad, in [0, pi/2]
  std::vector<double> crossWeight; // weight of the crossing normal in the blend, in [0, 1]
  std::vector<std::uint8_t> fallback;  // ContactFallback bits
  std::vector<std::int8_t> forced;     // forced normal (paper section 5.2.1): +1 N = +D (I over
                                       // J), -1 N = -D, 0 eqs. 10-11; set at generation, kept by
                                       // loop B (systems/contact_elements.h)
  std::vector<std::uint8_t> crossing;  // 1: a point element placed at the closest points of two
                                       // crossing centrelines; frictionless, its sections follow
                                       // them in Newton (systems/crossing_follow.h)
  // the particles as weights on their elements' DOFs (systems/contact_particles.h)
  std::vector<ParticleWeights> sideI, sideJ;
  // friction reference (systems/friction_reference.h): the state the slip is measured from
  std::vector<Vec3> d0;            // x^I - x^J at the reference state, mm
  std::vector<Vec3> gRev0;         // reversible slip at that state (normal to N), mm

  Index size() const { return Index(zone.size()); }
};

}  // namespace fibra
