#include "io/vtu_writer.h"

#include "io/output_file.h"
#include "io/vtu_document.h"

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
  std::vector<std::uint8_t> type, part;
  std::vector<std::int32_t> fibre;
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

// Per-point arrays: centreline nodes, then `sides` rim points per node.
struct PointArrays {
  std::vector<double> position, radius, g1, g2;
  std::vector<std::int32_t> fibre;
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

}  // namespace

void writeGrid(VtuDocument& doc, const std::vector<double>& points,
               const std::vector<std::int64_t>& connectivity,
               const std::vector<std::int64_t>& offsets, const std::vector<std::uint8_t>& types) {
  doc.open("<Points>");
  doc.array(nullptr, 3, points);
  doc.close("</Points>");
  doc.open("<Cells>");
  doc.array("connectivity", 1, connectivity);
  doc.array("offsets", 1, offsets);
  doc.array("types", 1, types);
  doc.close("</Cells>");
}

static std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const Vec3& x : v) out.insert(out.end(), x.data(), x.data() + 3);
  return out;
}

void writeContactVtu(const std::string& path, const ContactSnapshot& c, const VtuDef& def) {
  const Index n = c.size();
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types(n, kLine);
  std::vector<std::int32_t> fibreI(c.fibreI.begin(), c.fibreI.end()),
      fibreJ(c.fibreJ.begin(), c.fibreJ.end()), zone(c.zone.begin(), c.zone.end());
  for (Index e = 0; e < n; ++e) {
    for (const Vec3& x : {c.particleI[e], c.particleJ[e]})
      points.insert(points.end(), x.data(), x.data() + 3);
    connectivity.insert(connectivity.end(), {2 * e, 2 * e + 1});
    offsets.push_back(2 * e + 2);
  }
  VtuDocument doc(def.encoding, 2 * size_t(n), size_t(n));
  doc.open("<CellData Scalars=\"normal_force\" Vectors=\"normal\">");
  doc.array("normal", 3, flatten(c.normal));
  doc.array("gap", 1, c.gap);
  doc.array("normal_force", 1, c.normalForce);
  doc.array("length", 1, c.length);
  doc.array("friction", 3, flatten(c.friction));
  doc.array("slip", 1, c.slip);
  doc.array("tool", 1, c.tool);
  doc.array("fibre_i", 1, fibreI);
  doc.array("fibre_j", 1, fibreJ);
  doc.array("zone", 1, zone);
  doc.array("refined", 1, c.refined);
  doc.close("</CellData>");
  writeGrid(doc, points, connectivity, offsets, types);
  doc.write(path);
}

void writeVtu(const std::string& path, const FibreStore& fs, const Eigen::VectorXd& q,
              const VtuDef& def) {
  if (def.tubeSides < 3) throw std::invalid_argument("VtuDef::tubeSides must be >= 3");
  const PointArrays p = buildPoints(fs, q, def.tubeSides);
  const Cells c = buildCells(fs, def.tubeSides);
  VtuDocument doc(def.encoding, p.radius.size(), c.type.size());
  doc.open("<PointData Scalars=\"radius\">");
  doc.array("radius", 1, p.radius);
  doc.array("g1", 3, p.g1);
  doc.array("g2", 3, p.g2);
  doc.array("fibre", 1, p.fibre);
  doc.close("</PointData>");
  doc.open("<CellData Scalars=\"fibre\">");
  doc.array("fibre", 1, c.fibre);
  doc.array("part", 1, c.part);
  doc.close("</CellData>");
  writeGrid(doc, p.position, c.connectivity, c.offsets, c.type);
  doc.write(path);
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

void VtuSeries::write(const VtuFrame& f) {
  const std::filesystem::path dir(dir_);
  const int index = frames();
  writeVtu((dir / framePath(index)).string(), f.fibres, f.q, def_);
  if (f.contacts)
    writeContactVtu((dir / framePath(index, "_contacts")).string(), *f.contacts, def_);
  if (f.tools && f.tools->size() > 0) {
    if (extents_.empty()) extents_ = toolExtents(*f.tools, f.fibres, f.q);
    writeToolVtu((dir / framePath(index, "_tools")).string(), *f.tools, extents_, f.time, def_);
  }
  times_.push_back(f.time);
  contacts_.push_back(f.contacts != nullptr);
  tools_.push_back(f.tools && f.tools->size() > 0);
  writePvd();
}

void VtuSeries::resume(std::vector<double> times, bool contacts, bool tools,
                       std::vector<ToolExtent> extents) {
  times_ = std::move(times);
  contacts_.assign(times_.size(), contacts);
  tools_.assign(times_.size(), tools);
  extents_ = std::move(extents);
  writePvd();
}

void VtuSeries::writePvd() const {
  OutputFile pvd(pvdPath());
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  const auto dataset = [&](int i, int part, const char* suffix) {
    text += "<DataSet timestep=\"";
    appendNumber(text, times_[i]);
    text += "\" part=\"" + std::to_string(part) + "\" file=\"" + framePath(i, suffix) + "\"/>\n";
  };
  for (int i = 0; i < frames(); ++i) {
    dataset(i, 0, "");
    if (contacts_[i]) dataset(i, 1, "_contacts");
    if (tools_[i]) dataset(i, 2, "_tools");
  }
  text += "</Collection>\n</VTKFile>\n";
  pvd.stream() << text;
  pvd.commit();
}

}  // namespace fibra
