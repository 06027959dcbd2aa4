#include "systems/contact_cliques.h"

#include "systems/contact_geometry.h"
#include "systems/contact_params.h"
#include "systems/sparse_pattern.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <iterator>

namespace fibra {
namespace {

// The widening of one side (0 none, 1 the element before the particle's, 2 the one after): the
// other element of a node-averaged section tangent, with linearised normals only.
std::uint64_t widening(const FibreStore& fs, const ContactParams& p, Index f, double s,
                       Index element) {
  if (!normalsInNewton(p)) return 0;
  const Index node = interiorNodeAt(fs, f, s);
  if (node < 0) return 0;
  const Index after = fs.firstElement[f] + node;  // the element starting at the node
  return element == after ? 1 : element == after - 1 ? 2 : 0;
}

std::uint64_t keyOf(const FibreStore& fs, const ContactParams& p, const ContactElementStore& el,
                    Index e, Index elements) {
  const std::uint64_t pair = std::uint64_t(el.sideI[e].element) * std::uint64_t(elements) +
                             std::uint64_t(el.sideJ[e].element);
  return pair * 9 + 3 * widening(fs, p, el.fibreI[e], el.sI[e], el.sideI[e].element) +
         widening(fs, p, el.fibreJ[e], el.sJ[e], el.sideJ[e].element);
}

// The nodes of a clique: first node and count of side I, of side J.
std::array<Index, 4> layoutOf(const FibreStore& fs, std::uint64_t key) {
  const Index nE = fs.elements();
  const std::uint64_t pair = key / 9;
  const Index e[2] = {Index(pair / nE), Index(pair % nE)};
  const int w[2] = {int(key % 9 / 3), int(key % 3)};
  std::array<Index, 4> out;
  for (int s = 0; s < 2; ++s) {
    const int order = fs.order[fs.elementFibre[e[s]]];
    out[2 * s] = fs.elementFirstNode[e[s]] - (w[s] == 1 ? order : 0);
    out[2 * s + 1] = order + 1 + (w[s] ? order : 0);
  }
  return out;
}

// The pattern: beam cliques, then the contact cliques in key order.
void rebuildPattern(const FibreStore& fs, const ContactCliqueStore& c, LinearSystem& ls) {
  CliqueList cliques = beamCliques(fs);
  for (const std::array<Index, 4>& l : c.layout) cliques.addPair(l[0], int(l[1]), l[2], int(l[3]));
  buildPattern(fs, cliques, ls);
}

// Greedy colouring of every clique in key order; colours listed with ascending cliques.
void colour(const FibreStore& fs, ContactCliqueStore& c) {
  const Index n = c.size();
  std::vector<std::vector<Index>> nodeColours(fs.nodes());
  std::vector<Index> forbiddenBy, colourOf(n);
  for (Index q = 0; q < n; ++q) {
    Index nodes[10];
    int count = 0;
    for (int s = 0; s < 2; ++s)
      for (Index a = 0; a < c.layout[q][2 * s + 1]; ++a) nodes[count++] = c.layout[q][2 * s] + a;
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

void bindContactCliques(const FibreStore& fs, const ContactParams& p,
                        const ContactElementStore& el, ContactCliqueStore& c, LinearSystem& ls) {
  const Index nE = fs.elements(), n = el.size();
  if (c.elements != nE) {
    c.key.clear();
    c.elements = nE;
  }
  std::vector<std::uint64_t> keys(n);
  tbb::parallel_for(Index(0), n, [&](Index e) { keys[e] = keyOf(fs, p, el, e, nE); });
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
    c.layout.resize(c.key.size());
    for (size_t q = 0; q < c.key.size(); ++q) c.layout[q] = layoutOf(fs, c.key[q]);
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
