// Sparse pattern system: numbers the free DOFs and builds the tangent's fixed CSC pattern with
// the scatter map of every clique (a set of nodes whose DOFs are all coupled: a beam element,
// or the two elements of a contact element).
//
// Reads  FibreStore (sizes), the held DOFs (ConstraintStore::dof), the cliques.
// Writes LinearSystem (equation, K pattern with zero values, cliqueFirst, positions, revision).
// Runs when the topology changes, never per iteration: scattering into a fixed pattern is ~46x
// cheaper than rebuilding a matrix from triplets. The positions loop is parallel over cliques.
//
// Pattern: entry (I, J) exists iff DOFs I and J belong to nodes that share a clique. Equations
// are numbered in DOF order, so every column's rows come out sorted.
#pragma once

#include "components/boundary.h"
#include "components/linear_system.h"

namespace fibra {

// Cliques as lists of global node indices.
struct CliqueList {
  std::vector<Index> first;  // per clique: first entry in `nodes`; first.size() = cliques + 1
  std::vector<Index> nodes;  // per entry: global node
  Index size() const { return Index(first.size()) - 1; }
  void add(Index firstNode, int count) { addPair(firstNode, count, 0, 0); }
  // One clique of two node ranges (the two elements of a contact), in that order.
  void addPair(Index firstA, int countA, Index firstB, int countB) {
    if (first.empty()) first.push_back(0);
    for (int i = 0; i < countA; ++i) nodes.push_back(firstA + i);
    for (int i = 0; i < countB; ++i) nodes.push_back(firstB + i);
    first.push_back(Index(nodes.size()));
  }
};

// One clique per beam element, in element order.
CliqueList beamCliques(const FibreStore& fibres);

// Numbers the free DOFs (held DOFs get -1).
void numberEquations(const FibreStore& fibres, const ConstraintStore& constraints,
                     LinearSystem& ls);

// Builds K's pattern (upper triangle when ls.symmetric) and the cliques' scatter maps.
void buildPattern(const FibreStore& fibres, const CliqueList& cliques, LinearSystem& ls);

}  // namespace fibra
