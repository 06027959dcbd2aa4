#include "systems/tool_contact.h"

#include "systems/contact_law.h"
#include "systems/contact_scatter.h"

#include <Eigen/Geometry>

namespace fibra {

RigidMotion toolMotion(const ToolStore& tools, Index tool, double time) {
  return motionAt(tools.motion[tool], tools.point[tool], time);
}

SurfacePoint closestSurfacePoint(const ToolStore& tools, Index tool, const RigidMotion& m,
                                  const Vec3& x) {
  const Vec3 p = m(tools.point[tool]), dir = (m.R * tools.direction[tool]).normalized();
  if (tools.kind[tool] == ToolKind::Plane) {
    const double dist = (x - p).dot(dir);
    return {x - dist * dir, dir, dist};
  }
  Vec3 radial = (x - p) - (x - p).dot(dir) * dir;
  const double rho = radial.norm();
  // On the axis the radial direction is undefined: any normal to the axis will do.
  radial = rho > 0 ? Vec3(radial / rho) : Vec3(dir.unitOrthogonal());
  const bool inside = tools.inside[tool];
  const Vec3 normal = inside ? Vec3(-radial) : radial;
  const double dist = inside ? tools.radius[tool] - rho : rho - tools.radius[tool];
  return {x - dist * normal, normal, dist};
}

namespace {

// Particle facing the tool at (element, z): outline point in the direction -N.
void addContact(const FibreStore& fs, const Eigen::VectorXd& q, const ToolStore& tools, Index tool,
                Index e, double z, const RigidMotion& m, double proximity, ToolContactStore& c) {
  const Index f = fs.elementFibre[e];
  const Section sec = sectionAt(fs, q, {e, z});
  const SurfacePoint centre = closestSurfacePoint(tools, tool, m, sec.x0);
  const double reach = std::isfinite(proximity) ? proximity : std::max(fs.radius[f], 0.5 * elementLength(fs, f));
  if (centre.distance > fs.radius[f] + reach) return;
  const Eigen::Vector2d xi = outlinePoint(sec.g1, sec.g2, fs.radius[f], -centre.normal);
  const Vec3 x = sec.x0 + xi(0) * sec.g1 + xi(1) * sec.g2;
  const SurfacePoint sp = closestSurfacePoint(tools, tool, m, x);
  const RigidMotion inverse{m.R.transpose(), m.centre, -m.R.transpose() * m.shift};
  c.tool.push_back(tool);
  c.element.push_back(e);
  c.z.push_back(z);
  c.xi1.push_back(xi(0));
  c.xi2.push_back(xi(1));
  c.normal.push_back(sp.normal);
  c.toolPoint.push_back(inverse(sp.point));
  c.d0.push_back(x - sp.point);
  c.gRev0.push_back(Vec3::Zero());
  c.gap.push_back(sp.distance);
  c.normalForce.push_back(0);
  c.gRev.push_back(Vec3::Zero());
  c.slip.push_back(0);
}

}  // namespace

void detectToolContacts(const FibreStore& fs, const Eigen::VectorXd& q, const ToolStore& tools,
                        double time, double proximity, ToolContactStore& c) {
  c = ToolContactStore{};
  for (Index t = 0; t < tools.size(); ++t) {
    const RigidMotion m = toolMotion(tools, t, time);
    for (Index e = 0; e < fs.elements(); ++e) {
      const int order = fs.order[fs.elementFibre[e]];
      const double zs[2] = {-0.5, 0.5};
      for (int k = 0; k < order; ++k)
        addContact(fs, q, tools, t, e, order == 2 ? zs[k] : 0.0, m, proximity, c);
    }
  }
}

void updateToolNormals(const FibreStore& fs, const Eigen::VectorXd& q, const ToolStore& tools,
                       double time, ToolContactStore& c) {
  for (Index i = 0; i < c.size(); ++i) {
    const RigidMotion m = toolMotion(tools, c.tool[i], time);
    const Vec3 x = particlePosition(q, particleWeights(fs, c.element[i], c.z[i], c.xi1[i], c.xi2[i]));
    c.normal[i] = closestSurfacePoint(tools, c.tool[i], m, x).normal;
  }
}

void assembleToolContacts(const FibreStore& fs, const Eigen::VectorXd& q, ToolStore& tools,
                          ToolContactStore& c, const ToolContactParams& params, double time,
                          bool withTangent, LinearSystem& ls) {
  std::vector<RigidMotion> motion;
  for (Index t = 0; t < tools.size(); ++t) motion.push_back(toolMotion(tools, t, time));
  for (Vec3& r : tools.reaction) r.setZero();
  const double sign = 1;
  for (Index i = 0; i < c.size(); ++i) {
    const Index t = c.tool[i], f = fs.elementFibre[c.element[i]];
    const ParticleWeights w = particleWeights(fs, c.element[i], c.z[i], c.xi1[i], c.xi2[i]);
    const Vec3 d = particlePosition(q, w) - motion[t](c.toolPoint[i]);
    const double k = tools.penalty[t * fs.fibres() + f];
    const ContactLawParams law{k, params.pRegRatio * tools.pMax[t], tools.friction[t], params.gMax};
    const ContactLawResult res = contactLaw(d, {c.normal[i], c.d0[i], c.gRev0[i]}, law, params.symmetrised);
    c.gap[i] = res.gap;
    c.normalForce[i] = res.normalForce;
    c.gRev[i] = res.gRev;
    c.slip[i] = res.slip;
    tools.reaction[t] -= res.force;
    if (res.normalForce > 0) scatterContact(&w, &sign, 1, res.force, res.stiffness, c.element[i], withTangent, ls);
  }
}

}  // namespace fibra
