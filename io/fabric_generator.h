// The woven-fabric generator (paper section 5.2, Fig. 8, Table 1; docs/SCENE.md "Generators"):
// warp yarns along x and weft yarns along y, each yarn a bundle of straight parallel fibres in
// a compact hexagonal section, all in the plane z = 0 where they interpenetrate (the flat start
// of the initial-geometry procedure), expanded into fibres with their contact `class` and
// `levels` (the weave pattern, for a step with forced normals) and named union groups.
//
// Layout: warp yarn c (c = 0 .. nWarp - 1) has its axis at y_c = (c - (nWarp - 1)/2) sWarp,
// z = 0, from x = -Lwarp/2 to Lwarp/2; weft yarn r at x_r = (r - (nWeft - 1)/2) sWeft, from
// y = -Lweft/2 to Lweft/2. The section: the hexagonal rings of the yarn generator
// (hexagonalLayout, spacing 2R + gap), its first offset across the yarn in the plane (y for a
// warp yarn, x for a weft yarn), its second along z.
// Pattern: a matrix P of 0/1, rows = weft yarns, columns = warp yarns, repeated over the
// fabric; P[r mod rows][c mod cols] = 1: warp yarn c goes over weft yarn r at their crossing.
// Levels: a warp fibre of yarn c has level +1 on the piece holding weft crossing r when the
// pattern puts warp c over weft r there, -1 otherwise, the pieces changing halfway between
// crossings; weft fibres keep level 0. Classes: "NAME.warp" and "NAME.weft".
#pragma once

#include "core/types.h"
#include "io/json_reader.h"

#include <array>
#include <string>
#include <vector>

namespace fibra {

// One yarn direction of a fabric (its `warp` or `weft` object).
struct WeaveDirection {
  int yarns = 0;            // yarn count
  double spacing = 0;       // between neighbour yarn axes, mm
  int fibresPerYarn = 0;    // in the hexagonal section
  double fibreRadius = 0;   // R, mm
  double gap = 0;           // between neighbour fibre surfaces in the section, mm
  std::string material;     // a material of the scene, by name
  int elements = 0;         // per fibre
  int order = 2;            // 1 linear, 2 quadratic elements
  double length = 0;        // of every fibre, mm (the reader fills the default)
};

// Weave pattern: cell[r][c] = 1 where warp yarn c goes over weft yarn r (r, c modulo the size).
using WeavePattern = std::vector<std::vector<int>>;

struct FabricDef {
  std::string name;  // prefix of the fibres', classes' and groups' names
  WeavePattern pattern;
  WeaveDirection warp, weft;
};

// Reads and checks a woven_fabric spec at `path` ("generators[i]"); errors name "PATH.field".
FabricDef readFabric(const json_reader::Json& spec, const std::string& path);

// Named weaves: "plain" (2 x 2), "twill" with `over` and `under` (a diagonal of over/under
// floats shifted by one yarn per weft: P[r][c] = 1 when (c - r) mod (over + under) < over),
// "satin" with `repeat` n and `step` s (warp c over weft r only where c = r s mod n).
WeavePattern plainWeave();
WeavePattern twillWeave(int over, int under);
WeavePattern satinWeave(int repeat, int step);

// 1 where warp yarn c goes over weft yarn r in the fabric (the pattern repeated).
int warpOver(const FabricDef& f, int r, int c);

// Axis position of yarn k of a direction across the fabric (y of a warp, x of a weft), mm.
double yarnAxisPosition(const WeaveDirection& d, int k);

// Start and end points of fibre k of yarn c of the warp (warp = true) or weft, mm.
std::array<Vec3, 2> fabricFibreEnds(const FabricDef& f, bool warp, int c, int k);

// The level table [[from, level], ...] of a fibre of warp yarn c (reference arc length, mm).
std::vector<std::array<double, 2>> warpLevels(const FabricDef& f, int c);

// GeneratorExpand for "woven_fabric": appends the fibres NAME.warpC.fK and NAME.weftR.fK and
// the union groups (docs/SCENE.md, "Woven fabric") to the scene.
void expandWovenFabric(const json_reader::Json& spec, const std::string& path,
                       json_reader::Json& scene);

}  // namespace fibra
