// Fibre store: the fibres of a world, their nodes and their beam elements, as flat arrays.
//
// Every node carries nine DOFs, [x0 (3) | g1 (3) | g2 (3)]: the centroid of its cross-section
// (mm) and the two cross-section directors (dimensionless; orthonormal and orthogonal to the
// centreline tangent in the reference state). The current and reference states are two flat
// vectors of 9 values per node, node-major, so that the solver's unknown vector is `q` itself.
//
// A fibre owns a contiguous range of nodes and a contiguous range of elements of one order
// (1: two-node linear, 2: three-node quadratic). Elements have equal reference arc length, so
// element i of a fibre spans s in [i h, (i+1) h], h = length / elementCount, and uses nodes
// elementFirstNode[e] + 0..order. No logic lives here.
#pragma once

#include "core/types.h"

#include <string>
#include <vector>

namespace fibra {

constexpr int kNodeDofs = 9;  // x0, g1, g2

struct FibreStore {
  // --- per fibre ---
  std::vector<std::string> name;
  std::vector<Index> firstNode;     // first node of the fibre
  std::vector<Index> nodeCount;     // nodes of the fibre: order * elementCount + 1
  std::vector<Index> firstElement;  // first element of the fibre
  std::vector<Index> elementCount;  // elements of the fibre
  std::vector<int> order;           // 1 linear, 2 quadratic
  std::vector<double> radius;       // reference cross-section radius, mm
  std::vector<double> length;       // reference arc length, mm
  std::vector<Index> material;      // index into MaterialStore

  // --- per node ---
  std::vector<Index> nodeFibre;     // owning fibre
  std::vector<double> nodeS;        // reference arc length from the fibre's start, mm
  Eigen::VectorXd q;                // current [x0 g1 g2] per node (mm, -, -)
  Eigen::VectorXd qRef;             // reference [X0 G1 G2] per node (mm, -, -)

  // --- per element ---
  std::vector<Index> elementFibre;      // owning fibre
  std::vector<Index> elementFirstNode;  // element nodes: elementFirstNode + 0..order

  Index fibres() const { return Index(name.size()); }
  Index nodes() const { return Index(nodeFibre.size()); }
  Index elements() const { return Index(elementFibre.size()); }
};

// The hyperelastic law of a material's sections (systems/beam_section.h, systems/section_law.h).
enum class MaterialLaw {
  SaintVenantKirchhoff,  // W quadratic in E: a constant section stiffness (the paper's)
  NeoHookean             // compressible neo-Hookean: stable under large compression
};

// Per-material constants.
struct MaterialStore {
  std::vector<std::string> name;
  std::vector<double> youngModulus;   // E, MPa
  std::vector<double> poissonRatio;   // nu, -
  std::vector<double> bendingFactor;  // scales the bending stiffness EI (paper Table 1: 0.12), -
  std::vector<double> torsionFactor;  // scales the torsion stiffness GJ, -
  std::vector<MaterialLaw> law;       // the sections' law (Saint Venant-Kirchhoff by default)

  Index size() const { return Index(name.size()); }
};

// Views of one node's blocks inside a flat [x0 g1 g2] vector.
inline auto x0Of(Eigen::VectorXd& q, Index n) { return q.segment<3>(kNodeDofs * n); }
inline auto g1Of(Eigen::VectorXd& q, Index n) { return q.segment<3>(kNodeDofs * n + 3); }
inline auto g2Of(Eigen::VectorXd& q, Index n) { return q.segment<3>(kNodeDofs * n + 6); }
inline auto x0Of(const Eigen::VectorXd& q, Index n) { return q.segment<3>(kNodeDofs * n); }
inline auto g1Of(const Eigen::VectorXd& q, Index n) { return q.segment<3>(kNodeDofs * n + 3); }
inline auto g2Of(const Eigen::VectorXd& q, Index n) { return q.segment<3>(kNodeDofs * n + 6); }

}  // namespace fibra
