// Tool stores: rigid tools (planes, cylinders), the zones of their contacts with each fibre and
// their contact elements. No logic here; see systems/tool_detection.h and systems/tool_contact.h.
#pragma once

#include "components/fibres.h"
#include "components/motion.h"
#include "components/particle_weights.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fibra {

enum class ToolKind { Plane, Cylinder };

struct ToolStore {
  // --- per tool: geometry at t = 0, motion, contact ---
  std::vector<std::string> name;
  std::vector<ToolKind> kind;
  std::vector<Vec3> point;      // plane: a point of it; cylinder: a point of its axis, mm
  std::vector<Vec3> direction;  // plane: normal, towards the fibres; cylinder: axis (both
                                // normalised when used)
  std::vector<double> radius;   // cylinder radius, mm
  std::vector<std::uint8_t> inside;  // cylinder: 1 when the fibres are inside it
  std::vector<PrescribedMotion> motion;  // centre NaN: the tool's point
  std::vector<double> friction; // mu between the tool and the fibres
  std::vector<double> pMax;     // maximum penetration aimed at, mm

  Index size() const { return Index(kind.size()); }
};

// The zone of a tool's contacts with one fibre, for every (tool, fibre): zone tool * fibres + f.
// Its penalty is adapted like a fibre-fibre zone's (eq. 13, systems/penalty_adapter.h).
struct ToolZoneStore {
  // --- per (tool, fibre) ---
  std::vector<double> penalty;  // k, N/mm
  std::vector<double> pMax;     // p_max aimed at, mm (the tool's)
  std::vector<double> stiffness;  // section stiffness E_f R_f, N/mm: scale of the penalty bounds
  std::vector<double> penaltyMin;  // bounds on k, multiples of `stiffness` (the contact section's)
  std::vector<double> penaltyMax;

  Index size() const { return Index(penalty.size()); }
};

// One contact element between a fibre particle and a tool (side I: the fibre, side J: the
// tool). Particles are material points: (element, z) along the fibre, (xi1, xi2) in the section.
struct ToolContactStore {
  // --- per tool contact element ---
  std::vector<Index> tool;
  std::vector<Index> zone;          // ToolZoneStore index: tool * fibres + fibre
  std::vector<Index> element;       // fibre element holding the particle
  std::vector<double> z;            // element parameter in [-1, 1]
  std::vector<double> length;       // the particle's share of the deformed centreline, mm (0 on
                                    // an end face): its line force is normal force / length
  std::vector<double> weight;       // scales the zone's penalty on this element: 1 lateral,
                                    // |t . N| on an end face (systems/tool_detection.cpp)
  std::vector<double> xi1, xi2;     // section coordinates of the particle, mm
  std::vector<ParticleWeights> side;  // the particle as weights on its element's DOFs
  std::vector<Vec3> normal;         // N, unit, from the tool to the fibre (fixed during Newton)
  std::vector<double> gap;          // (x - p) . N at detection or the last normal update, mm
  std::vector<Vec3> toolPoint;      // the tool's material point under the particle, in the
                                    // tool's t = 0 frame, mm: p(t) = M(t) toolPoint
  // friction reference (systems/friction_reference.h)
  std::vector<Vec3> d0;             // x - p at the reference, mm
  std::vector<Vec3> gRev0;          // reversible slip at the reference, mm

  Index size() const { return Index(tool.size()); }
};

}  // namespace fibra
