// The yarn generator (paper section 5.3, Table 2; docs/SCENE.md "Generators"): n parallel fibres
// in a compact hexagonal section, optionally twisted into helices about the yarn axis, with a
// seeded random perturbation of their trajectories, expanded into polyline fibres and groups.
//
// Section: fibre centres on the hexagonal lattice of spacing d = 2R + gap, in rings of 1, 6,
// 12, 18, ... (1, 7, 19, 37, 61, 91, ... fibres in full rings); a count between those fills the
// outer ring partially, at evenly spread lattice sites.
// Trajectory of the fibre at section offset (x, y), s in [0, L] along the unit axis a:
//   P(s) = origin + s a + Rot(2 pi twist s / L) (x e1 + y e2) + u1(s) e1 + u2(s) e2,
// e1 the coordinate axis least aligned with a, made normal to it, e2 = a x e1; the
// perturbation u_d(s) = sum_m c_m sin(k_m pi s / L) vanishes at both ends, with integer wave
// numbers k_m in [1, 2L / min_wavelength] and sum_m |c_m| = amplitude, so |u_d| <= amplitude.
// Draws come from SeededRandom(seed), fibre by fibre, e1 then e2, mode by mode (k_m then c_m):
// the same seed gives the same yarn on every machine, and adding fibres keeps the first ones.
#pragma once

#include "core/types.h"
#include "io/json_reader.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fibra {

struct YarnPerturbation {
  double amplitude = 0;      // bound of each transverse offset u_d, mm; 0: straight fibres
  int modes = 3;             // sine modes per fibre and direction
  double minWavelength = 0;  // shortest wavelength 2L / k, mm (the reader's default: below)
  std::uint64_t seed = 0;
};

struct YarnDef {
  std::string name;       // prefix of the fibres' and groups' names
  std::string material;   // a material of the scene, by name
  int fibres = 0;         // fibre count
  double fibreRadius = 0; // R, mm
  double gap = 0;         // between neighbour fibre surfaces in the section, mm
  double length = 0;      // L, mm
  int elements = 0;       // per fibre
  int order = 2;          // 1 linear, 2 quadratic elements
  Vec3 origin = Vec3::Zero();  // the axis point where the yarn starts, mm
  Vec3 axis = Vec3::UnitZ();   // the yarn axis (normalised by the reader)
  double twist = 0;            // turns of the helices over the length (sign: handedness)
  YarnPerturbation perturbation;
};

// Polyline vertices per element of a generated fibre.
constexpr int kYarnPointsPerElement = 8;

// Reads and checks a yarn spec at `path` ("generators[i]"); errors name "PATH.field".
YarnDef readYarn(const json_reader::Json& spec, const std::string& path);

// Section offsets (x, y) of `count` fibre centres at lattice spacing `spacing` (mm), the first
// at the centre, ring after ring.
std::vector<std::array<double, 2>> hexagonalLayout(int count, double spacing);

// Every fibre's centreline as polyline vertices (kYarnPointsPerElement per element, plus one).
std::vector<std::vector<Vec3>> yarnCentrelines(const YarnDef& yarn);

// The transverse unit vectors e1, e2 of the section (see above).
std::array<Vec3, 2> yarnSectionAxes(const Vec3& axis);

// GeneratorExpand for "yarn": appends the fibres NAME.f0, NAME.f1, ... and the union groups
// NAME.start, NAME.end and NAME.all to the scene.
void expandYarn(const json_reader::Json& spec, const std::string& path, json_reader::Json& scene);

}  // namespace fibra
