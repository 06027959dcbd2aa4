// A VTK XML file (UnstructuredGrid, one piece) being written: its DataArrays as ASCII text or as
// zlib-compressed binary in an appended section, the format ParaView reads fastest and smallest.
//
//   VtuDocument doc(VtuEncoding::Binary, points, cells);
//   doc.open("<PointData Scalars=\"radius\">");
//   doc.array("radius", 1, radius);            // std::vector<double | int32 | int64 | uint8>
//   doc.close("</PointData>");
//   ... <CellData>, <Points>, <Cells> the same way ...
//   doc.write(path);                           // whole or not at all (io/output_file.h)
//
// Binary: each array is `format="appended" offset="N"`, N its byte offset in the AppendedData
// section (encoding "raw", after its '_'); there an array is a header of UInt64 [blocks,
// block size, last block's size, compressed size of each block] followed by its blocks, each
// up to 32768 bytes of little-endian values compressed by zlib (compressor
// "vtkZLibDataCompressor"). ASCII: values inline, floats as the shortest decimal that reads back
// exactly. Either way the values are the same bits.
#pragma once

#include "engine/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fibra {

class VtuDocument {
 public:
  VtuDocument(VtuEncoding encoding, size_t points, size_t cells);

  void open(const std::string& tag) { xml_ += tag + "\n"; }
  void close(const std::string& tag) { xml_ += tag + "\n"; }
  // One DataArray; name nullptr for the Points array. Throws std::runtime_error if zlib fails.
  void array(const char* name, int components, const std::vector<double>& values);
  void array(const char* name, int components, const std::vector<std::int32_t>& values);
  void array(const char* name, int components, const std::vector<std::int64_t>& values);
  void array(const char* name, int components, const std::vector<std::uint8_t>& values);
  // Closes the document and writes it to `path`; throws std::runtime_error.
  void write(const std::string& path);

 private:
  template <class T>
  void addArray(const char* type, const char* name, int components, const std::vector<T>& v);
  void appendCompressed(const void* data, size_t bytes);
  VtuEncoding encoding_;
  std::string xml_, appended_;
};

}  // namespace fibra
