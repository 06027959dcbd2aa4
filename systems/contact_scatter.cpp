#include "systems/contact_scatter.h"

#include <tbb/parallel_for.h>

namespace fibra {

namespace {

// A column block of V = dv/dq: the clique-local DOF where it starts (node, field), the block of
// v it feeds (0 x^I, 1 x^J, 2 x0I, 3 x0J, 4 dx0/ds|I, 5 dx0/ds|J) and its weight (-, mm, 1/mm).
struct VColumn {
  Index local;
  int block;
  double weight;
};

int vColumns(const ParticleWeights side[2], const NormalJacobian& jac, const CliqueSlots& at,
             const Index sideFirstNode[2], VColumn* out) {
  int n = 0;
  for (int s = 0; s < 2; ++s)
    for (int a = 0; a < side[s].nodes; ++a)
      for (int k = 0; k < 3; ++k)
        out[n++] = {kNodeDofs * (at.first[s] + a) + 3 * k, s, side[s].c[a][k]};
  const SectionWeights* sw[2] = {&jac.I, &jac.J};
  const int rangeStart[2] = {0, at.first[1] - int(side[1].firstNode - sideFirstNode[1])};
  const int rangeEnd[2] = {rangeStart[1], at.nodes};
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < sw[s]->count; ++i) {
      const Index local = rangeStart[s] + (sw[s]->node[i] - sideFirstNode[s]);
      if (local < rangeStart[s] || local >= rangeEnd[s]) continue;  // not in the clique: left out
      const Index col = kNodeDofs * local;  // field x0
      if (sw[s]->centre[i] != 0) out[n++] = {col, 2 + s, sw[s]->centre[i]};
      if (sw[s]->tangent[i] != 0) out[n++] = {col, 4 + s, sw[s]->tangent[i]};
    }
  return n;
}

// An element on its facing particles (systems/facing_particles.h): the normal force R_N N and
// its stiffness on them, each outline's rolling stiffness R_N (R / rho) w w^T, and the friction
// force f - R_N N on the material particles with its blocks on the material particles
// (frictionStiffness) and on the facing ones (coupling).
void scatterFacing(const ParticleWeights material[2], const ContactForceStore& f, Index e,
                   Index clique, const CliqueSlots& slots, bool withTangent, LinearSystem& ls) {
  const double sign[2] = {1, -1}, one = 1;
  const ParticleWeights facing[2] = {f.facingI[e], f.facingJ[e]};
  const Vec3 normal = f.normalForce[e] * f.normal[e];
  scatterContact(facing, sign, 2, normal, f.stiffness[e], clique, withTangent, ls, &slots);
  const Vec3 friction = f.force[e] - normal;
  if (friction != Vec3::Zero() || f.frictionStiffness[e] != Eigen::Matrix3d::Zero()) {
    scatterContact(material, sign, 2, friction, f.frictionStiffness[e], clique, withTangent, ls,
                   &slots);
    if (withTangent) scatterTangent(material, facing, sign, 2, f.coupling[e], clique, slots, ls);
  }
  if (!withTangent) return;
  const Eigen::Matrix3d S = f.normalForce[e] * f.normal[e] * f.normal[e].transpose();
  const ParticleWeights* rolling[2] = {&f.rollingI[e], &f.rollingJ[e]};
  for (int s = 0; s < 2; ++s) {
    const CliqueSlots side{{slots.first[s], 0}, slots.nodes};
    scatterContact(rolling[s], &one, 1, Vec3::Zero(), S, clique, true, ls, &side);
  }
}

}  // namespace

void scatterLinearisedContact(const ParticleWeights side[2], const NormalJacobian& jac,
                              const Vec3& f, Index clique, const CliqueSlots& at,
                              const Index sideFirstNode[2], bool withTangent, LinearSystem& ls) {
  const double sign[2] = {1, -1};
  scatterContact(side, sign, 2, f, Eigen::Matrix3d::Zero(), clique, false, ls, &at);
  if (!withTangent) return;
  VColumn cols[2 * 9 + 2 * 10];
  const int nc = vColumns(side, jac, at, sideFirstNode, cols);
  const Index n = kNodeDofs * at.nodes;
  const Index* pos = &ls.positions[ls.cliqueFirst[clique]];
  double* values = ls.K.valuePtr();
  for (int s = 0; s < 2; ++s)
    for (int a = 0; a < side[s].nodes; ++a)
      for (int k = 0; k < 3; ++k) {
        const double rw = sign[s] * side[s].c[a][k];
        if (rw == 0) continue;
        const Index i0 = kNodeDofs * (at.first[s] + a) + 3 * k;
        for (int c = 0; c < nc; ++c) {
          const double w = -rw * cols[c].weight;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              if (const Index p = pos[(i0 + i) * n + cols[c].local + j]; p >= 0)
                values[p] += w * jac.dfdv(i, 3 * cols[c].block + j);
        }
      }
}

void scatterFibreContacts(const ContactElementStore& el, const ContactForceStore& f,
                          const ContactCliqueStore& c, const IterationInput& input,
                          LinearSystem& ls) {
  const double sign[2] = {1, -1};
  for (Index colour = 0; colour < c.colours(); ++colour) {
    const Index first = c.colourFirst[colour], count = c.colourFirst[colour + 1] - first;
    tbb::parallel_for(Index(0), count, [&](Index k) {
      const Index q = c.colourClique[first + k];
      for (Index i = c.cliqueFirst[q]; i < c.cliqueFirst[q + 1]; ++i) {
        const Index e = c.byClique[i];
        if (f.normalForce[e] == 0) continue;
        const ParticleWeights sides[2] = {el.sideI[e], el.sideJ[e]};
        const std::array<Index, 4>& l = c.layout[q];  // the clique's node ranges
        const Index rangeFirst[2] = {l[0], l[2]};
        const CliqueSlots slots{
            {int(sides[0].firstNode - l[0]), int(l[1] + sides[1].firstNode - l[2])},
            int(l[1] + l[3])};
        if (!f.normalJacobian.empty() && f.normalJacobian[e].I.count > 0) {
          scatterLinearisedContact(sides, f.normalJacobian[e], f.force[e], c.firstClique + q,
                                   slots, rangeFirst, input.withTangent, ls);
        } else if (!f.facing.empty() && f.facing[e]) {
          scatterFacing(sides, f, e, c.firstClique + q, slots, input.withTangent, ls);
        } else {
          scatterContact(sides, sign, 2, f.force[e], f.stiffness[e], c.firstClique + q,
                         input.withTangent, ls, &slots);
        }
      }
    });
  }
}

void scatterToolContacts(const ToolContactStore& el, const ContactForceStore& f,
                         const IterationInput& input, LinearSystem& ls) {
  const double sign = 1;
  for (Index i = 0; i < el.size(); ++i)
    if (f.normalForce[i] > 0)
      scatterContact(&el.side[i], &sign, 1, f.force[i], f.stiffness[i], el.element[i],
                     input.withTangent, ls);
}

}  // namespace fibra
