#include "app/pictures.h"

#include "io/plot.h"
#include "io/section_cut.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibra::pictures {
namespace {

namespace fs = std::filesystem;

constexpr int kDrawn = 0, kFailed = 1, kBadInput = 2;

// RUN_DIR and the --key value pairs after it; only `known` keys, each at most once.
struct Arguments {
  std::string runDir;
  std::map<std::string, std::string> values;
  std::string get(const std::string& key, const std::string& fallback = "") const {
    const auto it = values.find(key);
    return it == values.end() ? fallback : it->second;
  }
};

Arguments parse(int argc, char** argv, const std::vector<std::string>& known) {
  const std::string command = argv[1];
  Arguments a;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!arg.starts_with("-")) {
      if (!a.runDir.empty())
        throw std::invalid_argument(command + ": more than one run directory ('" + a.runDir +
                                    "', '" + arg + "')");
      a.runDir = arg;
      continue;
    }
    if (std::find(known.begin(), known.end(), arg) == known.end())
      throw std::invalid_argument(command + ": unknown option '" + arg + "'");
    if (i + 1 >= argc) throw std::invalid_argument(arg + ": missing value");
    if (!a.values.emplace(arg, argv[++i]).second)
      throw std::invalid_argument(arg + ": given twice");
  }
  if (a.runDir.empty()) throw std::invalid_argument(command + ": missing the run directory");
  return a;
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> parts;
  size_t from = 0;
  for (size_t comma; (comma = text.find(',', from)) != std::string::npos; from = comma + 1)
    parts.push_back(text.substr(from, comma - from));
  parts.push_back(text.substr(from));
  for (const std::string& p : parts)
    if (p.empty()) throw std::invalid_argument("--y: an empty column name in '" + text + "'");
  return parts;
}

// A PNG named on the command line is taken from the working directory, the default one lies in
// RUN_DIR; both made absolute (the library puts a relative name inside RUN_DIR).
std::string pngPath(const Arguments& a, const std::string& fallbackName) {
  const std::string out = a.get("--out");
  return fs::absolute(out.empty() ? fs::path(a.runDir) / fallbackName : fs::path(out)).string();
}

// "z=0.25" -> axis 2, value 0.25; "z" -> axis 2, the middle of the span.
void parsePlane(const std::string& text, SectionPlot& plot) {
  static const std::string axes = "xyz";
  const bool named = !text.empty() && axes.find(text[0]) != std::string::npos;
  if (named && text.size() == 1) {
    plot.axis = int(axes.find(text[0]));
    return;
  }
  size_t used = 0;
  double value = 0;
  if (named && text.size() > 2 && text[1] == '=') {
    try {
      value = std::stod(text.substr(2), &used);
    } catch (const std::exception&) {
    }
  }
  if (used == 0 || used != text.size() - 2 || !std::isfinite(value))
    throw std::invalid_argument("--plane: expected x, y or z, optionally =VALUE (mm), got '" +
                                text + "'");
  plot.axis = int(axes.find(text[0]));
  plot.value = value;
}

int parseFrame(const std::string& text) {
  if (text == "last") return -1;
  size_t used = 0;
  int v = -1;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
  }
  if (text.empty() || used != text.size() || v < 0)
    throw std::invalid_argument("--frame: expected frame numbers (0, 1, ...) or last, got '" +
                                text + "'");
  return v;
}

// "0,12,last" -> {0, 12, -1}; none given: the last.
std::vector<int> parseFrames(const std::string& text) {
  if (text.empty()) return {-1};
  std::vector<int> frames;
  size_t from = 0;
  for (size_t comma; (comma = text.find(',', from)) != std::string::npos; from = comma + 1)
    frames.push_back(parseFrame(text.substr(from, comma - from)));
  frames.push_back(parseFrame(text.substr(from)));
  return frames;
}

// FILE.png for one frame, FILE_NNNN.png (the frame's index) for each of several.
std::string framePng(const std::string& png, int frame, size_t count) {
  if (count == 1) return png;
  char suffix[24];
  std::snprintf(suffix, sizeof suffix, "_%04d.png", frame);
  return (fs::path(png).replace_extension("").string()) + suffix;
}

void printSection(const SectionResult& r) {
  std::printf("fibra: wrote %s: %d sections by %c = %g mm at frame %d (t = %g)", r.png.c_str(),
              r.sections, "xyz"[r.plane.axis], r.plane.value, r.frame, r.time);
  if (r.toolSegments) std::printf(", tools: %d segments", r.toolSegments);
  std::printf("; outlines in %s, gnuplot script %s\n", r.data.c_str(), r.script.c_str());
}

// Runs `draw`, reporting a PlotError as exit 1 and a PlotInputError as exit 2.
template <class Draw>
int report(Draw draw) {
  try {
    draw();
    return kDrawn;
  } catch (const PlotInputError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  } catch (const PlotError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kFailed;
  }
}

}  // namespace

int plot(int argc, char** argv) {
  const Arguments a = parse(argc, argv, {"--x", "--y", "--out", "--title"});
  if (a.get("--x").empty()) throw std::invalid_argument("plot: missing --x COLUMN");
  if (a.get("--y").empty()) throw std::invalid_argument("plot: missing --y COLUMN[,COLUMN...]");
  CurvePlot p{a.get("--x"), splitCommas(a.get("--y")), a.get("--title"), ""};
  p.file = pngPath(a, p.y[0] + "_vs_" + p.x + ".png");
  return report([&] {
    const std::string script = drawCurves(a.runDir, p);
    std::printf("fibra: wrote %s (gnuplot script %s)\n", p.file.c_str(), script.c_str());
  });
}

int section(int argc, char** argv) {
  const Arguments a = parse(argc, argv, {"--plane", "--frame", "--out", "--title"});
  SectionPlot p;
  if (a.values.count("--plane")) parsePlane(a.get("--plane"), p);
  if (a.values.count("--frame") && a.get("--frame").empty())
    throw std::invalid_argument("--frame: expected frame numbers (0, 1, ...) or last, got ''");
  const std::vector<int> frames = parseFrames(a.get("--frame"));
  const std::string png = pngPath(a, "section.png");
  p.title = a.get("--title");
  return report([&] {
    const int count = int(readRunFrames(a.runDir).size());
    for (const int frame : frames) frameIndex(a.runDir, frame, count);  // all, before drawing
    for (const int frame : frames) {
      p.frame = frame;
      p.file = framePng(png, frameIndex(a.runDir, frame, count), frames.size());
      const SectionResult r = drawSection(a.runDir, p);
      p.axis = r.plane.axis;  // the stages of a run are cut by one plane: the first frame's
      p.value = r.plane.value;
      printSection(r);
    }
  });
}

}  // namespace fibra::pictures
