// Curves of a run's history as PNG pictures, drawn by gnuplot: what `fibra plot` and the
// scene's `output.plots` use (docs/PLOTS.md).
//
//   fibra::CurvePlot p{"time", {"reaction.beam.end.fy"}, "", "force.png"};
//   const std::string script = fibra::drawCurves("out/run", p);  // out/run/force.gp, force.png
//
// The history is read only for its header (the column names); gnuplot reads history.csv itself.
// The script is written beside the PNG (FILE.png -> FILE.gp) so that a person can edit it and
// draw again with `cd DIR && gnuplot FILE.gp`; it names the history relative to the PNG's
// folder, and gnuplot runs in that folder, started by fork/exec with the script's path as its
// only argument (no shell). User strings (title, column names, paths) enter the script as
// gnuplot single-quoted strings ('' for a quote) with enhanced text off, so nothing in them is
// interpreted. The terminal is pngcairo when gnuplot has it, png otherwise (decided by the
// script, from GPVAL_TERMINALS).
//
// Errors: PlotInputError (bad input: no history, an unknown column, an empty history; exit
// status 2 in the program) and PlotError (gnuplot missing or failing, a file not written;
// exit 1), both naming the file and what was wrong.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace fibra {

struct PlotError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct PlotInputError : PlotError {
  using PlotError::PlotError;
};

// A figure: the columns y against column x of the history. A y entry may be a sum of columns,
// "a+b" (the two holds of a beam: its whole reaction).
struct CurvePlot {
  std::string x;
  std::vector<std::string> y;  // one curve each (at least one)
  std::string title;           // "" for none
  std::string file;            // the PNG; a relative path is taken from the run's directory
};

// The column names of a history CSV file (its header line); PlotInputError when the file
// cannot be read or has no header, PlotInputError naming the file when it has no data row
// and `needRows`.
std::vector<std::string> readHistoryColumns(const std::string& path, bool needRows = true);

// "unknown column 'NAME' (did you mean 'X'?); the columns are: a, b, ..."
std::string unknownColumn(const std::vector<std::string>& columns, const std::string& name);
// The 0-based index of `name` in `columns`; PlotInputError "FILE: WHAT: unknown column ..."
// otherwise (`what`, e.g. "y", names where the name came from).
int findColumn(const std::vector<std::string>& columns, const std::string& name,
               const std::string& file, const std::string& what);

// The columns of a y entry: "a+b" -> {a, b}; "a" -> {a}.
std::vector<std::string> columnTerms(const std::string& entry);

// The unit of a history column from its name (docs/SCENE.md "What fibra run writes"; the
// scene units are mm-N-MPa): "N" for forces, "N mm" for moments and energies, "mm" for
// positions and lengths, "s" for wall_s; "" for counts, ratios, pseudo-time and any name not
// in the table (no unit rather than a wrong one). A sum has its terms' unit when they share one.
std::string columnUnit(const std::string& name);
// "NAME (UNIT)", or NAME when it has no unit.
std::string axisLabel(const std::string& name);
// The y axis of several curves: "a, b (N)" when they share a unit, "a (N), b (mm)" otherwise.
std::string axisLabel(const std::vector<std::string>& names);

// `text` as a gnuplot single-quoted string ('it''s'); line breaks become spaces.
std::string gnuplotString(const std::string& text);

// Script lines choosing the PNG terminal (pngcairo when gnuplot has it, else png), W x H pixels,
// enhanced text off.
std::string pngTerminal(int width, int height);

// The gnuplot script of a curve plot: `history` is the CSV's path as gnuplot will see it (from
// the PNG's folder), `png` the PNG's file name, `columns` the history's header.
std::string curveScript(const CurvePlot& plot, const std::vector<std::string>& columns,
                        const std::string& history, const std::string& png);

// Runs gnuplot on `script` with `dir` as working directory; PlotError when gnuplot cannot be
// found (PATH, or the FIBRA_GNUPLOT environment variable when set) or fails (its messages
// quoted). Safe to call from a multithreaded program.
void runGnuplot(const std::string& script, const std::string& dir);

// The full path of the gnuplot program, or "" when there is none.
std::string findGnuplot();

// Where a picture goes: `file` (`fallback` when empty) taken from RUN_DIR when relative, its
// folder created; PlotInputError unless it ends in .png, PlotError when the folder cannot be
// made.
std::string picturePath(const std::string& runDir, const std::string& file,
                        const std::string& fallback = "");

// Writes `script` as PNG's FILE.gp and runs gnuplot on it in PNG's folder; PlotError when no
// picture comes out. Returns the script's path.
std::string drawScript(const std::string& png, const std::string& script);

// Draws `plot` from RUN_DIR/history.csv: checks the columns, writes the script beside the PNG
// (FILE.gp), runs gnuplot; returns the script's path.
std::string drawCurves(const std::string& runDir, const CurvePlot& plot);

}  // namespace fibra
