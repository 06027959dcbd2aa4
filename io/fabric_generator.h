// The woven-fabric generator (paper section 5.2, Fig. 8, Table 1; docs/SCENE.md "Generators"):
// warp yarns along x and weft yarns along y, each yarn a bundle of straight parallel fibres in
// a compact hexagonal section, all in the plane z = 0 where they interpenetrate (the flat start
// of the initial-geometry procedure) or already over and under each other (the crimped start,
// below), expanded into fibres with their contact `class` and `levels` (the weave pattern, for a
// step with forced normals) and named union groups.
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
//
// Crimped start ("start": "crimped"; "flat", the default, is the layout above): every fibre a
// polyline that already follows the weave, no two fibres overlapping. Section of a direction:
// the offsets (a_k, b_k) of hexagonalLayout(n, 2R + gap) centred on their bounding box,
//   u_k = a_k - (max a + min a)/2 (across the yarn),  v_k = b_k - (max b + min b)/2 (vertical),
//   width w = max a - min a + 2R,  thickness t = max b - min b + 2R,  v_max = max |v_k|.
// Crimp height H = (t_warp + t_weft + gap_warp + gap_weft)/4: where warp c goes over weft r,
// warp c's axis lies at z = +H and weft r's at -H (the opposite where it goes under), so the
// nearest fibres of the two sections there are 2R + (gap_warp + gap_weft)/2 apart (centres).
// Axis profile of a yarn along its own coordinate x (x for a warp, y for a weft), the crossing
// yarns' axes X_j = X_0 + j s' (s', w' their spacing and width), levels l_j = +-1 as above:
//   z(x) = l_j H                     on the plateau |x - X_j| <= w'/2, and before the first
//                                    crossing's plateau and after the last one's (to the ends),
//   z(x) = l_j H cos(pi tau),  tau = (x - X_j - w'/2)/g,  g = s' - w',  on the ramp between
//                                    plateaus j and j + 1 when l_{j+1} = -l_j (else z = l_j H):
// C1, its slope 0 at both ends of a ramp. Fibre k of warp yarn c (a weft swaps x and y):
//   P_k(x) = (x, y_c + u_k, z(x)) + v_k n(x),  n = (-z', 0, 1)/sqrt(1 + z'^2),
// the normal offset in the vertical plane: the fibres of a yarn are parallel curves, at their
// section's spacing everywhere, while the axis' radius of curvature rho = (1 + z'^2)^(3/2)/|z''|
// exceeds v_max; on a ramp its least, at the ramp's ends, is g^2/(pi^2 H). The inner fibres'
// radius rho - v_max is asked to be at least kCrimpBendRadii R, so a direction whose crossing
// yarns ramp needs the other direction's spacing s' > w' + pi sqrt(H (v_max + kCrimpBendRadii R)),
// and every direction of two yarns or more s > w (side by side, room for a ramp) (errors name
// the spacing).
// The ends stay at x = +-L/2 (z' = 0 there: the offsets are vertical). Vertices uniform in x,
// kCrimpPointsPerElement per element, plus one (a chord of length l on radius rho sags
// l^2/(8 rho)); director +z at the start, where the profile is flat: transported without twist it
// is n along the whole fibre, as +z is for the flat start. Levels: as above, each warp fibre's
// pieces changing at its own arc length halfway (in x) between crossings.
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

// How the fibres start: straight in z = 0 (the yarns interpenetrate) or crimped (above).
enum class FabricStart { Flat, Crimped };

struct FabricDef {
  std::string name;  // prefix of the fibres', classes' and groups' names
  WeavePattern pattern;
  WeaveDirection warp, weft;
  FabricStart start = FabricStart::Flat;
};

// Polyline vertices per element of a crimped fibre.
constexpr int kCrimpPointsPerElement = 16;
// The least radius of curvature of a crimped fibre, in fibre radii: its bending strain R / rho
// at the start at most 10%. (Offset curves only need rho > 0: at spacing 0.35 mm a 7-fibre
// yarn's inner fibres bent at 2.8 um and the start did not solve under its end tensions.)
constexpr double kCrimpBendRadii = 10;

// A direction's section for the crimped start: offsets (u_k, v_k) centred on their bounding box,
// width w, thickness t and v_max (mm).
struct YarnSection {
  std::vector<std::array<double, 2>> offsets;
  double width = 0, thickness = 0, vMax = 0;
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

YarnSection yarnSection(const WeaveDirection& d);

// The crimp height H (mm).
double crimpHeight(const FabricDef& f);

// The axis profile z(x) of yarn c of the warp (warp = true) or weft, x its own coordinate (mm).
struct CrimpProfile {
  std::vector<int> level;  // l_j = +-1 at crossing j
  double first = 0;        // X_0, mm
  double spacing = 0;      // s' of the crossing yarns, mm
  double halfWidth = 0;    // w'/2 of the crossing yarns, mm
  double height = 0;       // H, mm
  // z and dz/dx at x (mm, 1).
  std::array<double, 2> at(double x) const;
};
CrimpProfile crimpProfile(const FabricDef& f, bool warp, int c);

// Polyline vertices of fibre k of yarn c of the warp (warp = true) or weft, crimped start (mm).
std::vector<Vec3> crimpedCentreline(const FabricDef& f, bool warp, int c, int k);

// The level table of a crimped warp fibre whose vertices are `points` (its own arc length, mm).
std::vector<std::array<double, 2>> crimpedWarpLevels(const FabricDef& f, int c,
                                                      const std::vector<Vec3>& points);

// The checks of a crimped start's spacings; errors name "PATH.warp.spacing" or ".weft.spacing".
void checkCrimp(const FabricDef& f, const std::string& path);

// GeneratorExpand for "woven_fabric": appends the fibres NAME.warpC.fK and NAME.weftR.fK and
// the union groups (docs/SCENE.md, "Woven fabric") to the scene.
void expandWovenFabric(const json_reader::Json& spec, const std::string& path,
                       json_reader::Json& scene);

}  // namespace fibra
