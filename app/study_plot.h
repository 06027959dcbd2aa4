// The picture of fibra study (app/study.h): a variant's error against its cost, drawn by gnuplot
// (io/plot.h) as FILE.png with its script FILE.gp.
//
// Two panels side by side: the error against wall time (s) and against Newton iterations, the
// error and the wall time on log axes, one curve per observed column, each point labelled with its
// value. The reference (error 0) and any error that is not > 0 cannot go on a log axis and are left
// out; the title says so. The data are in the script (a datablock), so that it draws again alone.
#pragma once

#include <string>
#include <vector>

namespace fibra::study {

struct PlotPoint {
  std::string value;          // the knob's value, the point's label
  double wall = 0;            // s
  double iterations = 0;      // Newton iterations, all attempts
  std::vector<double> error;  // per observed column; NaN or <= 0: not drawn
};

struct PlotData {
  std::string field;                 // the knob
  std::string reference;             // its reference value
  std::vector<std::string> columns;  // observed
  std::vector<PlotPoint> points;     // the variants that converged, the reference left out
};

// The gnuplot script drawing `data` into the PNG named `png` (a file name, relative to the
// script's folder).
std::string studyScript(const PlotData& data, const std::string& png);

// Writes FILE.gp beside `png` and runs gnuplot; returns the exit status: 0 drawn (or nothing to
// draw: a warning), 1 gnuplot missing or failing (the message printed).
int drawStudy(const std::string& png, const PlotData& data);

}  // namespace fibra::study
