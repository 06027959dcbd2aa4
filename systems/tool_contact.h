// Tool contact system: contact between the fibres and rigid tools (planes, cylinders) with the
// laws of fibre-fibre contact (systems/contact_law.h).
//
// Motion: a tool's point x (at t = 0) is at M(t) x = c + R(t)(x - c) + d(t).
// Detection (reads FibreStore, q, ToolStore; writes ToolContactStore; once per contact loop):
//   along every fibre element, at the contact test locations (2 per quadratic element, 1 per
//   linear), a contact element is made when the centreline is within R + Delta of the surface
//   (Delta: the scene's proximity distance; by default max(R, h/2), h the element length, so
//   that a fibre approaching the tool has elements before it arrives);
//   its particle is the outline point facing the tool (paper Fig. 4 with the direction -N), its
//   normal N the surface normal at the closest point (towards the fibre), its tool point the
//   surface point under the particle, kept as a material point of the tool.
// Normals (loop B): N and the tool point re-evaluated at the particles' current positions.
// Assembly (per Newton iteration; serial: tool contacts are few): d = x(particle) - M(t) p,
//   the contact law, r -= D^T f and K += D^T S D into the particle's beam-element clique; the
//   force the fibres exert on each tool summed into ToolStore::reaction.
#pragma once

#include "components/linear_system.h"
#include "components/tools.h"
#include "systems/motion.h"

namespace fibra {

// Motion of tool t at time t (its centre defaults to its point).
RigidMotion toolMotion(const ToolStore& tools, Index tool, double time);

// Closest point of the tool's surface to x at time t, the unit normal there pointing to the
// fibres' side, and the signed distance of x from the surface along it (mm).
struct SurfacePoint {
  Vec3 point, normal;
  double distance;
};
SurfacePoint closestSurfacePoint(const ToolStore& tools, Index tool, const RigidMotion& m,
                                  const Vec3& x);

struct ToolContactParams {
  double proximity = 0;   // extra distance beyond the fibre radius that makes an element, mm (NaN: default)
  double pRegRatio = 0.5; // p_reg / p_max
  double gMax = 0;        // reversible slip, mm
  bool symmetrised = false;
};

void detectToolContacts(const FibreStore& fibres, const Eigen::VectorXd& q, const ToolStore& tools,
                        double time, double proximity, ToolContactStore& contacts);

void updateToolNormals(const FibreStore& fibres, const Eigen::VectorXd& q, const ToolStore& tools,
                       double time, ToolContactStore& contacts);

void assembleToolContacts(const FibreStore& fibres, const Eigen::VectorXd& q, ToolStore& tools,
                          ToolContactStore& contacts, const ToolContactParams& params,
                          double time, bool withTangent, LinearSystem& ls);

}  // namespace fibra
