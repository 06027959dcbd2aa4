#include "io/vtu_reader.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace fibra {
namespace {

std::uint64_t word(const std::string& data, size_t at) {
  if (at + 8 > data.size()) throw std::runtime_error("VTU: appended data truncated");
  std::uint64_t v;
  std::memcpy(&v, data.data() + at, 8);
  return v;
}

// The bytes of the compressed array at `offset` of the appended data.
std::string inflateArray(const std::string& appended, size_t offset) {
  const std::uint64_t blocks = word(appended, offset), block = word(appended, offset + 8),
                      last = word(appended, offset + 16);
  size_t at = offset + 24 + 8 * blocks;
  std::string out;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t size = word(appended, offset + 24 + 8 * b);
    if (at + size > appended.size()) throw std::runtime_error("VTU: block truncated");
    std::string raw(b + 1 == blocks && last != 0 ? last : block, '\0');  // 0: a full block
    uLongf length = raw.size();
    if (uncompress(reinterpret_cast<Bytef*>(raw.data()), &length,
                   reinterpret_cast<const Bytef*>(appended.data() + at), size) != Z_OK ||
        length != raw.size())
      throw std::runtime_error("VTU: a block does not inflate");
    out += raw;
    at += size;
  }
  return out;
}

template <class T>
std::vector<double> decode(const std::string& bytes) {
  if (bytes.size() % sizeof(T) != 0) throw std::runtime_error("VTU: array size");
  std::vector<double> v(bytes.size() / sizeof(T));
  for (size_t i = 0; i < v.size(); ++i) {
    T x;
    std::memcpy(&x, bytes.data() + i * sizeof(T), sizeof(T));
    v[i] = double(x);
  }
  return v;
}

std::vector<double> decodeTyped(const std::string& type, const std::string& bytes) {
  if (type == "Float64") return decode<double>(bytes);
  if (type == "Int32") return decode<std::int32_t>(bytes);
  if (type == "Int64") return decode<std::int64_t>(bytes);
  if (type == "UInt8") return decode<std::uint8_t>(bytes);
  throw std::runtime_error("VTU: unknown type " + type);
}

std::vector<double> asciiValues(const std::string& xml, size_t tagAt) {
  const size_t from = xml.find('>', tagAt) + 1;
  std::istringstream text(xml.substr(from, xml.find("</DataArray>", from) - from));
  std::vector<double> v;
  for (std::string token; text >> token;) v.push_back(std::stod(token));
  return v;
}

}  // namespace

VtuArrays readVtuArrays(const std::string& file) {
  const size_t appendedTag = file.find("<AppendedData encoding=\"raw\">");
  std::string appended;
  if (appendedTag != std::string::npos) {
    const size_t start = file.find('_', appendedTag) + 1;
    const size_t end = file.rfind("\n</AppendedData>");
    if (start == 0 || end == std::string::npos || end < start)
      throw std::runtime_error("VTU: malformed AppendedData");
    appended = file.substr(start, end - start);
  }
  const std::string xml = file.substr(0, appendedTag);
  static const std::regex tag(
      R"re(<(PointData|CellData|Points|Cells)[ >]|<DataArray type="(\w+)"(?: Name="([^"]*)")?(?: NumberOfComponents="\d+")? format="(\w+)"(?: offset="(\d+)")?)re");
  VtuArrays arrays;
  std::string section;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), tag); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    if (m[1].matched) {
      section = m[1];
      continue;
    }
    const std::string key = section + "/" + m[3].str();
    arrays[key] = m[4] == "appended"
                      ? decodeTyped(m[2], inflateArray(appended, std::stoull(m[5])))
                      : asciiValues(xml, size_t(m.position(0)));
  }
  return arrays;
}

std::vector<PvdFrame> readPvdFrames(const std::string& pvdText) {
  static const std::regex dataset(
      R"re(<DataSet timestep="([^"]*)" part="0" file="([^"]*)"/>)re");
  std::vector<PvdFrame> frames;
  for (auto it = std::sregex_iterator(pvdText.begin(), pvdText.end(), dataset);
       it != std::sregex_iterator(); ++it)
    frames.push_back({std::stod((*it)[1].str()), (*it)[2].str()});
  if (frames.empty()) throw std::runtime_error("lists no frame");
  return frames;
}

}  // namespace fibra
