// The picture of a cut (io/section_cut.h, drawSection): the outlines and the tools' traces as
// gnuplot data, the script, and gnuplot run on it (io/plot.h).
#include "io/output_file.h"
#include "io/plot.h"
#include "io/section_cut.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace fibra {
namespace {

namespace fs = std::filesystem;

const char* const kAxisName[3] = {"x", "y", "z"};

std::string number(double v) {  // exact, for data and scripts
  std::string s;
  appendNumber(s, v);
  return s;
}

std::string shortNumber(double v) {  // %g, for titles and messages
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string pointLine(const Vec3& p, const std::array<int, 2>& uv) {
  return number(p[uv[0]]) + " " + number(p[uv[1]]) + "\n";
}

// Gnuplot data, in-plane coordinates (mm): index 0 one closed block per section, index 1 (after
// two blank lines) one block per tool segment.
std::string cutData(const std::vector<SectionOutline>& sections,
                    const std::vector<Segment>& tools, const CutPlane& plane) {
  const std::array<int, 2> uv = planeAxes(plane.axis);
  std::string text = "# " + std::string(kAxisName[uv[0]]) + " " + kAxisName[uv[1]] + " (mm)\n";
  for (const SectionOutline& s : sections) {
    text += "# fibre " + std::to_string(s.fibre) + "\n";
    for (size_t k = 0; k <= s.points.size(); ++k)
      text += pointLine(s.points[k % s.points.size()], uv);  // closed: the first point again
    text += "\n";
  }
  if (tools.empty()) return text;
  text += "\n# tools\n";
  for (const Segment& t : tools) text += pointLine(t.a, uv) + pointLine(t.b, uv) + "\n";
  return text;
}

// The sections' box in the plane with a margin of 15% of its larger side.
SectionView viewOf(const std::vector<SectionOutline>& sections, const CutPlane& plane,
                   bool tools) {
  const std::array<int, 2> uv = planeAxes(plane.axis);
  SectionView v{{1e300, 1e300}, {-1e300, -1e300}, tools};
  for (const SectionOutline& s : sections)
    for (const Vec3& p : s.points)
      for (int i = 0; i < 2; ++i) {
        v.lo[i] = std::min(v.lo[i], p[uv[i]]);
        v.hi[i] = std::max(v.hi[i], p[uv[i]]);
      }
  const double margin = 0.15 * std::max(v.hi[0] - v.lo[0], v.hi[1] - v.lo[1]);
  for (int i = 0; i < 2; ++i) {
    v.lo[i] -= margin;
    v.hi[i] += margin;
  }
  return v;
}

std::string span(const FibreFrame& f, int axis) {
  double lo = f.x0[0][axis], hi = lo;
  for (const Vec3& x : f.x0) {
    lo = std::min(lo, x[axis]);
    hi = std::max(hi, x[axis]);
  }
  return shortNumber(lo) + " to " + shortNumber(hi);
}

std::string defaultTitle(const SectionResult& r) {
  return "fibres cut by " + std::string(kAxisName[r.plane.axis]) + " = " +
         shortNumber(r.plane.value) + " mm, frame " + std::to_string(r.frame) +
         ", t = " + shortNumber(r.time) + ", " + std::to_string(r.sections) + " sections";
}

void writeWhole(const std::string& path, const std::string& text) {
  OutputFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace

std::string sectionScript(const CutPlane& plane, const std::string& data, const std::string& png,
                          const std::string& title, const SectionView& view) {
  const std::array<int, 2> uv = planeAxes(plane.axis);
  std::string s = "# fibra section: the fibres cut by the plane " +
                  std::string(kAxisName[plane.axis]) + " = " + number(plane.value) +
                  " mm, outlines in " + data + "\n# draw again, in this folder: gnuplot " +
                  fs::path(png).replace_extension(".gp").string() + "\n";
  s += pngTerminal(800, 800);
  s += "set output " + gnuplotString(png) + "\nset size ratio -1\nset grid\nunset key\n";
  s += "set clip two\n";  // tool lines whose ends lie outside the box
  s += "set title " + gnuplotString(title) + "\n";
  s += "set xlabel " + gnuplotString(std::string(kAxisName[uv[0]]) + " (mm)") + "\n";
  s += "set ylabel " + gnuplotString(std::string(kAxisName[uv[1]]) + " (mm)") + "\n";
  s += "set xrange [" + number(view.lo[0]) + ":" + number(view.hi[0]) + "]\n";
  s += "set yrange [" + number(view.lo[1]) + ":" + number(view.hi[1]) + "]\n";
  s += "plot " + gnuplotString(data) +
       " index 0 using 1:2 with filledcurves closed fillcolor rgb '#9ecae1' fillstyle solid "
       "0.7, \\\n     '' index 0 using 1:2 with lines linecolor rgb '#08519c' linewidth 1.5";
  if (view.tools)
    s += ", \\\n     '' index 1 using 1:2 with lines linecolor rgb '#636363' linewidth 3";
  return s + "\n";
}

SectionResult drawSection(const std::string& runDir, const SectionPlot& plot) {
  SectionResult r;
  const FibreFrame frame = readFibreFrame(runDir, plot.frame, &r.frame);
  r.plane = medianPlane(frame, plot.axis);
  if (plot.value) r.plane.value = *plot.value;
  r.time = frame.time;
  const std::vector<SectionOutline> sections = cutSections(frame, r.plane, plot.sides);
  if (sections.empty())
    throw PlotInputError(runDir + ": frame " + std::to_string(r.frame) + ": the plane " +
                         kAxisName[r.plane.axis] + " = " + shortNumber(r.plane.value) +
                         " mm cuts no fibre (the nodes span " + kAxisName[r.plane.axis] +
                         " = " + span(frame, r.plane.axis) + " mm)");
  const std::vector<Segment> tools = readToolCut(frame.file, r.plane);
  r.sections = int(sections.size());
  r.toolSegments = int(tools.size());
  r.png = picturePath(runDir, plot.file, "section.png");
  r.data = fs::path(r.png).replace_extension(".dat").string();
  writeWhole(r.data, cutData(sections, tools, r.plane));
  const std::string script =
      sectionScript(r.plane, fs::path(r.data).filename().string(),
                    fs::path(r.png).filename().string(),
                    plot.title.empty() ? defaultTitle(r) : plot.title,
                    viewOf(sections, r.plane, !tools.empty()));
  r.script = drawScript(r.png, script);
  return r;
}

}  // namespace fibra
