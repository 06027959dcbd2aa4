#include "engine/torqued_strings.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fibra {
namespace {

// Unit vector from fibre f's first reference node to its last.
Vec3 chordOf(const FibreStore& fs, Index f) {
  const Index first = fs.firstNode[f], last = first + fs.nodeCount[f] - 1;
  return (x0Of(fs.qRef, last) - x0Of(fs.qRef, first)).normalized();
}

double largest(const Table& table) {
  double m = 0;
  for (double v : table.v) m = std::max(m, std::abs(v));
  return m;
}

// |u . t| when u has a component about the fibre's axis t (|u . t| > 0.1 |u|), else 0.
double aboutAxis(const Vec3& u, const Vec3& t) {
  const double c = std::abs(u.dot(t));
  return c > 0.1 * u.norm() ? c : 0;
}

// torsion_factor G J / L of fibre f, N mm per rad.
double torsionStiffness(const World& world, Index f) {
  const MaterialStore& m = world.materials();
  const FibreStore& fs = world.fibres();
  const Index mat = fs.material[f];
  const double G = m.youngModulus[mat] / (2 * (1 + m.poissonRatio[mat]));
  const double J = std::numbers::pi * std::pow(fs.radius[f], 4) / 2;
  return m.torsionFactor[mat] * G * J / fs.length[f];
}

bool isString(const World& world, Index f) {
  const MaterialStore& m = world.materials();
  const Index mat = world.fibres().material[f];
  return m.bendingFactor[mat] == 0 && m.torsionFactor[mat] > 0;
}

// Per fibre, the largest torque that the held, turned sections build up.
void turnedSections(const World& world, std::vector<double>& torque) {
  const FibreStore& f = world.fibres();
  const ConstraintStore& c = world.constraints();
  for (size_t k = 0; k < c.dof.size(); ++k) {
    const PrescribedMotion& m = c.motion[c.owner[k]];
    if (c.dof[k] % kNodeDofs < 3 || !m.rotates) continue;
    const Index fibre = f.nodeFibre[c.dof[k] / kNodeDofs];
    const double phi = largest(m.angle) * aboutAxis(m.axis.normalized(), chordOf(f, fibre));
    torque[fibre] = std::max(torque[fibre], torsionStiffness(world, fibre) * phi);
  }
}

// Per fibre, the largest axial part of a moment load on one of its nodes.
void momentLoads(const World& world, std::vector<double>& torque) {
  const FibreStore& f = world.fibres();
  const GroupStore& groups = world.groups();
  for (const LoadDef& load : world.scene().loads) {
    if (load.kind != LoadKind::Moment) continue;
    const auto g = std::find(groups.name.begin(), groups.name.end(), load.group);
    if (g == groups.name.end()) continue;  // the scene loader has refused unknown groups
    const Index gi = Index(g - groups.name.begin());
    for (Index i = groups.first[gi]; i < groups.first[gi] + groups.count[gi]; ++i) {
      const Index fibre = f.nodeFibre[groups.members[i]];
      const double M = largest(load.table) * aboutAxis(load.vector, chordOf(f, fibre));
      torque[fibre] = std::max(torque[fibre], M);
    }
  }
}

}  // namespace

std::vector<TorquedString> torquedStrings(const World& world) {
  const FibreStore& f = world.fibres();
  std::vector<double> torque(f.fibres(), 0.0);
  turnedSections(world, torque);
  momentLoads(world, torque);
  std::vector<TorquedString> out;
  for (Index i = 0; i < f.fibres(); ++i)
    if (torque[i] > 0 && isString(world, i))
      out.push_back({i, torque[i], f.length[i] / double(f.elementCount[i])});
  return out;
}

}  // namespace fibra
