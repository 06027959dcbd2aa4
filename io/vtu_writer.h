// VTU writer system: the fibres of one state as a ParaView unstructured grid, and a time series
// of them listed in a PVD collection.
//
// Reads  FibreStore (topology, radius, names) and a state q ([x0 g1 g2] per node).
// Writes one .vtu file per call (XML, ASCII, shortest round-trip numbers), whole or not at all
//        (systems/output_file.h). Serial; the caller's thread.
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
// In ParaView the surface shows as is; for tubes drawn around the centrelines instead:
// Threshold part = 0, Extract Surface, Tube (vary radius by "radius").
#pragma once

#include "components/contact_snapshot.h"
#include "components/fibres.h"

#include <string>
#include <vector>

namespace fibra {

struct VtuDef {
  int tubeSides = 12;  // surface points around each section (>= 3)
};

void writeVtu(const std::string& path, const FibreStore& fibres, const Eigen::VectorXd& q,
              const VtuDef& def = {});

void writeContactVtu(const std::string& path, const ContactSnapshot& contacts);

// A series in `dir`: NAME_0000.vtu, NAME_0001.vtu, ... and NAME.pvd listing them with their
// pseudo-times (part 0); with contacts, NAME_contacts_0000.vtu, ... as part 1 of each time.
// After every write() the PVD lists exactly the frames on disk.
class VtuSeries {
 public:
  explicit VtuSeries(std::string dir, std::string name = "result", VtuDef def = {});

  void write(const FibreStore& fibres, const Eigen::VectorXd& q, double time,
             const ContactSnapshot* contacts = nullptr);
  int frames() const { return int(times_.size()); }
  std::string pvdPath() const;

 private:
  std::string framePath(int frame, const char* part = "") const;
  std::string dir_, name_;
  VtuDef def_;
  std::vector<double> times_;
  std::vector<bool> contacts_;  // per frame: a contact file was written
};

}  // namespace fibra
