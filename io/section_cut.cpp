#include "io/section_cut.h"

#include "io/output_file.h"
#include "io/plot.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace fibra {
namespace {

namespace fs = std::filesystem;

const char* const kAxisName[3] = {"x", "y", "z"};

// A point of fibre `nodes` at s (node index + fraction), linear between nodes.
template <class F>
auto along(const std::vector<Index>& nodes, double s, F at) {
  const size_t i = std::min(size_t(s), nodes.size() - 2);
  const double t = s - double(i);
  return ((1 - t) * at(nodes[i]) + t * at(nodes[i + 1])).eval();
}

// The s where the rim line of angle phi meets the plane, nearest to `sc`; NaN when it does not.
double rimCrossing(const FibreFrame& f, const std::vector<Index>& nodes, const CutPlane& plane,
                   double phi, double sc) {
  const auto h = [&](Index n) {
    const Vec3 r = f.x0[n] + f.radius[n] * (std::cos(phi) * f.g1[n] + std::sin(phi) * f.g2[n]);
    return r[plane.axis] - plane.value;
  };
  double best = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i + 1 < nodes.size(); ++i) {
    const double a = h(nodes[i]), b = h(nodes[i + 1]);
    if ((a < 0) == (b < 0)) continue;
    const double s = double(i) + a / (a - b);
    if (!(std::abs(s - sc) >= std::abs(best - sc))) best = s;
  }
  return best;
}

SectionOutline cutAt(const FibreFrame& f, Index fibre, const CutPlane& plane, double sc,
                     int sides) {
  const std::vector<Index>& nodes = f.fibres[fibre];
  SectionOutline out{fibre, sc, along(nodes, sc, [&](Index n) { return f.x0[n]; }), {}};
  for (int k = 0; k < sides; ++k) {
    const double phi = 2 * std::numbers::pi * k / sides;
    const double s = rimCrossing(f, nodes, plane, phi, sc);
    if (std::isnan(s)) continue;
    const auto rim = [&](Index n) {
      return (f.x0[n] + f.radius[n] * (std::cos(phi) * f.g1[n] + std::sin(phi) * f.g2[n]))
          .eval();
    };
    Vec3 p = along(nodes, s, rim);
    p[plane.axis] = plane.value;  // on the plane up to round-off: exactly on it
    out.points.push_back(p);
  }
  return out;
}

const std::vector<double>& array(const VtuArrays& a, const std::string& key, size_t size) {
  const auto it = a.find(key);
  if (it == a.end()) throw std::runtime_error("VTU: no array " + key);
  if (it->second.size() < size) throw std::runtime_error("VTU: array " + key + " too short");
  return it->second;
}

std::string number(double v) {  // exact, for data and scripts
  std::string s;
  appendNumber(s, v);
  return s;
}

