#include "systems/contact_assembler.h"

#include "systems/contact_law.h"
#include "systems/contact_scatter.h"

#include <tbb/parallel_for.h>

#include <map>

namespace fibra {

void colourContactCliques(ContactMechanicsStore& m, Index contactCliques) {
  // Elements grouped by clique, ascending within a clique.
  m.cliqueFirst.assign(contactCliques + 1, 0);
  for (Index e = 0; e < m.size(); ++e) ++m.cliqueFirst[m.clique[e] - m.firstContactClique + 1];
  for (Index c = 0; c < contactCliques; ++c) m.cliqueFirst[c + 1] += m.cliqueFirst[c];
  m.byClique.resize(m.size());
  std::vector<Index> next(m.cliqueFirst.begin(), m.cliqueFirst.end() - 1);
  std::vector<const ParticleWeights*> sides(2 * contactCliques, nullptr);
  for (Index e = 0; e < m.size(); ++e) {
    const Index c = m.clique[e] - m.firstContactClique;
    m.byClique[next[c]++] = e;
    sides[2 * c] = &m.sideI[e];
    sides[2 * c + 1] = &m.sideJ[e];
  }
  // Greedy colouring: the first colour none of whose cliques touches one of this clique's nodes.
  m.colourCliques.clear();
  std::map<Index, std::vector<bool>> used;  // node -> colours present
  for (Index c = 0; c < contactCliques; ++c) {
    if (!sides[2 * c]) continue;  // a clique of the pattern without elements now
    std::vector<Index> nodes;
    for (int s = 0; s < 2; ++s)
      for (int a = 0; a < sides[2 * c + s]->nodes; ++a) nodes.push_back(sides[2 * c + s]->firstNode + a);
    size_t colour = 0;
    for (;; ++colour) {
      bool free = true;
      for (Index n : nodes) free = free && !(colour < used[n].size() && used[n][colour]);
      if (free) break;
    }
    if (colour == m.colourCliques.size()) m.colourCliques.emplace_back();
    m.colourCliques[colour].push_back(c);
    for (Index n : nodes) {
      if (used[n].size() <= colour) used[n].resize(colour + 1, false);
      used[n][colour] = true;
    }
  }
}

void assembleContacts(const Eigen::VectorXd& q, const ContactAssemblyParams& p, bool withTangent,
                      ContactMechanicsStore& m, LinearSystem& ls) {
  tbb::parallel_for(Index(0), m.size(), [&](Index e) {
    const Vec3 d = particlePosition(q, m.sideI[e]) - particlePosition(q, m.sideJ[e]);
    const ContactLawParams law{m.penalty[m.zone[e]], p.pRegRatio * p.pMax, p.mu, p.gMax};
    const ContactLawResult r = contactLaw(d, {m.normal[e], m.d0[e], m.gRev0[e]}, law, p.symmetrised);
    m.gap[e] = r.gap;
    m.normalForce[e] = r.normalForce;
    m.force[e] = r.force;
    m.gRev[e] = r.gRev;
    m.slip[e] = r.slip;
    m.stiffness[e] = r.stiffness;
  });
  const double sign[2] = {1, -1};
  for (const std::vector<Index>& colour : m.colourCliques) {
    tbb::parallel_for(size_t(0), colour.size(), [&](size_t k) {
      const Index c = colour[k];
      for (Index i = m.cliqueFirst[c]; i < m.cliqueFirst[c + 1]; ++i) {
        const Index e = m.byClique[i];
        if (m.normalForce[e] == 0) continue;
        const ParticleWeights sides[2] = {m.sideI[e], m.sideJ[e]};
        scatterContact(sides, sign, 2, m.force[e], m.stiffness[e], m.clique[e], withTangent, ls);
      }
    });
  }
}

}  // namespace fibra
