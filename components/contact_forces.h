// Contact force store: what the contact law (systems/contact_law.h) gives each contact element
// at the last evaluation, for fibre-fibre and fibre-tool elements alike (one instance each, in
// the order of their element store). No logic here.
#pragma once

#include "core/types.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace fibra {

struct ContactForceStore {
  // --- per contact element ---
  std::vector<double> gap;          // g_N = (x^I - x^J) . N, mm (negative: penetration)
  std::vector<double> normalForce;  // R_N >= 0, N
  std::vector<Vec3> force;          // f on particle I (J or the tool gets -f), N
  std::vector<Eigen::Matrix3d> stiffness;  // S = -df/d(x^I - x^J), N/mm
  std::vector<Vec3> gRev;           // reversible slip, mm
  std::vector<std::uint8_t> slip;   // 1 when the trial slip left the disc of radius g_T,max

  Index size() const { return Index(gap.size()); }
};

}  // namespace fibra
