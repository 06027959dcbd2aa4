// Contact scatter systems: the forces of the contact elements (fibre-fibre and fibre-tool) into
// the linear system.
//
// scatterFibreContacts  reads ContactElementStore (particle weights), ContactForceStore,
//   ContactCliqueStore (cliques, colours), IterationInput (withTangent); writes LinearSystem r,
//   K. Colour by colour; the cliques of one colour (no shared node) in parallel, the elements of
//   a clique in ascending order: every entry receives its contributions in a fixed order.
// scatterToolContacts   reads ToolContactStore (particle weights), ContactForceStore,
//   IterationInput; writes LinearSystem r, K, serially in element order (tool contacts are few);
//   the clique of a tool element is its beam element's.
// Both skip elements without normal force. A fibre element with a linearised normal goes
// through scatterLinearisedContact; one on facing particles (ContactForceStore::facing) has its
// normal force act on them, with each outline's rolling stiffness, and its friction force on
// its material particles (systems/facing_particles.h).
//
// One element (scatterContact below):
// A contact element acts on the relative position d = sum_s sign_s x_s of its particles
// (sign +1 for side I, -1 for side J; a tool side has no DOFs). With f the force on side I and
// S = -df/dd its stiffness, it adds
//   r -= D^T f,   K += D^T S D,   D = dd/dq = [sign_s c_s[a][f] I3],
// into the clique whose nodes are the sides' element nodes in order (side I's, then J's).
// Not thread-safe on its own: callers scatter cliques of one colour in parallel.
#pragma once

#include "components/contact.h"
#include "components/contact_cliques.h"
#include "components/contact_forces.h"
#include "components/iteration.h"
#include "components/linear_system.h"
#include "components/tools.h"
#include "systems/particle.h"

namespace fibra {

// Where the sides' element nodes sit in their clique: side s's first node is the clique's
// node first[s] of `nodes` (a widened contact clique holds a neighbouring element too,
// systems/contact_cliques.h); by default the sides' elements in order.
struct CliqueSlots {
  int first[2];
  int nodes;
};

inline CliqueSlots defaultSlots(const ParticleWeights* side, int sides) {
  CliqueSlots c{{0, side[0].nodes}, side[0].nodes};
  if (sides == 2) c.nodes += side[1].nodes;
  return c;
}

// K += D_rows^T S D_cols: the tangent of a force that acts on the particles `rows` and
// depends on the positions of the particles `cols` (both sides' weights on the same elements:
// the same slots).
inline void scatterTangent(const ParticleWeights* rows, const ParticleWeights* cols,
                           const double* sign, int sides, const Eigen::Matrix3d& S, Index clique,
                           const CliqueSlots& at, LinearSystem& ls) {
  const Index n = kNodeDofs * at.nodes;
  const Index* pos = &ls.positions[ls.cliqueFirst[clique]];
  double* values = ls.K.valuePtr();
  for (int s = 0; s < sides; ++s)
    for (int t = 0; t < sides; ++t)
      for (int a = 0, na = at.first[s], nb = at.first[t]; a < rows[s].nodes; ++a)
        for (int b = 0; b < cols[t].nodes; ++b)
          for (int k = 0; k < 3; ++k)
            for (int h = 0; h < 3; ++h) {
              const double w = sign[s] * sign[t] * rows[s].c[a][k] * cols[t].c[b][h];
              const Index i0 = kNodeDofs * (na + a) + 3 * k, j0 = kNodeDofs * (nb + b) + 3 * h;
              for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                  if (const Index p = pos[(i0 + i) * n + j0 + j]; p >= 0) values[p] += w * S(i, j);
            }
}

inline void scatterContact(const ParticleWeights* side, const double* sign, int sides,
                           const Vec3& f, const Eigen::Matrix3d& S, Index clique,
                           bool withTangent, LinearSystem& ls, const CliqueSlots* slots = nullptr) {
  for (int s = 0; s < sides; ++s)
    for (int a = 0; a < side[s].nodes; ++a)
      for (int k = 0; k < 3; ++k)
        ls.r.segment<3>(kNodeDofs * (side[s].firstNode + a) + 3 * k) -= sign[s] * side[s].c[a][k] * f;
  if (withTangent)
    scatterTangent(side, side, sign, sides, S, clique, slots ? *slots : defaultSlots(side, sides), ls);
}

// An element with a linearised normal (ContactForceStore::normalJacobian,
// systems/normal_linearisation.h): r -= D_N^T f_N + D^T f_T, K += D_N^T (-df_N/dv) V +
// D^T (-df_T/dv) V with V = dv/dq, v = (x_N^I, x_N^J, x0I, x0J, dx0/ds|I, dx0/ds|J, x^I, x^J):
// the normal force's points (facing ones with contact.facing_particles, else the material
// `sides`) and the material particles by their weights, the sections' weights on the nodal x0
// for the rest; with facing points also their motion (through N: NormalJacobian::dxi; through
// the directors: the rolling stiffness, as scatterFacing). sideFirstNode[s]: the global node at
// the start of side s's range in the (possibly widened) clique. Not thread-safe on its own.
void scatterLinearisedContact(const ParticleWeights sides[2], const ContactForceStore& forces,
                              Index e, Index clique, const CliqueSlots& slots,
                              const Index sideFirstNode[2], bool withTangent, LinearSystem& ls);

void scatterFibreContacts(const ContactElementStore& elements, const ContactForceStore& forces,
                          const ContactCliqueStore& cliques, const IterationInput& input,
                          LinearSystem& ls);

void scatterToolContacts(const ToolContactStore& elements, const ContactForceStore& forces,
                         const IterationInput& input, LinearSystem& ls);

}  // namespace fibra
