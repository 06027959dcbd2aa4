// State writer system: every node's x0, g1, g2, to restart from or compare against.
//
// Reads  FibreStore (names, node ranges) and a state q. Writes one CSV file, whole or not at
//        all (systems/output_file.h). Serial; the caller's thread.
//
//   fibre,node,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z
//   beam,0,0,0,0,0,1,0,0,0,1
// One row per node, fibres in store order, node the 0-based index within its fibre; x0 in mm,
// directors dimensionless; every value the shortest decimal that reads back exactly.
#pragma once

#include "components/fibres.h"

#include <string>

namespace fibra {

void writeState(const std::string& path, const FibreStore& fibres, const Eigen::VectorXd& q);

}  // namespace fibra
