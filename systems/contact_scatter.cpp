#include "systems/contact_scatter.h"

#include <tbb/parallel_for.h>

namespace fibra {

namespace {

// A column block of V = dv/dq: the clique-local DOF where it starts (node, field), the block of
// v it feeds (0 x_N^I, 1 x_N^J, 2 x0I, 3 x0J, 4 dx0/ds|I, 5 dx0/ds|J, 6 x^I, 7 x^J) and its
// weight (-, mm, 1/mm).
struct VColumn {
  Index local;
  int block;
  double weight;
};

// The columns of V: the normal force's points (`normal`, blocks 0-1), the sections (2-5), the
// material particles (`material`, 6-7).
int vColumns(const ParticleWeights material[2], const ParticleWeights normal[2],
             const NormalJacobian& jac, const CliqueSlots& at, const Index sideFirstNode[2],
             VColumn* out) {
  int n = 0;
  for (int s = 0; s < 2; ++s)
    for (int a = 0; a < material[s].nodes; ++a)
      for (int k = 0; k < 3; ++k) {
        const Index local = kNodeDofs * (at.first[s] + a) + 3 * k;
        if (normal[s].c[a][k] != 0) out[n++] = {local, s, normal[s].c[a][k]};
        if (material[s].c[a][k] != 0) out[n++] = {local, 6 + s, material[s].c[a][k]};
      }
  const SectionWeights* sw[2] = {&jac.I, &jac.J};
  const int rangeStart[2] = {0, at.first[1] - int(material[1].firstNode - sideFirstNode[1])};
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

// K += -sum_s sign_s rows_s^T (block) V: a force on side I's points (`rows`), -it on J's, whose
// derivative with respect to v is `block`.
void addForceDerivative(const ParticleWeights rows[2], const NormalJacobian::Block& block,
                        const VColumn* cols, int nc, Index clique, const CliqueSlots& at,
                        LinearSystem& ls) {
  const double sign[2] = {1, -1};
  const Index n = kNodeDofs * at.nodes;
  const Index* pos = &ls.positions[ls.cliqueFirst[clique]];
  double* values = ls.K.valuePtr();
  for (int s = 0; s < 2; ++s)
    for (int a = 0; a < rows[s].nodes; ++a)
      for (int k = 0; k < 3; ++k) {
        const double rw = sign[s] * rows[s].c[a][k];
        if (rw == 0) continue;
        const Index i0 = kNodeDofs * (at.first[s] + a) + 3 * k;
        for (int c = 0; c < nc; ++c) {
          const double w = -rw * cols[c].weight;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              if (const Index p = pos[(i0 + i) * n + cols[c].local + j]; p >= 0)
                values[p] += w * block(i, 3 * cols[c].block + j);
        }
      }
}

// The facing points' motion with N: the rows of side s's directors g_f (f = 1, 2) carry
// sign_s N_a xi_f f_N (f_N on I), so K += -sign_s N_a f_N (d xi_f/dv) V there: a force
// derivative f_N (d xi_f/dv) on the weights N_a of g_f alone, one side at a time.
void addFacingMotion(const ParticleWeights material[2], const NormalJacobian& jac, const Vec3& fN,
                     const VColumn* cols, int nc, Index clique, const CliqueSlots& at,
                     LinearSystem& ls) {
  for (int s = 0; s < 2; ++s)
    for (int f = 1; f <= 2; ++f) {
      ParticleWeights rows[2] = {material[0], material[1]};
      for (int side = 0; side < 2; ++side)
        for (int a = 0; a < rows[side].nodes; ++a)
          for (int k = 0; k < 3; ++k)
            rows[side].c[a][k] = side == s && k == f ? material[side].c[a][0] : 0;
      const NormalJacobian::Block block = fN * jac.dxi.row(2 * s + f - 1);
      addForceDerivative(rows, block, cols, nc, clique, at, ls);
    }
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

void scatterLinearisedContact(const ParticleWeights material[2], const ContactForceStore& f,
                              Index e, Index clique, const CliqueSlots& at,
                              const Index sideFirstNode[2], bool withTangent, LinearSystem& ls) {
  const double sign[2] = {1, -1}, one = 1;
  const bool facing = !f.facing.empty() && f.facing[e];
  const ParticleWeights normal[2] = {facing ? f.facingI[e] : material[0],
                                     facing ? f.facingJ[e] : material[1]};
  const Vec3 fN = f.normalForce[e] * f.normal[e];
  const Eigen::Matrix3d none = Eigen::Matrix3d::Zero();
  scatterContact(normal, sign, 2, fN, none, clique, false, ls, &at);
  scatterContact(material, sign, 2, f.force[e] - fN, none, clique, false, ls, &at);
  if (!withTangent) return;
  const NormalJacobian& jac = f.normalJacobian[e];
  VColumn cols[4 * 9 + 2 * 10];
  const int nc = vColumns(material, normal, jac, at, sideFirstNode, cols);
  addForceDerivative(normal, jac.dfN, cols, nc, clique, at, ls);
  addForceDerivative(material, jac.dfT, cols, nc, clique, at, ls);
  if (!facing) return;
  addFacingMotion(material, jac, fN, cols, nc, clique, at, ls);
  const Eigen::Matrix3d S = f.normalForce[e] * f.normal[e] * f.normal[e].transpose();
  const ParticleWeights* rolling[2] = {&f.rollingI[e], &f.rollingJ[e]};
  for (int s = 0; s < 2; ++s) {
    const CliqueSlots side{{at.first[s], 0}, at.nodes};
    scatterContact(rolling[s], &one, 1, Vec3::Zero(), S, clique, true, ls, &side);
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
          scatterLinearisedContact(sides, f, e, c.firstClique + q, slots, rangeFirst,
                                   input.withTangent, ls);
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
