#include "engine/free_spin.h"

#include <Eigen/Geometry>

#include <cmath>

namespace fibra {
namespace {

// Unit vector from fibre f's first reference node to its last.
Vec3 chord(const FibreStore& fs, Index f) {
  const Index first = fs.firstNode[f], last = first + fs.nodeCount[f] - 1;
  return (x0Of(fs.qRef, last) - x0Of(fs.qRef, first)).normalized();
}

bool straight(const FibreStore& fs, Index f) {
  const Index first = fs.firstNode[f], last = first + fs.nodeCount[f] - 1;
  const Vec3 a = x0Of(fs.qRef, first), t = chord(fs, f);
  for (Index n = first; n <= last; ++n) {
    const Vec3 d = x0Of(fs.qRef, n) - a;
    if ((d - d.dot(t) * t).norm() > 1e-6 * fs.length[f]) return false;
  }
  return true;
}

}  // namespace

bool gripsSpin(const FibreStore& fs, Index n, Index c, const Vec3& t) {
  if (c < 3) return false;
  const Vec3 g = c < 6 ? Vec3(g1Of(fs.qRef, n)) : Vec3(g2Of(fs.qRef, n));
  return std::abs(t.cross(g)(c % 3)) > 0.1 * g.norm();
}

bool frictionCanAct(const SceneDef& s) {
  bool scaled = false;
  for (const StepDef& st : s.steps) scaled = scaled || st.frictionFactor > 0;
  const bool pairs = s.contact.enabled && (s.fibres.size() > 1 || s.contact.selfContact);
  bool mu = pairs && s.contact.friction > 0;
  for (const ContactPairDef& r : s.contact.pairs) mu = mu || (pairs && r.friction > 0);
  for (const ToolDef& t : s.tools) mu = mu || t.friction > 0;
  return scaled && mu;
}

std::vector<Index> freeSpinFibres(const World& world) {
  const FibreStore& f = world.fibres();
  std::vector<Index> out;
  if (!frictionCanAct(world.scene())) return out;
  std::vector<bool> position(f.fibres(), false), gripped(f.fibres(), false);
  for (Index d : world.constraints().dof) {
    const Index node = d / kNodeDofs, c = d % kNodeDofs, fibre = f.nodeFibre[node];
    if (c < 3) {
      position[fibre] = true;
      continue;
    }
    gripped[fibre] = gripped[fibre] || gripsSpin(f, node, c, chord(f, fibre));
  }
  for (Index i = 0; i < f.fibres(); ++i)
    if (position[i] && !gripped[i] && straight(f, i)) out.push_back(i);
  return out;
}

}  // namespace fibra
