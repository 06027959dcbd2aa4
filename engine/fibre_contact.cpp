#include "engine/fibre_contact.h"

#include "engine/contact_setup.h"
#include "systems/contact_assembler.h"
#include "systems/contact_detection.h"
#include "systems/contact_normals.h"
#include "systems/friction_history.h"
#include "systems/interpolation.h"
#include "systems/particle.h"
#include "systems/sparse_pattern.h"

#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

double initialPenalty(const WorldState& w, Index I, Index J) {
  if (std::isfinite(w.scene.contact.initialPenalty)) return w.scene.contact.initialPenalty;
  auto ER = [&](Index f) { return w.materials.youngModulus[w.fibres.material[f]] * w.fibres.radius[f]; };
  return std::min(ER(I), ER(J));
}

// Penalties of this call's zones, carried by zone id (or from the parent of a split).
void carryPenalties(WorldState& w, const std::vector<std::uint64_t>& previousIds) {
  const ZoneStore& z = w.zones;
  w.mechanics.penalty.resize(z.size());
  for (Index i = 0; i < z.size(); ++i) {
    auto it = w.zonePenalty.find(z.id[i]);
    if (it == w.zonePenalty.end() && z.previous[i] >= 0)
      it = w.zonePenalty.find(previousIds[z.previous[i]]);
    w.mechanics.penalty[i] = it != w.zonePenalty.end() ? it->second : initialPenalty(w, z.fibreI[i], z.fibreJ[i]);
  }
}

// Particle weights, zone and normal of every element.
void bindParticles(WorldState& w) {
  const ContactElementStore& el = w.elements;
  ContactMechanicsStore& m = w.mechanics;
  const Index n = el.size();
  m.sideI.resize(n), m.sideJ.resize(n), m.clique.resize(n), m.zone.resize(n), m.normal.resize(n);
  m.d0.resize(n), m.gRev0.resize(n), m.gap.resize(n), m.normalForce.resize(n), m.force.resize(n);
  m.stiffness.resize(n), m.gRev.resize(n), m.slip.resize(n);
  for (Index e = 0; e < n; ++e) {
    const FibrePoint pI = locate(w.fibres, el.fibreI[e], el.sI[e]);
    const FibrePoint pJ = locate(w.fibres, el.fibreJ[e], el.sJ[e]);
    m.sideI[e] = particleWeights(w.fibres, pI.element, pI.z, el.xiI1[e], el.xiI2[e]);
    m.sideJ[e] = particleWeights(w.fibres, pJ.element, pJ.z, el.xiJ1[e], el.xiJ2[e]);
    m.zone[e] = el.zone[e];
    m.normal[e] = el.normal[e];
    m.gap[e] = el.gap[e];
    m.normalForce[e] = 0;
    m.slip[e] = 0;
  }
}

}  // namespace

// Registers the element pairs as cliques; rebuilds the pattern when one is new, or when more
// than half of the contact cliques went unused.
void registerFibreCliques(WorldState& w) {
  ContactMechanicsStore& m = w.mechanics;
  std::map<std::pair<Index, Index>, Index>& of = w.contactClique;
  const auto pairOf = [&](Index e) { return std::make_pair(m.sideI[e].element, m.sideJ[e].element); };
  bool changed = false;
  std::vector<bool> used(of.size(), false);
  for (Index e = 0; e < m.size(); ++e) {
    auto [it, fresh] = of.emplace(pairOf(e), Index(of.size()));
    changed |= fresh;
    if (fresh) used.push_back(true);
    else used[it->second] = true;
  }
  const Index inUse = Index(std::count(used.begin(), used.end(), true));
  if (Index(of.size()) > 2 * inUse + 64) {
    of.clear();
    for (Index e = 0; e < m.size(); ++e) of.emplace(pairOf(e), Index(of.size()));
    changed = true;
  }
  m.firstContactClique = w.fibres.elements();
  if (changed) {
    CliqueList cliques = beamCliques(w.fibres);
    std::vector<std::pair<Index, Index>> byIndex(of.size());
    for (const auto& [pair, c] : of) byIndex[c] = pair;
    for (const auto& [eI, eJ] : byIndex) {
      const auto& fs = w.fibres;
      cliques.addPair(fs.elementFirstNode[eI], fs.order[fs.elementFibre[eI]] + 1,
                      fs.elementFirstNode[eJ], fs.order[fs.elementFibre[eJ]] + 1);
    }
    w.arena->execute([&] { buildPattern(w.fibres, cliques, w.system); });
  }
  for (Index e = 0; e < m.size(); ++e) m.clique[e] = m.firstContactClique + of.at(pairOf(e));
  colourContactCliques(m, Index(of.size()));
}

