// Contact mechanics store: the state of the fibre-fibre contact elements that the laws need,
// beside the geometric ContactElementStore of the detection. Filled when the contact elements
// are (re)generated (engine/contact_loops.cpp), read and written by the contact assembler. No
// logic here; see systems/contact_assembler.h.
#pragma once

#include "components/fibres.h"
#include "components/particle_weights.h"

#include <cstdint>
#include <vector>

namespace fibra {

struct ContactMechanicsStore {
  // --- per contact element (same order as the ContactElementStore) ---
  std::vector<ParticleWeights> sideI, sideJ;  // particles as weights on their elements' DOFs
  std::vector<Index> clique;      // LinearSystem clique of the element pair (eI, eJ)
  std::vector<Index> zone;        // zone of the element (penalty)
  std::vector<Vec3> normal;       // N, unit, from J to I (fixed during Newton)
  std::vector<Vec3> d0;           // x^I - x^J at the friction reference state, mm
  std::vector<Vec3> gRev0;        // reversible slip at that state, mm
  // results of the last assembly
  std::vector<double> gap;          // g_N, mm
  std::vector<double> normalForce;  // R_N, N
  std::vector<Vec3> force;          // force on particle I (J gets the opposite), N
  std::vector<Eigen::Matrix3d> stiffness;  // -d force / d(x^I - x^J), N/mm
  std::vector<Vec3> gRev;           // reversible slip, mm
  std::vector<std::uint8_t> slip;   // 1 when sliding

  // --- per zone ---
  std::vector<double> penalty;      // k, N/mm (eq. 13)

  // --- per colour: cliques that share no node, scattered in parallel ---
  std::vector<std::vector<Index>> colourCliques;  // contact cliques of each colour
  std::vector<Index> cliqueFirst;   // per contact clique: first element in `byClique`
  std::vector<Index> byClique;      // element indices grouped by clique (ascending)
  Index firstContactClique = 0;     // LinearSystem clique index of contact clique 0

  Index size() const { return Index(normal.size()); }
};

}  // namespace fibra
