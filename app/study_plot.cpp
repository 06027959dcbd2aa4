// The picture of fibra study (app/study_plot.h): the gnuplot script and its drawing.
#include "app/study_plot.h"

#include "io/plot.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

namespace fibra::study {
namespace {

namespace fs = std::filesystem;

constexpr int kDrawn = 0, kFailed = 1;

bool drawable(double error) { return std::isfinite(error) && error > 0; }

// One datablock line: wall_s iterations error per column ('?' for none) "value".
std::string dataLine(const PlotPoint& p) {
  char number[32];
  std::snprintf(number, sizeof number, "%.6g %.6g", p.wall, p.iterations);
  std::string line = number;
  for (const double e : p.error) {
    std::snprintf(number, sizeof number, " %.6g", e);
    line += drawable(e) ? std::string(number) : " ?";
  }
  std::string label = p.value;  // a double-quoted field of the datablock
  for (char& c : label)
    if (c == '"') c = '\'';
  return line + " \"" + label + "\"\n";
}

// The plot command of one panel: x is the datablock's column 1 (wall time) or 2 (iterations).
std::string panel(const PlotData& d, int x) {
  const std::string labelColumn = std::to_string(d.columns.size() + 3);
  std::string s = "plot ";
  for (size_t c = 0; c < d.columns.size(); ++c) {
    const std::string using_ = std::to_string(x) + ":" + std::to_string(c + 3);
    s += (c ? ", \\\n     " : "") + std::string("$study using ") + using_ +
         " with linespoints pt 7 ps 1 title " + gnuplotString(d.columns[c]);
  }
  // Labels on the first column's points (the others share the x of each variant).
  return s + ", \\\n     $study using " + std::to_string(x) + ":3:" + labelColumn +
         " with labels offset char 0,0.9 notitle\n";
}

}  // namespace

std::string studyScript(const PlotData& d, const std::string& png) {
  std::string s = "# fibra study: the error of each variant of " + d.field +
                  " against its wall time and Newton iterations\n# draw again, in this folder: "
                  "gnuplot " +
                  fs::path(png).replace_extension(".gp").string() + "\n";
  s += pngTerminal(1300, 560);
  s += "set output " + gnuplotString(png) + "\n";
  s += "$study << EOD\n# wall_s iterations";
  for (const std::string& c : d.columns) s += " error_" + c;
  s += " value\n";
  for (const PlotPoint& p : d.points) s += dataLine(p);
  s += "EOD\nset datafile missing '?'\n";
  s += "set multiplot layout 1,2 title " +
       gnuplotString(d.field + ": error against cost (the reference " + d.field + "=" +
                     d.reference + ", error 0, is not drawn on the log axis)") +
       "\n";
  s += "set logscale y\nset format y '%g'\nset grid\nset key below\n"
       "set offsets graph 0.08, graph 0.08, graph 0.1, graph 0.05\n"
       "set ylabel 'relative error (max over the curve)'\n";
  s += "set logscale x\nset xlabel 'wall time in the solver (s)'\n" + panel(d, 1);
  s += "unset logscale x\nset xlabel 'Newton iterations (all attempts)'\n" + panel(d, 2);
  return s + "unset multiplot\n";
}

int drawStudy(const std::string& png, const PlotData& data) {
  bool any = false;
  for (const PlotPoint& p : data.points)
    for (const double e : p.error) any = any || drawable(e);
  if (!any) {
    std::fprintf(stderr, "fibra: warning: no error > 0 to draw on a log axis: %s not drawn\n",
                 png.c_str());
    return kDrawn;
  }
  try {
    const std::string script =
        drawScript(png, studyScript(data, fs::path(png).filename().string()));
    std::printf("fibra: wrote %s (gnuplot script %s)\n", png.c_str(), script.c_str());
    return kDrawn;
  } catch (const PlotError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kFailed;
  }
}

}  // namespace fibra::study
