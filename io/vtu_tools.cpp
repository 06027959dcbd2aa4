// The tools' surfaces for the VTU series (io/vtu_writer.h): a patch of each plane, the covered
// length of each cylinder, moved to the frame's time by the tool's motion.
#include "io/vtu_writer.h"

#include "systems/tool_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace fibra {
namespace {

constexpr std::uint8_t kQuadCell = 9;  // VTK_QUAD

// The tool's axes at t = 0: plane (u, v in the plane, n its normal); cylinder (u, v normal to
// the axis, n the axis).
struct Axes {
  Vec3 u, v, n;
};

Axes axesOf(const ToolStore& tools, Index t) {
  const Vec3 n = tools.direction[t].normalized();
  const Vec3 u = n.unitOrthogonal();
  return {u, n.cross(u), n};
}

// Lowest and highest value of `coordinate` over the fibres' nodes, widened by the margin.
void cover(ToolExtent& e, int axis, double lo, double hi, double radius) {
  const double margin = std::max(0.1 * (hi - lo) + 2 * radius, 1.0);
  e.lo[axis] = lo - margin;
  e.hi[axis] = hi + margin;
}

}  // namespace

std::vector<ToolExtent> toolExtents(const ToolStore& tools, const FibreStore& fibres,
                                    const Eigen::VectorXd& q) {
  double radius = 0;
  for (double r : fibres.radius) radius = std::max(radius, r);
  std::vector<ToolExtent> extents(tools.size());
  for (Index t = 0; t < tools.size(); ++t) {
    const Axes a = axesOf(tools, t);
    const Vec3 along[2] = {tools.kind[t] == ToolKind::Plane ? a.u : a.n, a.v};
    for (int k = 0; k < 2; ++k) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (Index n = 0; n < fibres.nodes(); ++n) {
        const double s = (Vec3(x0Of(q, n)) - tools.point[t]).dot(along[k]);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
      if (fibres.nodes() == 0) lo = hi = 0;
      cover(extents[t], k, lo, hi, radius);
    }
  }
  return extents;
}

void writeToolVtu(const std::string& path, const ToolStore& tools,
                  const std::vector<ToolExtent>& extents, double time, const VtuDef& def) {
  if (def.toolSides < 3) throw std::invalid_argument("VtuDef::toolSides must be >= 3");
  if (extents.size() != size_t(tools.size()))
    throw std::invalid_argument("writeToolVtu: one extent per tool expected");
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types, kind;
  std::vector<std::int32_t> toolIndex;
  const auto addPoint = [&](const RigidMotion& m, const Vec3& x) {
    const Vec3 p = m(x);
    points.insert(points.end(), p.data(), p.data() + 3);
    return std::int64_t(points.size() / 3 - 1);
  };
  const auto addQuad = [&](Index t, std::initializer_list<std::int64_t> corners) {
    connectivity.insert(connectivity.end(), corners);
    offsets.push_back(std::int64_t(connectivity.size()));
    types.push_back(kQuadCell);
    kind.push_back(tools.kind[t] == ToolKind::Plane ? 0 : 1);
    toolIndex.push_back(t);
  };
  for (Index t = 0; t < tools.size(); ++t) {
    const RigidMotion m = toolMotion(tools, t, time);
    const Axes a = axesOf(tools, t);
    const Vec3 p = tools.point[t];
    const ToolExtent& e = extents[t];
    if (tools.kind[t] == ToolKind::Plane) {
      const std::int64_t first = addPoint(m, p + e.lo[0] * a.u + e.lo[1] * a.v);
      addPoint(m, p + e.hi[0] * a.u + e.lo[1] * a.v);
      addPoint(m, p + e.hi[0] * a.u + e.hi[1] * a.v);
      addPoint(m, p + e.lo[0] * a.u + e.hi[1] * a.v);
      addQuad(t, {first, first + 1, first + 2, first + 3});  // facing the fibres (+n)
      continue;
    }
    const int sides = def.toolSides;
    const double R = tools.radius[t];
    std::int64_t first = -1;
    for (double s : {e.lo[0], e.hi[0]})
      for (int k = 0; k < sides; ++k) {
        const double phi = 2 * std::numbers::pi * k / sides;
        const std::int64_t i =
            addPoint(m, p + s * a.n + R * (std::cos(phi) * a.u + std::sin(phi) * a.v));
        if (first < 0) first = i;
      }
    for (int k = 0; k < sides; ++k) {
      const std::int64_t k1 = (k + 1) % sides;
      addQuad(t, {first + k, first + k1, first + sides + k1, first + sides + k});
    }
  }
  VtuDocument doc(def.encoding, points.size() / 3, types.size());
  doc.open("<CellData Scalars=\"tool\">");
  doc.array("tool", 1, toolIndex);
  doc.array("kind", 1, kind);
  doc.close("</CellData>");
  writeGrid(doc, points, connectivity, offsets, types);
  doc.write(path);
}

}  // namespace fibra
