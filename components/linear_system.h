// Linear system store: the equation numbering, the sparse tangent with its fixed pattern, the
// residual, and the maps that scatter element blocks into the pattern. Rebuilt only when the
// topology changes (held DOFs, or the coupling cliques of contact); values are overwritten
// every Newton iteration. No logic here; see systems/sparse_pattern.h.
#pragma once

#include "components/fibres.h"

#include <Eigen/SparseCore>
#include <vector>

namespace fibra {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

struct LinearSystem {
  // --- per DOF (9 per node) ---
  std::vector<Index> equation;  // equation number of a free DOF, -1 for a held DOF
  Index freeCount = 0;          // number of equations
  // --- per equation ---
  std::vector<Index> dofOf;     // the DOF of an equation
  std::vector<Index> diagonal;  // index into K.valuePtr() of the equation's diagonal entry

  // --- the tangent: upper triangle (symmetric) or full (non-symmetric), CSC, free DOFs ---
  bool symmetric = true;
  SparseMatrix K;               // d r / d q on free DOFs; pattern fixed, values overwritten
  Eigen::VectorXd r;            // residual f_int - f_ext on every DOF (held ones = reactions), N
  Eigen::VectorXd fext;         // external load on every DOF (dead forces, moment loads), N

  // --- scatter maps: for a clique of nodes (a beam element), its dense block's entries ---
  // positions[cliqueFirst[c] + i * n + j] = index into K.valuePtr() of local (i, j),
  // -1 when the entry is not stored (a held DOF, or below the diagonal when symmetric);
  // n = 9 * nodes of the clique. Beam element e is clique e.
  std::vector<Index> cliqueFirst;  // per clique
  std::vector<Index> positions;    // per clique entry
  Index revision = 0;              // bumped whenever the pattern changes
};

}  // namespace fibra
