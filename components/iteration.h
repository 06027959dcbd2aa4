// Small stores that pass values between the driver and the systems of an iteration. No logic.
#pragma once

#include "core/types.h"

namespace fibra {

// What the next run of a stage is for: written by the driver before it runs a stage.
struct IterationInput {
  double time = 0;          // pseudo-time the systems evaluate at (held DOFs, tools, loads)
  bool withTangent = true;  // assemble the tangent K besides the residual r
};

// What the contact systems of one kind (fibre-fibre, fibre-tool) tell the nested loops.
struct ContactLoopStats {
  double normalTurn = 0;     // rad: largest turn of a normal at the last normal update
  double crossingShift = 0;  // mm: largest move of a crossing's section at the same update
                             // (systems/crossing_follow.h; fibre-fibre only)
  double faceShift = 0;      // mm: largest move of an end face's point or of its other section
                             // at the same update (systems/face_follow.h)
  double penaltyChange = 0;  // largest |k_new / k_old - 1| at the last penalty adaptation
  Index zonesAtCeiling = 0;  // zones held at the penalty ceiling deeper than p_max (same update)
};

}  // namespace fibra
