// Contact cliques: the coupling blocks that fibre-fibre contact adds to the tangent's pattern,
// one per pair of beam elements (eI, eJ) that some contact element joins (widened by a
// neighbouring element where a linearised normal reads a node-averaged tangent), and the colouring
// that lets their scatter run in parallel. A cache of the linear system's pattern, rebuilt by
// systems/contact_cliques.h only when the set of pairs changes. No logic here.
#pragma once

#include "core/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace fibra {

struct ContactCliqueStore {
  // --- per contact clique, sorted by key ---
  std::vector<std::uint64_t> key;   // (eI * elements + eJ) * 9 + 3 wI + wJ: the pair of beam
                                    // elements and each side's widening w (0 none, 1 the element
                                    // before, 2 the one after; systems/contact_cliques.h)
  std::vector<std::array<Index, 4>> layout;  // first node and node count of side I, of side J
  std::vector<Index> cliqueFirst;   // first element in `byClique` (size cliques + 1)
  // --- per colour: cliques that share no node, scattered in parallel ---
  std::vector<Index> colourFirst;   // first entry in `colourClique` (size colours + 1)
  std::vector<Index> colourClique;  // contact clique indices, ascending within a colour
  // --- per contact element of the current set ---
  std::vector<Index> clique;        // its contact clique
  std::vector<Index> byClique;      // element indices grouped by clique, ascending
  // --- per store ---
  Index firstClique = 0;            // LinearSystem clique index of contact clique 0
  Index elements = 0;               // beam elements when the keys were made
  std::int64_t rebuilds = 0;        // pattern rebuilds since creation

  Index size() const { return Index(key.size()); }
  Index colours() const { return colourFirst.empty() ? 0 : Index(colourFirst.size()) - 1; }
};

}  // namespace fibra
