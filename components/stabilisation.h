// Stabilisation store: the springs that hold fibres held only by contact (DESIGN.md 1.4), and
// the viscous continuation of a step (systems/stabilisation.h). No logic here.
#pragma once

#include "core/types.h"

#include <Eigen/Core>
#include <vector>

namespace fibra {

struct StabilisationStore {
  // --- per node ---
  std::vector<double> stiffness;  // k, N/mm (directors: k R^2, N mm); 0 where off
  // --- per DOF ---
  Eigen::VectorXd qStart;         // the state at the start of the increment (mm, -)

  // --- per attempt ---
  double viscous = 0;             // c / dt: the step's damping over the attempt's size, N/mm

  bool active = false;            // some node has k > 0, or some step has damping
};

}  // namespace fibra
