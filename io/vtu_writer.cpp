#include "io/vtu_writer.h"

#include "io/output_file.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>

namespace fibra {
namespace {

constexpr int kLine = 3, kPolyLine = 4, kPolygon = 7, kQuad = 9;  // VTK cell types

struct Cells {
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<int> type, fibre, part;
  void add(int cellType, Index f, int cellPart, std::initializer_list<std::int64_t> points) {
    connectivity.insert(connectivity.end(), points);
    close(cellType, f, cellPart);
  }
  void close(int cellType, Index f, int cellPart) {
    offsets.push_back(std::int64_t(connectivity.size()));
    type.push_back(cellType);
    fibre.push_back(f);
    part.push_back(cellPart);
  }
};

// Surface point k of node n: after the centreline nodes, `sides` per node.
std::int64_t rim(const FibreStore& fs, int sides, Index n, int k) {
  return fs.nodes() + std::int64_t(n) * sides + (k % sides);
}

Cells buildCells(const FibreStore& fs, int sides) {
  Cells c;
  for (Index f = 0; f < fs.fibres(); ++f) {
    const Index first = fs.firstNode[f], last = first + fs.nodeCount[f] - 1;
    for (Index n = first; n <= last; ++n) c.connectivity.push_back(n);
    c.close(kPolyLine, f, 0);
    // (e_r, e_phi, t) is right-handed (g1 x g2 along t), so k -> k+1 -> next section faces out.
    for (Index n = first; n < last; ++n)
      for (int k = 0; k < sides; ++k)
        c.add(kQuad, f, 1,
              {rim(fs, sides, n, k), rim(fs, sides, n, k + 1), rim(fs, sides, n + 1, k + 1),
               rim(fs, sides, n + 1, k)});
    for (int k = sides - 1; k >= 0; --k) c.connectivity.push_back(rim(fs, sides, first, k));
    c.close(kPolygon, f, 1);  // start cap, facing -t
    for (int k = 0; k < sides; ++k) c.connectivity.push_back(rim(fs, sides, last, k));
    c.close(kPolygon, f, 1);  // end cap, facing +t
  }
  return c;
}

template <class T>
void dataArray(std::ostream& out, const char* type, const char* name, int components,
               const std::vector<T>& values) {
  out << "<DataArray type=\"" << type << "\"";
  if (name) out << " Name=\"" << name << "\"";
  if (components > 1) out << " NumberOfComponents=\"" << components << "\"";
  out << " format=\"ascii\">\n";
  std::string text;
  for (size_t i = 0; i < values.size(); ++i) {
    if constexpr (std::is_floating_point_v<T>)
      appendNumber(text, values[i]);
    else
      text += std::to_string(values[i]);
    text += (i + 1) % (components * 4) == 0 ? '\n' : ' ';
  }
  out << text << "\n</DataArray>\n";
}

// Per-point arrays: centreline nodes, then `sides` rim points per node.
struct PointArrays {
  std::vector<double> position, radius, g1, g2;
  std::vector<int> fibre;
  void add(const Vec3& x, double r, const Vec3& a, const Vec3& b, Index f) {
    position.insert(position.end(), x.data(), x.data() + 3);
    radius.push_back(r);
    g1.insert(g1.end(), a.data(), a.data() + 3);
    g2.insert(g2.end(), b.data(), b.data() + 3);
    fibre.push_back(f);
  }
};

PointArrays buildPoints(const FibreStore& fs, const Eigen::VectorXd& q, int sides) {
  PointArrays p;
  for (Index n = 0; n < fs.nodes(); ++n) {
    const Index f = fs.nodeFibre[n];
    p.add(x0Of(q, n), fs.radius[f], g1Of(q, n), g2Of(q, n), f);
  }
  for (Index n = 0; n < fs.nodes(); ++n) {
    const Index f = fs.nodeFibre[n];
    const double R = fs.radius[f];
    const Vec3 x0 = x0Of(q, n), g1 = g1Of(q, n), g2 = g2Of(q, n);
    for (int k = 0; k < sides; ++k) {
      const double phi = 2 * std::numbers::pi * k / sides;
      p.add(x0 + R * std::cos(phi) * g1 + R * std::sin(phi) * g2, R, g1, g2, f);
    }
  }
  return p;
}

void vtuHeader(std::ostream& out, size_t points, size_t cells) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<UnstructuredGrid>\n"
      << "<Piece NumberOfPoints=\"" << points << "\" NumberOfCells=\"" << cells << "\">\n";
}

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const Vec3& x : v) out.insert(out.end(), x.data(), x.data() + 3);
  return out;
}

}  // namespace

