// Energy balance store: the generalised forces on the fibres of the last converged state, one
// entry per DOF (N on x0, N mm on the directors), kept so that the next increment's work is a
// trapezoid between both ends (systems/energy_balance.h); and the balance since t = 0. No logic.
#pragma once

#include "core/report.h"

#include <Eigen/Core>

namespace fibra {

struct EnergyForces {
  Eigen::VectorXd external;  // dead loads f_ext
  Eigen::VectorXd supports;  // forces of the held DOFs' supports: r on held DOFs, 0 elsewhere
  Eigen::VectorXd normal;    // fibre-fibre contact, normal part: R_N N on I, -R_N N on J
  Eigen::VectorXd friction;  // friction part of fibre-fibre and fibre-tool contact
  Eigen::VectorXd tools;     // fibre-tool contact, normal part
};

struct EnergyStore {
  EnergyForces last;         // at the last converged state
  double strainAtStart = 0;  // U(q) at t = 0, N mm
  EnergyBalance balance;     // since t = 0
};

}  // namespace fibra
