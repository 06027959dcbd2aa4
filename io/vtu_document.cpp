#include "io/vtu_document.h"

#include "io/output_file.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace fibra {
namespace {

static_assert(std::endian::native == std::endian::little, "VTU binary output is little-endian");
constexpr size_t kBlock = 32768;  // uncompressed bytes per zlib block, as VTK writes them

void appendWord(std::string& out, std::uint64_t v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

VtuDocument::VtuDocument(VtuEncoding encoding, size_t points, size_t cells) : encoding_(encoding) {
  xml_ = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (encoding_ == VtuEncoding::Binary) xml_ += " compressor=\"vtkZLibDataCompressor\"";
  xml_ += ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(points) +
          "\" NumberOfCells=\"" + std::to_string(cells) + "\">\n";
}

void VtuDocument::appendCompressed(const void* data, size_t bytes) {
  const size_t blocks = (bytes + kBlock - 1) / kBlock;
  const size_t last = blocks == 0 ? 0 : bytes - (blocks - 1) * kBlock;
  std::vector<std::string> compressed(blocks);
  for (size_t b = 0; b < blocks; ++b) {
    const size_t size = b + 1 == blocks ? last : kBlock;
    uLongf length = compressBound(uLong(size));
    compressed[b].resize(length);
    const auto* source = static_cast<const Bytef*>(data) + b * kBlock;
    if (compress2(reinterpret_cast<Bytef*>(compressed[b].data()), &length, source, uLong(size),
                  Z_DEFAULT_COMPRESSION) != Z_OK)
      throw std::runtime_error("zlib: cannot compress a VTU array");
    compressed[b].resize(length);
  }
  appendWord(appended_, blocks);
  appendWord(appended_, kBlock);
  appendWord(appended_, last);
  for (const std::string& c : compressed) appendWord(appended_, c.size());
  for (const std::string& c : compressed) appended_ += c;
}

template <class T>
void VtuDocument::addArray(const char* type, const char* name, int components,
                           const std::vector<T>& values) {
  xml_ += std::string("<DataArray type=\"") + type + "\"";
  if (name) xml_ += std::string(" Name=\"") + name + "\"";
  if (components > 1) xml_ += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  if (encoding_ == VtuEncoding::Binary) {
    xml_ += " format=\"appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
    appendCompressed(values.data(), values.size() * sizeof(T));
    return;
  }
  xml_ += " format=\"ascii\">\n";
  for (size_t i = 0; i < values.size(); ++i) {
    if constexpr (std::is_floating_point_v<T>)
      appendNumber(xml_, values[i]);
    else
      xml_ += std::to_string(values[i]);
    xml_ += (i + 1) % (components * 4) == 0 ? '\n' : ' ';
  }
  xml_ += "\n</DataArray>\n";
}

void VtuDocument::array(const char* name, int components, const std::vector<double>& v) {
  addArray("Float64", name, components, v);
}
void VtuDocument::array(const char* name, int components, const std::vector<std::int32_t>& v) {
  addArray("Int32", name, components, v);
}
void VtuDocument::array(const char* name, int components, const std::vector<std::int64_t>& v) {
  addArray("Int64", name, components, v);
}
void VtuDocument::array(const char* name, int components, const std::vector<std::uint8_t>& v) {
  addArray("UInt8", name, components, v);
}

void VtuDocument::write(const std::string& path) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << xml_ << "</Piece>\n</UnstructuredGrid>\n";
  if (encoding_ == VtuEncoding::Binary) {
    out << "<AppendedData encoding=\"raw\">\n_";
    out.write(appended_.data(), std::streamsize(appended_.size()));
    out << "\n</AppendedData>\n";
  }
  out << "</VTKFile>\n";
  file.commit();
}

}  // namespace fibra
