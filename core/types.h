// The scalar and vector types every layer shares: indices into flat stores and 3-vectors.
// Units are mm, N, MPa throughout (stresses N/mm^2, moments N mm, energies N mm), angles rad.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace fibra {

using Index = std::int32_t;  // index into a store (fibre, node, element, zone, contact element)
using Vec3 = Eigen::Vector3d;

}  // namespace fibra
