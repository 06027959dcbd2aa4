#include "systems/contact_cliques.h"

#include "systems/sparse_pattern.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <iterator>

namespace fibra {
namespace {

std::uint64_t keyOf(const ContactElementStore& el, Index e, Index elements) {
  return std::uint64_t(el.sideI[e].element) * std::uint64_t(elements) +
         std::uint64_t(el.sideJ[e].element);
}

// The pattern: beam cliques, then the contact cliques in key order.
void rebuildPattern(const FibreStore& fs, const ContactCliqueStore& c, LinearSystem& ls) {
  CliqueList cliques = beamCliques(fs);
  const Index nE = fs.elements();
  for (const std::uint64_t k : c.key) {
    const Index eI = Index(k / nE), eJ = Index(k % nE);
    cliques.addPair(fs.elementFirstNode[eI], fs.order[fs.elementFibre[eI]] + 1,
                    fs.elementFirstNode[eJ], fs.order[fs.elementFibre[eJ]] + 1);
  }
  buildPattern(fs, cliques, ls);
}

// Greedy colouring of every clique in key order; colours listed with ascending cliques.
void colour(const FibreStore& fs, ContactCliqueStore& c) {
  const Index nE = fs.elements(), n = c.size();
  std::vector<std::vector<Index>> nodeColours(fs.nodes());
  std::vector<Index> forbiddenBy, colourOf(n);
  for (Index q = 0; q < n; ++q) {
    Index nodes[6];
    int count = 0;
    for (const Index e : {Index(c.key[q] / nE), Index(c.key[q] % nE)})
      for (int a = 0; a <= fs.order[fs.elementFibre[e]]; ++a) nodes[count++] = fs.elementFirstNode[e] + a;
    for (int i = 0; i < count; ++i)
      for (const Index col : nodeColours[nodes[i]]) forbiddenBy[col] = q;
    Index col = 0;
    while (col < Index(forbiddenBy.size()) && forbiddenBy[col] == q) ++col;
    if (col == Index(forbiddenBy.size())) forbiddenBy.push_back(-1);
    colourOf[q] = col;
    for (int i = 0; i < count; ++i) nodeColours[nodes[i]].push_back(col);
  }
  const Index colours = Index(forbiddenBy.size());
  c.colourFirst.assign(colours + 1, 0);
  for (Index q = 0; q < n; ++q) ++c.colourFirst[colourOf[q] + 1];
  for (Index k = 0; k < colours; ++k) c.colourFirst[k + 1] += c.colourFirst[k];
  c.colourClique.resize(n);
  std::vector<Index> next(c.colourFirst.begin(), c.colourFirst.end() - 1);
  for (Index q = 0; q < n; ++q) c.colourClique[next[colourOf[q]]++] = q;
}

}  // namespace

void bindContactCliques(const FibreStore& fs, const ContactElementStore& el,
                        ContactCliqueStore& c, LinearSystem& ls) {
  const Index nE = fs.elements(), n = el.size();
  if (c.elements != nE) {
    c.key.clear();
    c.elements = nE;
  }
  std::vector<std::uint64_t> keys(n);
  tbb::parallel_for(Index(0), n, [&](Index e) { keys[e] = keyOf(el, e, nE); });
  std::vector<std::uint64_t> present = keys;
  std::sort(present.begin(), present.end());
  present.erase(std::unique(present.begin(), present.end()), present.end());

  const bool grows = !std::includes(c.key.begin(), c.key.end(), present.begin(), present.end());
  if (grows) {
    std::vector<std::uint64_t> merged;
    std::set_union(c.key.begin(), c.key.end(), present.begin(), present.end(),
                   std::back_inserter(merged));
    c.key.swap(merged);
  }
  const bool prune = c.key.size() > 2 * present.size() + 64;
  if (prune) c.key = present;
  if (grows || prune || c.colourFirst.empty()) {
    c.firstClique = nE;
    rebuildPattern(fs, c, ls);
    colour(fs, c);
    ++c.rebuilds;
  }

  c.clique.resize(n);
  tbb::parallel_for(Index(0), n, [&](Index e) {
    c.clique[e] = Index(std::lower_bound(c.key.begin(), c.key.end(), keys[e]) - c.key.begin());
  });
  c.cliqueFirst.assign(c.size() + 1, 0);
  for (Index e = 0; e < n; ++e) ++c.cliqueFirst[c.clique[e] + 1];
  for (Index q = 0; q < c.size(); ++q) c.cliqueFirst[q + 1] += c.cliqueFirst[q];
  c.byClique.resize(n);
  std::vector<Index> next(c.cliqueFirst.begin(), c.cliqueFirst.end() - 1);
  for (Index e = 0; e < n; ++e) c.byClique[next[c.clique[e]]++] = e;
}

}  // namespace fibra
