// Contact snapshot: the contact elements of one converged state, flattened for output (VTU,
// benches). Filled by World::contactSnapshot(); no logic.
#pragma once

#include "components/fibres.h"

#include <cstdint>
#include <vector>

namespace fibra {

struct ContactSnapshot {
  // --- per contact element: fibre-fibre first, then fibre-tool ---
  std::vector<Vec3> particleI;      // x^I, the particle on fibre I, mm
  std::vector<Vec3> particleJ;      // x^J, the particle on fibre J, or the tool surface point
                                    // x^I - g N below a fibre-tool particle, mm
  std::vector<Vec3> normal;         // N, unit, from J (or the tool) to I
  std::vector<double> gap;          // g_N, mm (< 0: penetration)
  std::vector<double> normalForce;  // R_N, N
  std::vector<double> length;       // the element's share of the contact line, mm (0: a point,
                                    // e.g. on an end face); line force = R_N / length, N/mm
  std::vector<Vec3> friction;       // friction force on I, N (in the plane normal to N)
  std::vector<std::uint8_t> slip;   // 1: sliding (friction >= 99% of mu R_N, kSlidingShare)
  std::vector<std::uint8_t> tool;   // 0: fibre-fibre, 1: fibre-tool
  std::vector<Index> fibreI, fibreJ;  // fibre indices (fibreJ: the tool's index for tools)
  std::vector<Index> zone;          // the element's proximity zone in this state's set (-1: tool)
  std::vector<std::uint8_t> refined;  // 1: its zone carries Lobatto elements because the
                                      // acceptance found an overlap between its elements
                                      // (ZoneStore::refined; 0 for tools)

  Index size() const { return Index(normal.size()); }
};

}  // namespace fibra
