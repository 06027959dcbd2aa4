#include "engine/torqued_strings.h"

#include "engine/free_spin.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fibra {
namespace {

// Unit tangent of the reference centreline at node n, from its neighbours on the fibre.
Vec3 tangentAt(const FibreStore& fs, Index n) {
  const Index f = fs.nodeFibre[n], first = fs.firstNode[f], last = first + fs.nodeCount[f] - 1;
  return (x0Of(fs.qRef, std::min(n + 1, last)) - x0Of(fs.qRef, std::max(n - 1, first))).normalized();
}

// A gripped section: the node and the motion that holds it (nullptr: none rotates it).
struct Grip {
  Index node;
  const PrescribedMotion* motion;
};

// Per fibre, its gripped sections (sorted by node, so by arc length).
std::vector<std::vector<Grip>> gripsByFibre(const World& world) {
  const FibreStore& f = world.fibres();
  const ConstraintStore& c = world.constraints();
  std::vector<std::vector<Grip>> out(f.fibres());
  for (size_t k = 0; k < c.dof.size(); ++k) {
    const Index node = c.dof[k] / kNodeDofs;
    if (!gripsSpin(f, node, c.dof[k] % kNodeDofs, tangentAt(f, node))) continue;
    std::vector<Grip>& g = out[f.nodeFibre[node]];
    const PrescribedMotion* m = c.motion[c.owner[k]].rotates ? &c.motion[c.owner[k]] : nullptr;
    if (!g.empty() && g.back().node == node) {
      if (m) g.back().motion = m;
    } else {
      g.push_back({node, m});
    }
  }
  return out;
}

// torsion_factor G J of fibre f, N mm^2.
double torsionStiffness(const World& world, Index f) {
  const MaterialStore& m = world.materials();
  const FibreStore& fs = world.fibres();
  const Index mat = fs.material[f];
  const double G = m.youngModulus[mat] / (2 * (1 + m.poissonRatio[mat]));
  return m.torsionFactor[mat] * G * std::numbers::pi * std::pow(fs.radius[f], 4) / 2;
}

// The turn of a gripped section about its tangent at time t, rad.
double turn(const FibreStore& fs, const Grip& g, double t) {
  if (!g.motion) return 0;
  return tableValue(g.motion->angle, t) * g.motion->axis.normalized().dot(tangentAt(fs, g.node));
}

// The largest torque between neighbouring gripped sections of one fibre, N mm.
double sectionTorque(const World& world, Index f, const std::vector<Grip>& grips) {
  const FibreStore& fs = world.fibres();
  std::vector<double> times;
  for (const Grip& g : grips)
    if (g.motion) times.insert(times.end(), g.motion->angle.t.begin(), g.motion->angle.t.end());
  double torque = 0;
  for (double t : times)
    for (size_t k = 1; k < grips.size(); ++k) {
      const double ds = fs.nodeS[grips[k].node] - fs.nodeS[grips[k - 1].node];
      const double dphi = turn(fs, grips[k], t) - turn(fs, grips[k - 1], t);
      torque = std::max(torque, torsionStiffness(world, f) * std::abs(dphi) / ds);
    }
  return torque;
}

double largest(const Table& table) {
  double m = 0;
  for (double v : table.v) m = std::max(m, std::abs(v));
  return m;
}

// Per fibre, the axial moment loads on its nodes that do not grip, summed (signed), of a fibre
// gripped elsewhere: the grips react the sum, N mm.
void momentLoads(const World& world, const std::vector<std::vector<Grip>>& grips,
                 std::vector<double>& torque) {
  const FibreStore& f = world.fibres();
  const GroupStore& groups = world.groups();
  std::vector<double> sum(f.fibres(), 0.0);
  for (const LoadDef& load : world.scene().loads) {
    if (load.kind != LoadKind::Moment) continue;
    const auto g = std::find(groups.name.begin(), groups.name.end(), load.group);
    if (g == groups.name.end()) continue;  // the scene loader has refused unknown groups
    const Index gi = Index(g - groups.name.begin());
    for (Index i = groups.first[gi]; i < groups.first[gi] + groups.count[gi]; ++i) {
      const Index node = groups.members[i], fibre = f.nodeFibre[node];
      const std::vector<Grip>& held = grips[fibre];
      const bool gripped = std::any_of(held.begin(), held.end(), [&](const Grip& h) { return h.node == node; });
      if (held.empty() || gripped) continue;
      const double axial = load.vector.dot(tangentAt(f, node));
      if (std::abs(axial) > 0.1 * load.vector.norm()) sum[fibre] += axial * largest(load.table);
    }
  }
  for (Index i = 0; i < f.fibres(); ++i) torque[i] = std::max(torque[i], std::abs(sum[i]));
}

bool isString(const World& world, Index f) {
  const MaterialStore& m = world.materials();
  const Index mat = world.fibres().material[f];
  return m.bendingFactor[mat] == 0 && m.torsionFactor[mat] > 0;
}

}  // namespace

std::vector<TorquedString> torquedStrings(const World& world) {
  const FibreStore& f = world.fibres();
  const std::vector<std::vector<Grip>> grips = gripsByFibre(world);
  std::vector<double> torque(f.fibres(), 0.0);
  for (Index i = 0; i < f.fibres(); ++i) torque[i] = sectionTorque(world, i, grips[i]);
  momentLoads(world, grips, torque);
  std::vector<TorquedString> out;
  for (Index i = 0; i < f.fibres(); ++i)
    if (torque[i] > 0 && isString(world, i)) out.push_back({i, torque[i], f.radius[i]});
  return out;
}

}  // namespace fibra
