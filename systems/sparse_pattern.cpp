#include "systems/sparse_pattern.h"

#include "core/sparse_room.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace fibra {

CliqueList beamCliques(const FibreStore& fs) {
  CliqueList c;
  c.first.reserve(fs.elements() + 1);
  for (Index e = 0; e < fs.elements(); ++e) c.add(fs.elementFirstNode[e], fs.order[fs.elementFibre[e]] + 1);
  if (c.first.empty()) c.first.push_back(0);
  return c;
}

void numberEquations(const FibreStore& fs, const ConstraintStore& cs, LinearSystem& ls) {
  ls.equation.assign(size_t(kNodeDofs) * fs.nodes(), 0);
  for (Index d : cs.dof) ls.equation[d] = -1;
  ls.dofOf.clear();
  for (Index d = 0; d < Index(ls.equation.size()); ++d) {
    if (ls.equation[d] < 0) continue;
    ls.equation[d] = Index(ls.dofOf.size());
    ls.dofOf.push_back(d);
  }
  ls.freeCount = Index(ls.dofOf.size());
}

namespace {

// Node adjacency (CSR, sorted, self included) from the cliques.
void nodeAdjacency(Index nodes, const CliqueList& cl, std::vector<Index>& start,
                   std::vector<Index>& adj) {
  std::vector<std::pair<Index, Index>> pairs;
  for (Index c = 0; c < cl.size(); ++c)
    for (Index i = cl.first[c]; i < cl.first[c + 1]; ++i)
      for (Index j = cl.first[c]; j < cl.first[c + 1]; ++j) pairs.emplace_back(cl.nodes[i], cl.nodes[j]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  start.assign(nodes + 1, 0);
  adj.resize(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    ++start[pairs[k].first + 1];
    adj[k] = pairs[k].second;
  }
  for (Index n = 0; n < nodes; ++n) start[n + 1] += start[n];
}

}  // namespace

void buildPattern(const FibreStore& fs, const CliqueList& cl, LinearSystem& ls) {
  std::vector<Index> start, adj;
  nodeAdjacency(fs.nodes(), cl, start, adj);

  // Columns in equation order; rows: free DOFs of adjacent nodes (upper part if symmetric).
  // Counted, then written into K's own storage (core/sparse_room.h), all values 0.
  const auto forEachRow = [&](Index n, Index J, auto&& row) {
    for (Index k = start[n]; k < start[n + 1]; ++k)
      for (int r = 0; r < kNodeDofs; ++r) {
        const Index I = ls.equation[kNodeDofs * adj[k] + r];
        if (I >= 0 && (!ls.symmetric || I <= J)) row(I);
      }
  };
  Index nnz = 0;
  for (Index n = 0; n < fs.nodes(); ++n)
    for (int c = 0; c < kNodeDofs; ++c)
      if (const Index J = ls.equation[kNodeDofs * n + c]; J >= 0) forEachRow(n, J, [&](Index) { ++nnz; });
  roomFor(ls.K, ls.freeCount, ls.freeCount, nnz);
  int* outer = ls.K.outerIndexPtr();
  int* inner = ls.K.innerIndexPtr();
  Index at = 0;
  outer[0] = 0;
  for (Index n = 0; n < fs.nodes(); ++n)
    for (int c = 0; c < kNodeDofs; ++c) {
      const Index J = ls.equation[kNodeDofs * n + c];
      if (J < 0) continue;
      forEachRow(n, J, [&](Index I) { inner[at++] = int(I); });
      outer[J + 1] = int(at);
    }
  std::fill_n(ls.K.valuePtr(), nnz, 0.0);

  ls.diagonal.resize(ls.freeCount);
  for (Index J = 0; J < ls.freeCount; ++J) {
    const int* it = std::lower_bound(ls.K.innerIndexPtr() + outer[J], ls.K.innerIndexPtr() + outer[J + 1], J);
    ls.diagonal[J] = Index(it - ls.K.innerIndexPtr());
  }

  // Scatter maps: binary search of each clique entry's row in its column.
  ls.cliqueFirst.assign(cl.size() + 1, 0);
  for (Index c = 0; c < cl.size(); ++c) {
    const Index n = kNodeDofs * (cl.first[c + 1] - cl.first[c]);
    ls.cliqueFirst[c + 1] = ls.cliqueFirst[c] + n * n;
  }
  const size_t entries = size_t(ls.cliqueFirst.back());  // room kept, as K's (core/sparse_room.h)
  if (ls.positions.capacity() < entries) ls.positions.reserve(entries + entries / 4);
  ls.positions.resize(entries);
  const int* op = ls.K.outerIndexPtr();
  const int* ip = ls.K.innerIndexPtr();
  tbb::parallel_for(Index(0), cl.size(), [&](Index c) {
    const Index nn = cl.first[c + 1] - cl.first[c], n = kNodeDofs * nn;
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j < n; ++j) {
        const Index I = ls.equation[kNodeDofs * cl.nodes[cl.first[c] + i / kNodeDofs] + i % kNodeDofs];
        const Index J = ls.equation[kNodeDofs * cl.nodes[cl.first[c] + j / kNodeDofs] + j % kNodeDofs];
        Index pos = -1;
        if (I >= 0 && J >= 0 && (!ls.symmetric || I <= J))
          pos = Index(std::lower_bound(ip + op[J], ip + op[J + 1], I) - ip);
        ls.positions[ls.cliqueFirst[c] + i * n + j] = pos;
      }
  });
  ++ls.revision;
}

}  // namespace fibra
