// A reader for the VTU files fibra writes (io/vtu_document.h): every DataArray of a file, ASCII
// or zlib-compressed appended binary, as doubles (integers convert exactly). Used by
// `fibra section` (io/section_cut.h) to read a frame back, and by the tests.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace fibra {

// Key: "SECTION/NAME" (Points/ for the points, PointData/radius, Cells/types, ...).
using VtuArrays = std::map<std::string, std::vector<double>>;

// Every array of the VTU text `file`; throws std::runtime_error on anything malformed.
VtuArrays readVtuArrays(const std::string& file);

// The VTU files of part 0 (the fibres) listed by a PVD collection's text, in its order, with
// their pseudo-times; throws std::runtime_error when it lists none.
struct PvdFrame {
  double time;
  std::string file;  // relative to the PVD's directory
};
std::vector<PvdFrame> readPvdFrames(const std::string& pvdText);

}  // namespace fibra
