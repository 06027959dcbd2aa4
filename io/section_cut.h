// Cross-sections of the fibres cut by a plane normal to a coordinate axis, as the paper draws
// them (Figs. 11-12, 17): each fibre's section is an outline in the cut plane, a circle for a
// round fibre normal to the plane, an ellipse for one crossing it at an angle or with a
// flattened section. What `fibra section` draws (docs/PLOTS.md).
//
//   const fibra::FibreFrame frame = fibra::readFibreFrame("out/yarn", -1);  // the last frame
//   const fibra::CutPlane plane = fibra::medianPlane(frame);
//   for (const fibra::SectionOutline& s : fibra::cutSections(frame, plane)) ...
//
// Geometry (paper eq. 2): the material points of a fibre are x0(s) + xi1 g1(s) + xi2 g2(s)
// with (xi1, xi2) in the reference disc of radius R. Between nodes x0, g1 and g2 are
// interpolated linearly (the VTU frames hold them at the nodes; the VTU surface is the same
// ruled surface). A fibre crosses the plane where its centreline does; for each of `sides`
// angles phi the rim line x0(s) + R (cos phi g1(s) + sin phi g2(s)) is followed to where it
// meets the plane, nearest to the centreline's crossing. The outline is those points, so
// obliquity and the section's deformation both show. Rim lines that leave the fibre's end
// before meeting the plane are skipped (an end face cut shows as a partial outline).
// Where the centreline meets the plane at less than 30 deg, or runs beside it within R, the rim
// lines meet the plane far from the crossing (or not at all): the cut is then drawn as the union
// of the chords in which the plane cuts the section discs, sampled 16 per element, each run of s
// whose discs reach the plane one band (a shallow crossing's long ellipse, a yarn lying along
// the cut).
#pragma once

#include "core/types.h"
#include "io/vtu_reader.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace fibra {

// The fibres of one frame, as the VTU holds them.
struct FibreFrame {
  std::vector<Vec3> x0, g1, g2;          // per node: centreline position (mm), directors
  std::vector<double> radius;            // per node, mm
  std::vector<std::vector<Index>> fibres;  // per fibre its nodes, in order
  double time = 0;                       // pseudo-time
  std::string file;                      // the VTU file read ("" when built in code)
};

// The plane x[axis] = value (axis 0, 1, 2 for x, y, z; value in mm).
struct CutPlane {
  int axis = 2;
  double value = 0;
};

// The section of one fibre in the plane.
struct SectionOutline {
  Index fibre = 0;           // index of the fibre in the frame
  double s = 0;              // where its centreline crosses (a band: the middle of its run),
                             // node index + fraction
  Vec3 centre;               // the centreline's crossing point (a band: the centreline at s,
                             // projected on the plane), mm
  std::vector<Vec3> points;  // the outline, in the plane, in order of phi (a band: one side's
                             // chord ends along s, the other's back), mm
};

// Every fibre's sections by `plane` (a fibre crossing it several times has several): `sides`
// outline points each (>= 3) at steep crossings, the chord ends of its band otherwise.
std::vector<SectionOutline> cutSections(const FibreFrame& frame, const CutPlane& plane,
                                        int sides = 48);

// The plane normal to `axis` through the middle of the nodes' span along it; axis -1: the axis
// along which the nodes spread the most (a yarn's median plane).
CutPlane medianPlane(const FibreFrame& frame, int axis = -1);

// The two in-plane axes drawn as (horizontal, vertical): z -> (x, y), x -> (y, z), y -> (z, x).
std::array<int, 2> planeAxes(int axis);

// The fibres of a VTU file's arrays (io/vtu_reader.h): points, g1, g2, radius and the
// poly-line cells of part 0. std::runtime_error when arrays are missing or inconsistent.
FibreFrame fibreFrameFromVtu(const VtuArrays& arrays);

// The frames of RUN_DIR/result.pvd (part 0); PlotInputError when there are none.
std::vector<PvdFrame> readRunFrames(const std::string& runDir);

// Frame `index` (0-based, -1 for the last) of a run with `count` frames, as an index in
// 0..count-1; PlotInputError naming RUN_DIR/result.pvd when it is out of range.
int frameIndex(const std::string& runDir, int index, int count);

// Frame `index` (0-based, -1 for the last) of RUN_DIR/result.pvd; PlotInputError when the run
// has no frames or `index` is out of range. `chosen` receives the frame's index.
FibreFrame readFibreFrame(const std::string& runDir, int index, int* chosen = nullptr);

// Where the plane cuts the polygons of a VTU file's arrays (a tool's surface): one segment per
// polygon whose edges cross the plane twice (mm).
struct Segment {
  Vec3 a, b;
};
std::vector<Segment> cutPolygons(const VtuArrays& arrays, const CutPlane& plane);

// The tools of a frame cut by the plane: the series' tool file beside the fibres' VTU
// (result_tools_NNNN.vtu for result_NNNN.vtu); empty when the run has no tools.
std::vector<Segment> readToolCut(const std::string& frameFile, const CutPlane& plane);

// A section picture.
struct SectionPlot {
  int axis = -1;                  // 0, 1, 2 (x, y, z); -1: the axis the nodes spread most along
  std::optional<double> value;    // the plane's coordinate, mm; nullopt: the middle of the span
  int frame = -1;                 // -1: the last
  std::string file;               // the PNG; relative paths from the run's directory
  std::string title;              // "" for the default (plane, frame, time)
  int sides = 48;
};

struct SectionResult {
  std::string png, script, data;  // the files written
  CutPlane plane;
  int frame = 0;
  double time = 0;
  int sections = 0;
  int toolSegments = 0;  // pieces of the tools' surfaces in the plane, drawn as grey lines
};

// What a section picture shows: the in-plane ranges (mm; the sections' box with a margin, so
// that large tools do not shrink the fibres) and whether there are tool segments.
struct SectionView {
  std::array<double, 2> lo{}, hi{};
  bool tools = false;
};

// The gnuplot script drawing `data`: index 0 the outlines (one block per section, blank lines
// between), index 1 the tool segments, with equal axis scales.
std::string sectionScript(const CutPlane& plane, const std::string& data, const std::string& png,
                          const std::string& title, const SectionView& view);

// Cuts frame `plot.frame` of RUN_DIR and draws it: writes FILE.dat (the outlines and the tool
// segments, in-plane coordinates in mm) and FILE.gp beside the PNG and runs gnuplot
// (io/plot.h). PlotInputError when no fibre crosses the plane.
SectionResult drawSection(const std::string& runDir, const SectionPlot& plot);

}  // namespace fibra
