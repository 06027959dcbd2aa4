// VTU writer system: the fibres of one state as a ParaView unstructured grid, and a time series
// of them listed in a PVD collection.
//
// Reads  FibreStore (topology, radius, names) and a state q ([x0 g1 g2] per node).
// Writes one .vtu file per call, whole or not at all (io/output_file.h): XML with its arrays
//        zlib-compressed in an appended binary section (the default), or ASCII with the
//        shortest round-trip numbers (io/vtu_document.h). Serial; the caller's thread.
//
// Content of a file, one piece:
//   points  0 .. nodes-1: the centreline nodes x0, in the store's node order;
//           then, per node, `tubeSides` surface points x0 + R cos(phi) g1 + R sin(phi) g2,
//           phi = 2 pi k / tubeSides: the deformed section outline (paper eq. 2 on the rim of the
//           reference disc, so elliptical sections show).
//   cells   per fibre one poly-line through its nodes (part 0); the tube surface as quads between
//           consecutive sections, outward-facing, and a polygon closing each end (part 1).
//   point data  radius (mm), g1, g2 (the node's directors), fibre (index in the store);
//   cell data   fibre, part (0 centreline, 1 surface).
// Contact files (writeContactVtu): one line cell per contact element from x^I to x^J (for a
// tool: to the surface point below x^I), cell data normal, gap (mm), normal_force (N), friction
// (N, on I), slip (1 sliding), tool (1 fibre-tool), fibre_i, fibre_j. Glyph the Cell Centers by
// normal scaled by normal_force to see the contact forces.
// Tool files (writeToolVtu): each tool's surface at the frame's time, moved by its motion
// (systems/tool_geometry.h): a plane as one quad, a patch of it covering the fibres; a cylinder as
// `toolSides` quads around its axis over the length the fibres span along it (ToolExtents, from
// the first frame's fibres, then fixed in the tool's frame). Cell data tool (index in the store),
// kind (0 plane, 1 cylinder).
// In ParaView the surface shows as is; for tubes drawn around the centrelines instead:
// Threshold part = 0, Extract Surface, Tube (vary radius by "radius").
#pragma once

#include "components/contact_snapshot.h"
#include "components/fibres.h"
#include "components/tools.h"
#include "engine/scene.h"
#include "io/vtu_document.h"

#include <string>
#include <vector>

namespace fibra {

struct VtuDef {
  int tubeSides = 12;  // surface points around each section (>= 3)
  VtuEncoding encoding = VtuEncoding::Binary;
  int toolSides = 32;  // quads around a cylinder tool (>= 3)
};

// Errors: std::invalid_argument for a bad VtuDef, std::runtime_error when the file cannot be
// written.
void writeVtu(const std::string& path, const FibreStore& fibres, const Eigen::VectorXd& q,
              const VtuDef& def = {});

void writeContactVtu(const std::string& path, const ContactSnapshot& contacts,
                     const VtuDef& def = {});

// The part of each tool drawn, in its t = 0 frame: a plane from lo to hi along two in-plane axes
// (u = direction.unitOrthogonal(), v = direction x u), a cylinder from lo[0] to hi[0] along its
// axis; distances in mm from the tool's point. Covers the fibres' nodes of q (x0) projected on
// the tool, with a margin of 10% of their span plus 2 radii (at least 1 mm).
// Points, then Cells (connectivity, offsets, types) of a document (io/vtu_document.h).
void writeGrid(VtuDocument& doc, const std::vector<double>& points,
               const std::vector<std::int64_t>& connectivity,
               const std::vector<std::int64_t>& offsets, const std::vector<std::uint8_t>& types);

struct ToolExtent {
  double lo[2], hi[2];
};
std::vector<ToolExtent> toolExtents(const ToolStore& tools, const FibreStore& fibres,
                                    const Eigen::VectorXd& q);

void writeToolVtu(const std::string& path, const ToolStore& tools,
                  const std::vector<ToolExtent>& extents, double time, const VtuDef& def = {});

// One frame of a series: the fibres in state q at pseudo-time `time`, and optionally the
// contact elements and the tools.
struct VtuFrame {
  const FibreStore& fibres;
  const Eigen::VectorXd& q;
  double time;
  const ContactSnapshot* contacts = nullptr;
  const ToolStore* tools = nullptr;
};

// A series in `dir`: NAME_0000.vtu, NAME_0001.vtu, ... and NAME.pvd listing them with their
// pseudo-times (part 0); with contacts, NAME_contacts_0000.vtu, ... as part 1 of each time; with
// tools, NAME_tools_0000.vtu, ... as part 2 (their extents fixed at the first frame with tools).
// After every write() the PVD lists exactly the frames on disk.
class VtuSeries {
 public:
  explicit VtuSeries(std::string dir, std::string name = "result", VtuDef def = {});

  void write(const VtuFrame& frame);
  void write(const FibreStore& fibres, const Eigen::VectorXd& q, double time,
             const ContactSnapshot* contacts = nullptr) {
    write(VtuFrame{fibres, q, time, contacts});
  }
  // Continues a series whose frames 0 .. times.size() - 1 are on disk (a resumed run), each with
  // a contact file when `contacts` and a tool file when `tools`, the tools drawn over
  // `extents`; the next write() is frame times.size(). Rewrites the PVD to list exactly those.
  void resume(std::vector<double> times, bool contacts, bool tools,
              std::vector<ToolExtent> extents);
  int frames() const { return int(times_.size()); }
  std::string pvdPath() const;

 private:
  std::string framePath(int frame, const char* part = "") const;
  void writePvd() const;
  std::string dir_, name_;
  VtuDef def_;
  std::vector<double> times_;
  std::vector<bool> contacts_, tools_;  // per frame: a contact file, a tool file was written
  std::vector<ToolExtent> extents_;
};

}  // namespace fibra