std::string shortNumber(double v) {  // %g, for titles
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

std::vector<SectionOutline> cutSections(const FibreFrame& f, const CutPlane& plane, int sides) {
  if (sides < 3) throw std::invalid_argument("cutSections: sides must be >= 3");
  std::vector<SectionOutline> out;
  for (Index fibre = 0; fibre < Index(f.fibres.size()); ++fibre) {
    const std::vector<Index>& nodes = f.fibres[fibre];
    for (size_t i = 0; i + 1 < nodes.size(); ++i) {
      const double a = f.x0[nodes[i]][plane.axis] - plane.value,
                   b = f.x0[nodes[i + 1]][plane.axis] - plane.value;
      if ((a < 0) == (b < 0)) continue;
      SectionOutline s = cutAt(f, fibre, plane, double(i) + a / (a - b), sides);
      if (s.points.size() >= 3) out.push_back(std::move(s));
    }
  }
  return out;
}

CutPlane medianPlane(const FibreFrame& f, int axis) {
  if (f.x0.empty()) throw std::invalid_argument("medianPlane: no nodes");
  Vec3 lo = f.x0[0], hi = f.x0[0];
  for (const Vec3& x : f.x0) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (axis < 0) (hi - lo).maxCoeff(&axis);
  return {axis, 0.5 * (lo[axis] + hi[axis])};
}

std::array<int, 2> planeAxes(int axis) { return {(axis + 1) % 3, (axis + 2) % 3}; }

FibreFrame fibreFrameFromVtu(const VtuArrays& a) {
  const std::vector<double>& types = array(a, "Cells/types", 0);
  const std::vector<double>& offsets = array(a, "Cells/offsets", types.size());
  const std::vector<double>& connectivity =
      array(a, "Cells/connectivity", types.empty() ? 0 : size_t(offsets[types.size() - 1]));
  FibreFrame f;
  Index nodes = 0;
  for (size_t c = 0; c < types.size(); ++c) {
    if (types[c] != 4) continue;  // VTK_POLY_LINE: a fibre's centreline
    std::vector<Index>& fibre = f.fibres.emplace_back();
    for (size_t k = c ? size_t(offsets[c - 1]) : 0; k < size_t(offsets[c]); ++k)
      fibre.push_back(Index(connectivity[k]));
    if (fibre.size() < 2) throw std::runtime_error("VTU: a fibre with fewer than 2 nodes");
    for (Index n : fibre) nodes = std::max(nodes, n + 1);
  }
  const std::vector<double>& points = array(a, "Points/", 3 * size_t(nodes));
  const std::vector<double>& g1 = array(a, "PointData/g1", 3 * size_t(nodes));
  const std::vector<double>& g2 = array(a, "PointData/g2", 3 * size_t(nodes));
  const std::vector<double>& radius = array(a, "PointData/radius", size_t(nodes));
  for (Index n = 0; n < nodes; ++n) {
    f.x0.emplace_back(points[3 * n], points[3 * n + 1], points[3 * n + 2]);
    f.g1.emplace_back(g1[3 * n], g1[3 * n + 1], g1[3 * n + 2]);
    f.g2.emplace_back(g2[3 * n], g2[3 * n + 1], g2[3 * n + 2]);
    f.radius.push_back(radius[n]);
  }
  return f;
}

FibreFrame readFibreFrame(const std::string& runDir, int index, int* chosen) {
  const fs::path pvd = fs::path(runDir) / "result.pvd";
  std::ifstream in(pvd);
  if (!in)
    throw PlotInputError(pvd.string() + ": cannot read the frames (is " + runDir +
                         " a fibra run's output directory, with output.vtu on?)");
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<PvdFrame> frames;
  try {
    frames = readPvdFrames(text.str());
  } catch (const std::runtime_error& e) {
    throw PlotInputError(pvd.string() + ": " + e.what());
  }
  const int last = int(frames.size()) - 1;
  if (index < -1 || index > last)
    throw PlotInputError(pvd.string() + ": --frame: " + std::to_string(index) +
                         " outside 0.." + std::to_string(last) + " (or last)");
  const int k = index < 0 ? last : index;
  const fs::path vtu = fs::path(runDir) / frames[size_t(k)].file;
  std::ifstream file(vtu, std::ios::binary);
  if (!file) throw PlotInputError(vtu.string() + ": cannot read frame " + std::to_string(k));
  std::ostringstream bytes;
  bytes << file.rdbuf();
  try {
    FibreFrame f = fibreFrameFromVtu(readVtuArrays(bytes.str()));
    f.time = frames[size_t(k)].time;
    if (chosen) *chosen = k;
    return f;
  } catch (const std::runtime_error& e) {
    throw PlotInputError(vtu.string() + ": " + e.what());
  }
}

std::string sectionScript(const CutPlane& plane, const std::string& data, const std::string& png,
                          const std::string& title) {
  const std::array<int, 2> uv = planeAxes(plane.axis);
  std::string s = "# fibra section: the fibres cut by the plane " +
                  std::string(kAxisName[plane.axis]) + " = " + number(plane.value) +
                  " mm, outlines in " + data + "\n# draw again, in this folder: gnuplot " +
                  fs::path(png).replace_extension(".gp").string() + "\n";
  s += pngTerminal(800, 800);
  s += "set output " + gnuplotString(png) + "\nset size ratio -1\nset grid\nunset key\n";
  s += "set title " + gnuplotString(title) + "\n";
  s += "set xlabel " + gnuplotString(std::string(kAxisName[uv[0]]) + " (mm)") + "\n";
  s += "set ylabel " + gnuplotString(std::string(kAxisName[uv[1]]) + " (mm)") + "\n";
  s += "plot " + gnuplotString(data) +
       " using 1:2 with filledcurves closed fillcolor rgb '#9ecae1' fillstyle solid 0.7, \\\n"
       "     '' using 1:2 with lines linecolor rgb '#08519c' linewidth 1.5\n";
  return s;
}

namespace {

// The outlines as gnuplot data: in-plane coordinates (mm), one closed block per section.
std::string outlineData(const std::vector<SectionOutline>& sections, const CutPlane& plane) {
  const std::array<int, 2> uv = planeAxes(plane.axis);
  std::string text = "# " + std::string(kAxisName[uv[0]]) + " " + kAxisName[uv[1]] + " (mm)\n";
  for (const SectionOutline& s : sections) {
    text += "# fibre " + std::to_string(s.fibre) + "\n";
    for (size_t k = 0; k <= s.points.size(); ++k) {
      const Vec3& p = s.points[k % s.points.size()];  // closed: the first point again
      text += number(p[uv[0]]) + " " + number(p[uv[1]]) + "\n";
    }
    text += "\n";
  }
  return text;
}

void writeWhole(const fs::path& path, const std::string& text) {
  OutputFile file(path.string());
  file.stream() << text;
  file.commit();
}

std::string span(const FibreFrame& f, int axis) {
  double lo = f.x0[0][axis], hi = lo;
  for (const Vec3& x : f.x0) {
    lo = std::min(lo, x[axis]);
    hi = std::max(hi, x[axis]);
  }
  return shortNumber(lo) + " to " + shortNumber(hi);
}

}  // namespace

SectionResult drawSection(const std::string& runDir, const SectionPlot& plot) {
  SectionResult r;
  const FibreFrame frame = readFibreFrame(runDir, plot.frame, &r.frame);
  r.plane = medianPlane(frame, plot.axis);
  if (plot.value) r.plane.value = *plot.value;
  r.time = frame.time;
  const std::vector<SectionOutline> sections = cutSections(frame, r.plane, plot.sides);
  const std::string where =
      std::string(kAxisName[r.plane.axis]) + " = " + shortNumber(r.plane.value);
  if (sections.empty())
    throw PlotInputError(runDir + ": frame " + std::to_string(r.frame) + ": the plane " + where +
                         " mm cuts no fibre (the nodes span " + kAxisName[r.plane.axis] +
                         " = " + span(frame, r.plane.axis) + " mm)");
  r.sections = int(sections.size());
  fs::path png = plot.file.empty() ? fs::path("section.png") : fs::path(plot.file);
  if (png.is_relative()) png = fs::path(runDir) / png;
  if (png.extension() != ".png")
    throw PlotInputError(png.string() + ": the picture's name must end in .png");
  const fs::path dir = png.parent_path().empty() ? fs::path(".") : png.parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw PlotError("cannot create '" + dir.string() + "': " + ec.message());
  fs::path data = png, script = png;
  data.replace_extension(".dat");
  script.replace_extension(".gp");
  const std::string title =
      !plot.title.empty() ? plot.title
                          : "fibres cut by " + where + " mm, frame " + std::to_string(r.frame) +
                                ", t = " + shortNumber(r.time) + ", " +
                                std::to_string(r.sections) +
                                " sections";
  writeWhole(data, outlineData(sections, r.plane));
  writeWhole(script, sectionScript(r.plane, data.filename().string(), png.filename().string(),
                                   title));
  fs::remove(png, ec);  // so that a picture after the run is this run's
  runGnuplot(script.filename().string(), dir.string());
  if (!fs::exists(png) || fs::file_size(png) == 0)
    throw PlotError(png.string() + ": gnuplot ran but wrote no picture");
  r.png = png.string();
  r.script = script.string();
  r.data = data.string();
  return r;
}

}  // namespace fibra
