// Boundary stores: named node groups, held DOFs and dead loads, resolved from the scene's Defs.
// No logic here; targets and load vectors are evaluated by systems/boundary.h.
#pragma once

#include "components/fibres.h"
#include "engine/scene.h"

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
  std::vector<BcDef> def;
  std::vector<Index> group;  // GroupStore index
  // --- per held DOF (sorted by DOF) ---
  std::vector<Index> dof;    // global DOF index, 9 node + component
  std::vector<Index> owner;  // the boundary condition that holds it
};

struct LoadStore {
  // --- per load ---
  std::vector<LoadDef> def;
  std::vector<Index> group;         // GroupStore index
  std::vector<Index> elementFirst;  // line loads: first entry in `elements` (size loads + 1)
  // --- per loaded element ---
  std::vector<Index> elements;      // elements a line load acts on
};

}  // namespace fibra
