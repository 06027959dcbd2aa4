// Boundary stores: named node groups, held DOFs and dead loads, resolved from the scene.
// No logic here; targets and load vectors are evaluated by systems/boundary.h.
#pragma once

#include "components/fibres.h"
#include "components/motion.h"

#include <string>
#include <vector>

namespace fibra {

struct GroupStore {
  // --- per group ---
  std::vector<std::string> name;
  std::vector<Index> first;  // first member in `members`
  std::vector<Index> count;  // members of the group
  // --- per member ---
  std::vector<Index> members;  // global node index

  Index size() const { return Index(name.size()); }
};

struct ConstraintStore {
  // --- per boundary condition ---
  std::vector<PrescribedMotion> motion;  // of the held DOFs (centre NaN: each node's X0)
  std::vector<Index> group;              // GroupStore index
  // --- per held DOF (sorted by DOF) ---
  std::vector<Index> dof;    // global DOF index, 9 node + component
  std::vector<Index> owner;  // the boundary condition that holds it

  Index size() const { return Index(group.size()); }
};

// Dead loads. Force: F (N) on each node of the group. Moment: M (N mm) on each node, a torque
// |M| about the fixed axis M/|M|. LineForce: w (N/mm) per unit reference length on every
// element whose nodes all belong to the group.
enum class LoadKind { Force, Moment, LineForce };

struct LoadStore {
  // --- per load ---
  std::vector<LoadKind> kind;
  std::vector<Vec3> vector;         // N, N mm or N/mm (by kind), scaled by table
  std::vector<Table> table;         // -
  std::vector<Index> group;         // GroupStore index
  std::vector<Index> elementFirst;  // line loads: first entry in `elements` (size loads + 1)
  // --- per loaded element ---
  std::vector<Index> elements;      // elements a line load acts on

  Index size() const { return Index(kind.size()); }
};

}  // namespace fibra