void writeContactVtu(const std::string& path, const ContactSnapshot& c) {
  const Index n = c.size();
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<int> types(n, kLine), fibreI(c.fibreI.begin(), c.fibreI.end()),
      fibreJ(c.fibreJ.begin(), c.fibreJ.end());
  for (Index e = 0; e < n; ++e) {
    for (const Vec3& x : {c.particleI[e], c.particleJ[e]}) points.insert(points.end(), x.data(), x.data() + 3);
    connectivity.insert(connectivity.end(), {2 * e, 2 * e + 1});
    offsets.push_back(2 * e + 2);
  }
  OutputFile file(path);
  std::ostream& out = file.stream();
  vtuHeader(out, 2 * size_t(n), size_t(n));
  out << "<CellData Scalars=\"normal_force\" Vectors=\"normal\">\n";
  dataArray(out, "Float64", "normal", 3, flatten(c.normal));
  dataArray(out, "Float64", "gap", 1, c.gap);
  dataArray(out, "Float64", "normal_force", 1, c.normalForce);
  dataArray(out, "Float64", "friction", 3, flatten(c.friction));
  dataArray(out, "UInt8", "slip", 1, c.slip);
  dataArray(out, "UInt8", "tool", 1, c.tool);
  dataArray(out, "Int32", "fibre_i", 1, fibreI);
  dataArray(out, "Int32", "fibre_j", 1, fibreJ);
  out << "</CellData>\n<Points>\n";
  dataArray(out, "Float64", nullptr, 3, points);
  out << "</Points>\n<Cells>\n";
  dataArray(out, "Int64", "connectivity", 1, connectivity);
  dataArray(out, "Int64", "offsets", 1, offsets);
  dataArray(out, "UInt8", "types", 1, types);
  out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
}

void writeVtu(const std::string& path, const FibreStore& fs, const Eigen::VectorXd& q,
              const VtuDef& def) {
  if (def.tubeSides < 3) throw std::invalid_argument("VtuDef::tubeSides must be >= 3");
  const PointArrays p = buildPoints(fs, q, def.tubeSides);
  const Cells c = buildCells(fs, def.tubeSides);
  OutputFile file(path);
  std::ostream& out = file.stream();
  vtuHeader(out, p.radius.size(), c.type.size());
  out << "<PointData Scalars=\"radius\">\n";
  dataArray(out, "Float64", "radius", 1, p.radius);
  dataArray(out, "Float64", "g1", 3, p.g1);
  dataArray(out, "Float64", "g2", 3, p.g2);
  dataArray(out, "Int32", "fibre", 1, p.fibre);
  out << "</PointData>\n<CellData Scalars=\"fibre\">\n";
  dataArray(out, "Int32", "fibre", 1, c.fibre);
  dataArray(out, "UInt8", "part", 1, c.part);
  out << "</CellData>\n<Points>\n";
  dataArray(out, "Float64", nullptr, 3, p.position);
  out << "</Points>\n<Cells>\n";
  dataArray(out, "Int64", "connectivity", 1, c.connectivity);
  dataArray(out, "Int64", "offsets", 1, c.offsets);
  dataArray(out, "UInt8", "types", 1, c.type);
  out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
}

VtuSeries::VtuSeries(std::string dir, std::string name, VtuDef def)
    : dir_(std::move(dir)), name_(std::move(name)), def_(def) {}

std::string VtuSeries::framePath(int frame, const char* part) const {
  char index[16];
  std::snprintf(index, sizeof index, "_%04d.vtu", frame);
  return name_ + part + index;
}

std::string VtuSeries::pvdPath() const {
  return (std::filesystem::path(dir_) / (name_ + ".pvd")).string();
}

void VtuSeries::write(const FibreStore& fibres, const Eigen::VectorXd& q, double time,
                      const ContactSnapshot* contacts) {
  const std::filesystem::path dir(dir_);
  writeVtu((dir / framePath(frames())).string(), fibres, q, def_);
  if (contacts) writeContactVtu((dir / framePath(frames(), "_contacts")).string(), *contacts);
  times_.push_back(time);
  contacts_.push_back(contacts != nullptr);
  OutputFile pvd(pvdPath());
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (int i = 0; i < frames(); ++i) {
    text += "<DataSet timestep=\"";
    appendNumber(text, times_[i]);
    text += "\" part=\"0\" file=\"" + framePath(i) + "\"/>\n";
    if (!contacts_[i]) continue;
    text += "<DataSet timestep=\"";
    appendNumber(text, times_[i]);
    text += "\" part=\"1\" file=\"" + framePath(i, "_contacts") + "\"/>\n";
  }
  text += "</Collection>\n</VTKFile>\n";
  pvd.stream() << text;
  pvd.commit();
}

}  // namespace fibra
