// A material particle of a fibre as weights on its element's DOFs (systems/particle.h builds
// them): x = sum_a c[a][0] x0_a + c[a][1] g1_a + c[a][2] g2_a over the element's nodes. A column
// type of the contact stores; no logic here.
#pragma once

#include "core/types.h"

#include <array>

namespace fibra {

struct ParticleWeights {
  Index element = -1;
  Index firstNode = 0;  // the element's first node
  int nodes = 0;        // 2 or 3
  std::array<std::array<double, 3>, 3> c{};  // c[a][f]: weight of node a's field f (0 x0,
                                              // 1 g1, 2 g2), - or mm
};

}  // namespace fibra
