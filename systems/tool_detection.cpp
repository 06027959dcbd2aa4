#include "systems/tool_detection.h"

#include "core/columns.h"
#include "systems/interpolation.h"
#include "systems/particle.h"
#include "systems/tool_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

namespace fibra {
namespace {

// A contact element for the particle (element, z, xi): its normal is the surface normal at the
// closest point, its tool point the surface point under it. A lateral particle (length > 0) has
// the penalty weight `lateral`; an end-face particle (length 0) |t . N|, t the unit tangent: the
// face bears fully on a tool it faces and not at all on one the fibre lies along, where its
// rim's lowest point would otherwise add a point force to the line contact the lateral
// particles already carry.
void addParticle(const FibreStore& fs, const ToolStore& tools, Index tool, Index e, double z,
                 double length, double lateral, const Section& sec, const Eigen::Vector2d& xi,
                 const RigidMotion& m, ToolContactStore& c) {
  const Index f = fs.elementFibre[e];
  const Vec3 x = sec.x0 + xi(0) * sec.g1 + xi(1) * sec.g2;
  const SurfacePoint sp = closestSurfacePoint(tools, tool, m, x);
  c.weight.push_back(length > 0 ? lateral : std::abs(sec.dx0ds.normalized().dot(sp.normal)));
  const RigidMotion inverse{m.R.transpose(), m.centre, -m.R.transpose() * m.shift};
  c.tool.push_back(tool);
  c.zone.push_back(tool * fs.fibres() + f);
  c.element.push_back(e);
  c.z.push_back(z);
  c.length.push_back(length);
  c.xi1.push_back(xi(0));
  c.xi2.push_back(xi(1));
  c.side.push_back(particleWeights(fs, e, z, xi(0), xi(1)));
  c.normal.push_back(sp.normal);
  c.gap.push_back(sp.distance);
  c.toolPoint.push_back(inverse(sp.point));
  c.d0.push_back(Vec3::Zero());
  c.gRev0.push_back(Vec3::Zero());
}

// The section at (element, z) when its centre is within R + Delta of the tool, with the closest
// surface point to that centre.
std::optional<std::pair<Section, SurfacePoint>> sectionNearTool(const FibreStore& fs,
                                                                const ToolStore& tools, Index tool,
                                                                Index e, double z,
                                                                const RigidMotion& m,
                                                                double proximity) {
  const Index f = fs.elementFibre[e];
  const Section sec = sectionAt(fs, fs.q, {e, z});
  const SurfacePoint centre = closestSurfacePoint(tools, tool, m, sec.x0);
  const double reach =
      std::isfinite(proximity) ? proximity : std::max(fs.radius[f], 0.5 * elementLength(fs, f));
  if (centre.distance > fs.radius[f] + reach) return std::nullopt;
  return std::pair{sec, centre};
}

// Lateral contact at (element, z), a Gauss point of weight w (on [-1, 1]): the outline point
// facing the tool (direction -N), carrying w h / 2 of the centreline (times the stretch); its
// penalty weight w order / 2 is 1 on the element's default rule (one point per order).
void addLateral(const FibreStore& fs, const ToolStore& tools, Index tool, Index e, double z,
                double w, const RigidMotion& m, double proximity, ToolContactStore& c) {
  const auto near = sectionNearTool(fs, tools, tool, e, z, m, proximity);
  if (!near) return;
  const auto& [sec, centre] = *near;
  const Index f = fs.elementFibre[e];
  const double R = fs.radius[f], length = 0.5 * w * elementLength(fs, f) * sec.dx0ds.norm();
  addParticle(fs, tools, tool, e, z, length, 0.5 * w * fs.order[f], sec,
              outlinePoint(sec.g1, sec.g2, R, -centre.normal), m, c);
}

// The flat end face of a fibre at (element, z = +-1): its centre and kEndRim points of its rim
// (the face is a disc of the section's radius; no cap reaches past it).
constexpr int kEndRim = 8;
void addEndFace(const FibreStore& fs, const ToolStore& tools, Index tool, Index e, double z,
                const RigidMotion& m, double proximity, ToolContactStore& c) {
  const auto near = sectionNearTool(fs, tools, tool, e, z, m, proximity);
  if (!near) return;
  const Section& sec = near->first;
  const double R = fs.radius[fs.elementFibre[e]];
  addParticle(fs, tools, tool, e, z, 0.0, 0.0, sec, Eigen::Vector2d::Zero(), m, c);
  for (int k = 0; k < kEndRim; ++k) {
    const double phi = 2 * std::numbers::pi * k / kEndRim;
    addParticle(fs, tools, tool, e, z, 0.0, 0.0, sec,
                R * Eigen::Vector2d(std::cos(phi), std::sin(phi)), m, c);
  }
}

// The Gauss rule of an element of length h and order `order` against one tool (the points
// toolPointsPerElement gives), found in `rules` or added to it.
struct PointRule {
  double h;
  int order, n;
  double z[kMaxToolPoints], w[kMaxToolPoints];
};
const PointRule& pointRule(std::vector<PointRule>& rules, double h, int order, double rho,
                           double pMax) {
  for (const PointRule& r : rules)
    if (r.h == h && r.order == order) return r;
  PointRule& r = rules.emplace_back();
  r.h = h, r.order = order, r.n = toolPointsPerElement(h, rho, pMax, order);
  gaussLegendre(r.n, r.z, r.w);
  return r;
}

}  // namespace

double toolCurvatureRadius(const ToolStore& tools, Index tool) {
  return tools.kind[tool] == ToolKind::Cylinder && !tools.inside[tool]
             ? tools.radius[tool]
             : std::numeric_limits<double>::infinity();
}

double toolSagittaBound(double h, double rho, int n) {
  double z[kMaxToolPoints], w[kMaxToolPoints];
  gaussLegendre(n, z, w);
  double widest = (1 - z[n - 1]) + (z[0] + 1);  // across the element's end, in z
  for (int k = 1; k < n; ++k) widest = std::max(widest, z[k] - z[k - 1]);
  const double s = 0.5 * h * widest;
  return s * s / (8 * rho);
}

int toolPointsPerElement(double h, double rho, double pMax, int order) {
  if (!std::isfinite(rho)) return order;
  for (int n = order; n < kMaxToolPoints; ++n)
    if (toolSagittaBound(h, rho, n) <= 0.25 * pMax) return n;
  return kMaxToolPoints;
}

void detectToolContacts(const FibreStore& fs, const ToolStore& tools, const ContactParams& params,
                        const IterationInput& input, ToolContactStore& c) {
  clearColumns(c);
  for (Index t = 0; t < tools.size(); ++t) {
    const RigidMotion m = toolMotion(tools, t, input.time);
    std::vector<PointRule> rules;  // one per distinct (element length, order): fibres share them
    for (Index f = 0; f < fs.fibres(); ++f) {
      const PointRule& r = pointRule(rules, elementLength(fs, f), fs.order[f],
                                     toolCurvatureRadius(tools, t), tools.pMax[t]);
      for (Index e = fs.firstElement[f]; e < fs.firstElement[f] + fs.elementCount[f]; ++e)
        for (int k = 0; k < r.n; ++k)
          addLateral(fs, tools, t, e, r.z[k], r.w[k], m, params.toolProximity, c);
    }
    for (Index f = 0; f < fs.fibres(); ++f) {
      const Index first = fs.firstElement[f], last = first + fs.elementCount[f] - 1;
      addEndFace(fs, tools, t, first, -1, m, params.toolProximity, c);
      addEndFace(fs, tools, t, last, 1, m, params.toolProximity, c);
    }
  }
}

}  // namespace fibra
