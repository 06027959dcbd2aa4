// What a user reads of a world's converged state, and its bitwise comparison (doctest CHECKs):
// positions, residual, reactions, the first tool's reaction, every contact element.
#pragma once

#include "engine/world.h"

#include <doctest/doctest.h>

namespace fibra::test {

// Everything a user reads of a converged state.
struct Observed {
  Eigen::VectorXd q, residual;
  std::vector<Reaction> reactions;
  Vec3 toolReaction;
  ContactSnapshot contacts;
  double time;
};

inline Observed observe(const World& w) {
  Observed o{w.fibres().q, w.residual(), {}, w.toolReaction(0), w.contactSnapshot(), w.time()};
  for (Index b = 0; b < w.constraints().size(); ++b) o.reactions.push_back(w.reaction(b));
  return o;
}

inline void checkSame(const Observed& a, const Observed& b) {
  CHECK(a.time == b.time);
  CHECK(a.q.cwiseNotEqual(b.q).count() == 0);
  CHECK(a.residual.cwiseNotEqual(b.residual).count() == 0);
  REQUIRE(a.reactions.size() == b.reactions.size());
  for (size_t i = 0; i < a.reactions.size(); ++i) {
    CHECK(a.reactions[i].force == b.reactions[i].force);
    CHECK(a.reactions[i].moment == b.reactions[i].moment);
  }
  CHECK(a.toolReaction == b.toolReaction);
  const ContactSnapshot &c = a.contacts, &d = b.contacts;
  CHECK(c.size() == d.size());
  CHECK(c.particleI == d.particleI);
  CHECK(c.particleJ == d.particleJ);
  CHECK(c.normal == d.normal);
  CHECK(c.gap == d.gap);
  CHECK(c.normalForce == d.normalForce);
  CHECK(c.friction == d.friction);
  CHECK(c.slip == d.slip);
  CHECK(c.tool == d.tool);
  CHECK(c.fibreI == d.fibreI);
  CHECK(c.fibreJ == d.fibreJ);
}

}  // namespace fibra::test