void buildFibreContact(WorldState& w) {
  if (!w.scene.contact.enabled) return;
  w.detection = resolveContactParams(w.fibres, w.scene.contact);
}

void detectFibreContacts(WorldState& w) {
  if (!w.scene.contact.enabled) return;
  const std::vector<std::uint64_t> previousIds = w.zones.id;
  detectContacts(w.fibres, w.fibres.q, w.detection, w.cache, w.zones, w.elements, w.def.trace);
  carryPenalties(w, previousIds);
  bindParticles(w);
  registerFibreCliques(w);
}

void rebaseFibreContacts(WorldState& w) {
  ContactMechanicsStore& m = w.mechanics;
  const ContactElementStore& el = w.elements;
  for (Index e = 0; e < m.size(); ++e) {
    m.d0[e] = particlePosition(w.fibres.q, m.sideI[e]) - particlePosition(w.fibres.q, m.sideJ[e]);
    const Index I = el.fibreI[e], J = el.fibreJ[e];
    const Vec3 hI = lookupHistory(w.history, I, J, el.sI[e], elementLength(w.fibres, I));
    const Vec3 hJ = lookupHistory(w.history, J, I, el.sJ[e], elementLength(w.fibres, J));
    m.gRev0[e] = projectOnPlane(0.5 * (hI - hJ), m.normal[e]);
  }
}

double updateFibreNormals(WorldState& w) {
  ContactMechanicsStore& m = w.mechanics;
  updateNormalsAndGaps(w.fibres, w.fibres.q, w.detection, w.elements, w.def.trace);
  double turned = 0;
  for (Index e = 0; e < m.size(); ++e) {
    turned = std::max(turned, std::acos(std::clamp(m.normal[e].dot(w.elements.normal[e]), -1.0, 1.0)));
    m.normal[e] = w.elements.normal[e];
    m.gRev0[e] = projectOnPlane(m.gRev0[e], m.normal[e]);
  }
  return turned;
}

double adaptZonePenalties(WorldState& w) {
  ContactMechanicsStore& m = w.mechanics;
  std::vector<double> deepest(w.zones.size(), 0.0);
  for (Index e = 0; e < m.size(); ++e) deepest[m.zone[e]] = std::max(deepest[m.zone[e]], -m.gap[e]);
  const double beta = w.contact.penaltyChange;
  double change = 0;
  for (Index z = 0; z < w.zones.size(); ++z) {
    if (deepest[z] > 0) {
      const double factor = std::clamp(deepest[z] / (w.contact.penaltyTarget * w.contact.pMax), 1 / beta, beta);
      m.penalty[z] *= factor;
      change = std::max(change, std::abs(factor - 1));
    }
    w.zonePenalty[w.zones.id[z]] = m.penalty[z];
  }
  return change;
}

void fibreHistoryEntries(const WorldState& w, std::vector<HistoryEntry>& out) {
  const ContactMechanicsStore& m = w.mechanics;
  const ContactElementStore& el = w.elements;
  for (Index e = 0; e < m.size(); ++e) {
    if (m.normalForce[e] <= 0) continue;
    out.push_back({el.fibreI[e], el.fibreJ[e], el.sI[e], m.gRev[e]});
    out.push_back({el.fibreJ[e], el.fibreI[e], el.sJ[e], -m.gRev[e]});
  }
}

double fibreStepLimit(const WorldState& w, const Eigen::VectorXd& dq) {
  const ContactMechanicsStore& m = w.mechanics;
  const double allowed = w.contact.stepPenetration * w.contact.pMax;
  double a = 1;
  for (Index e = 0; e < m.size(); ++e) {
    const double dg = m.normal[e].dot(particlePosition(dq, m.sideI[e]) - particlePosition(dq, m.sideJ[e]));
    if (dg < 0 && m.gap[e] > -allowed) a = std::min(a, (m.gap[e] + allowed) / -dg);
  }
  return a;
}

double deepestFibreContact(const WorldState& w) {
  double d = 0;
  for (double g : w.elements.gap) d = std::max(d, -g / w.contact.pMax);
  return d;
}

void fibreContactReport(const WorldState& w, ContactReport& r) {
  const ContactMechanicsStore& m = w.mechanics;
  r.zones = w.zones.size();
  r.elements = m.size();
  for (Index e = 0; e < m.size(); ++e) {
    r.active += m.normalForce[e] > 0;
    r.sliding += sliding(m.normalForce[e], m.gRev[e], w.contact.gMax);
    r.maxPenetration = std::max(r.maxPenetration, -m.gap[e]);
    r.maxPenetrationRatio = std::max(r.maxPenetrationRatio, -m.gap[e] / w.contact.pMax);
  }
}

}  // namespace fibra
