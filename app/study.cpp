// fibra study (app/study.h): variants of a scene that differ in one field, run in-process one
// after the other; their cost (wall time, Newton iterations) and their error against a reference
// variant on history columns, as DIR/study.csv and a gnuplot picture DIR/study.png.
//
// Error of a variant on an observed history column y, against the reference's curve y_ref
// (both sampled at their converged increments, at pseudo-times t from the `time` column):
//
//   error = max_k |y(t_k) - y_ref(t_k)| / max_k |y_ref(t_k)|
//
// over the reference's rows k whose t_k lies in the variant's span [0, last t], y(t_k)
// interpolated linearly in t between the variant's rows, from its initial state at t = 0 (the
// history has no row there; increments and cutbacks make the variants' pseudo-times differ), so
// that a variant of few increments is compared along the whole curve, not at its rows alone. The final error is
// |y(t_end) - y_ref(t_end)| / |y_ref(t_end)| at each curve's last row. A zero denominator
// leaves the difference absolute. The reference's own errors are 0.
//
// Wall time is the time spent in World::step (the solve): building the World and writing the
// outputs are left out, so that outputs do not blur the solver's cost.
#include "app/study.h"

#include "app/arguments.h"

#include "app/study_knob.h"
#include "app/study_plot.h"
#include "engine/world.h"
#include "io/json_reader.h"
#include "io/output_file.h"
#include "io/outputs.h"
#include "io/plot.h"
#include "io/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibra::study {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kDone = 0, kFailed = 1, kBadInput = 2;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Arguments {
  std::string scene, vary, observe, out, reference;
  int threads = 0;  // 0: all cores
};

std::vector<std::string> splitCommas(const std::string& text, const std::string& option) {
  std::vector<std::string> parts;
  std::stringstream in(text + ",");
  for (std::string part; std::getline(in, part, ',');) {
    if (part.empty()) throw std::invalid_argument(option + ": an empty entry in '" + text + "'");
    parts.push_back(part);
  }
  return parts;
}

Arguments parse(int argc, char** argv) {
  static const std::vector<std::string> known{"--vary", "--observe", "--out", "--reference",
                                              "--threads"};
  Arguments a;
  std::map<std::string, std::string> values;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!arg.starts_with("-")) {
      if (!a.scene.empty())
        throw std::invalid_argument("study: more than one scene file ('" + a.scene + "', '" + arg +
                                    "')");
      a.scene = arg;
      continue;
    }
    if (std::find(known.begin(), known.end(), arg) == known.end())
      throw std::invalid_argument("study: unknown option '" + arg + "'");
    if (i + 1 >= argc) throw std::invalid_argument(arg + ": missing value");
    if (!values.emplace(arg, argv[++i]).second) throw std::invalid_argument(arg + ": given twice");
  }
  if (a.scene.empty()) throw std::invalid_argument("study: missing the scene file");
  a.vary = values["--vary"];
  a.observe = values["--observe"];
  a.out = values["--out"];
  a.reference = values["--reference"];
  if (a.vary.empty()) throw std::invalid_argument("study: missing --vary FIELD=V1,V2,...");
  if (a.observe.empty()) throw std::invalid_argument("study: missing --observe COLUMN[,...]");
  if (a.out.empty()) throw std::invalid_argument("study: missing --out DIR");
  if (values.count("--threads")) a.threads = arguments::positiveInt(values["--threads"], "--threads");
  return a;
}


struct Variant {
  std::string text;  // the value as given
  Json value;
  std::string sceneText;  // the variant's scene, JSON (kept beside its checkpoint)
  SceneDef scene;
  std::string folder;  // DIR/FIELD=VALUE
  // Results
  bool converged = false;
  std::string message;  // why it failed
  double wall = 0;      // s in World::step
  int iterations = 0, increments = 0, cutbacks = 0;
  std::vector<double> initial;             // per observed column: at t = 0
  std::vector<double> last, error, final;  // per observed column; NaN: none
};

struct Study {
  std::string field;
  std::vector<PathStep> path;
  std::vector<std::string> columns;  // observed
  std::vector<Variant> variants;
  size_t reference = 0;
  std::string why;  // how the reference was chosen
};

// Fields whose finer end is known (by the path's last key): a larger value is finer (more
// elements, increments, loops), or a smaller one (penetrations, tolerances, spacings).
const std::vector<std::string> kFinerWhenLarger{
    "elements", "order", "increments", "rings", "sectors", "max_iterations",
    "max_detection_loops", "max_normal_loops", "krylov_restart", "krylov_max_iterations"};
const std::vector<std::string> kFinerWhenSmaller{"max_penetration",     "force_tolerance",
                                                 "increment_tolerance", "krylov_tolerance",
                                                 "max_reversible_slip", "test_point_spacing"};

bool listed(const std::vector<std::string>& names, const std::string& key) {
  return std::find(names.begin(), names.end(), key) != names.end();
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

// --reference V when given (matched as text, or as a number for a numeric knob); else the
// finest value of a known numeric field. InputError when neither applies.
void chooseReference(Study& s, const std::string& given) {
  const std::vector<Variant>& v = s.variants;
  if (!given.empty()) {
    const Json g = parseValue(given);
    for (size_t i = 0; i < v.size(); ++i)
      if (v[i].text == given || (g.is_number() && v[i].value.is_number() &&
                                 g.get<double>() == v[i].value.get<double>())) {
        s.reference = i;
        s.why = "given by --reference";
        return;
      }
    std::vector<std::string> texts;
    for (const Variant& x : v) texts.push_back(x.text);
    throw InputError("--reference " + given + ": not among the values of " + s.field + " (" +
                     joined(texts) + ")");
  }
  const bool numeric =
      std::all_of(v.begin(), v.end(), [](const Variant& x) { return x.value.is_number(); });
  if (!numeric)
    throw InputError(s.field +
                     ": the values are not all numbers: name the reference with "
                     "--reference V");
  std::string key;
  for (const PathStep& p : s.path)
    if (!p.key.empty()) key = p.key;
  const bool larger = listed(kFinerWhenLarger, key);
  if (!larger && !listed(kFinerWhenSmaller, key))
    throw InputError(s.field + ": which end of '" + key +
                     "' is the finer is not known (known: " + joined(kFinerWhenLarger) + ", " +
                     joined(kFinerWhenSmaller) + "): name the reference with --reference V");
  for (size_t i = 1; i < v.size(); ++i) {
    const double a = v[i].value.get<double>(), b = v[s.reference].value.get<double>();
    if (larger ? a > b : a < b) s.reference = i;
  }
  s.why = std::string("the finest: the ") + (larger ? "largest" : "smallest") + " value of " + key;
}

// ---- Validation: every variant loaded and its World built before anything runs ----

std::string readText(const std::string& path) {
  if (fs::is_directory(path)) throw InputError(path + ": is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!(in && text << in.rdbuf())) throw InputError(path + ": cannot read the scene file");
  return text.str();
}

// The history columns of a World (as history.csv will have them).
std::vector<std::string> historyColumns(const World& world) {
  std::vector<std::string> names;
  for (const HistoryColumns& family : standardHistoryColumns(world))
    names.insert(names.end(), family.names.begin(), family.names.end());
  return names;
}

void prepare(Study& s, Variant& v, const Json& root, const Arguments& a) {
  Json j = root;
  slot(j, s.path, s.field, a.scene) = v.value;
  const std::string label = "variant " + s.field + "=" + v.text + ": ";
  try {
    v.sceneText = j.dump(2);
    v.scene = loadSceneFromString(v.sceneText, a.scene);
    if (!v.scene.output.history)
      throw SceneError("output.history: is off, and fibra study reads the history");
    WorldDef def;
    def.threads = a.threads;
    const World world(v.scene, def);
    checkScenePlots(world);
    const std::vector<std::string> names = historyColumns(world);
    for (const std::string& c : s.columns)
      if (std::find(names.begin(), names.end(), c) == names.end())
        throw SceneError("--observe: " + unknownColumn(names, c));
  } catch (const SceneError& e) {
    throw InputError(label + e.what());
  }
  v.folder = (fs::path(a.out) / folderName(s.field, v.text)).string();
}

Study prepareStudy(const Arguments& a) {
  Study s;
  const size_t eq = a.vary.find('=');
  if (eq == std::string::npos)
    throw std::invalid_argument("--vary: expected FIELD=V1,V2,..., got '" + a.vary + "'");
  s.field = a.vary.substr(0, eq);
  s.path = parsePath(s.field);
  s.columns = splitCommas(a.observe, "--observe");
  std::set<std::string> texts, folders;
  for (const std::string& text : splitCommas(a.vary.substr(eq + 1), "--vary")) {
    if (!texts.insert(text).second) throw std::invalid_argument("--vary: '" + text + "' twice");
    if (!folders.insert(folderName(s.field, text)).second)
      throw std::invalid_argument("--vary: values give the same folder " +
                                  folderName(s.field, text));
    const Json value = parseValue(text);
    for (const Variant& other : s.variants)
      if (other.value == value)
        throw std::invalid_argument("--vary: '" + text + "' is the value of '" + other.text + "'");
    Variant& v = s.variants.emplace_back();
    v.text = text;
    v.value = value;
  }
  if (s.variants.size() < 2) throw std::invalid_argument("--vary: give at least two values");
  if (fs::exists(a.out) && !fs::is_directory(a.out))
    throw InputError("--out: '" + a.out + "' exists and is not a directory");
  Json root;
  try {
    root = json_reader::parse(readText(a.scene));
  } catch (const SceneError& e) {
    throw InputError(a.scene + ": " + e.what());
  }
  for (Variant& v : s.variants) prepare(s, v, root, a);
  chooseReference(s, a.reference);
  return s;
}

// ---- Running ----

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Solves the variant into its folder; counts as fibra run does (a failure's last attempt is
// the failure, not a cutback).
// The observed columns at the initial state, t = 0, as the history's column families give them
// for a state no increment has reached (the counters 0): where every variant's curve starts.
std::vector<double> initialValues(const World& world, const std::vector<std::string>& columns) {
  std::vector<std::string> names;
  std::vector<double> row;
  for (const HistoryColumns& family : standardHistoryColumns(world)) {
    names.insert(names.end(), family.names.begin(), family.names.end());
    family.values(world, StepReport{}, row);
  }
  std::vector<double> values;
  for (const std::string& c : columns)
    values.push_back(row[size_t(std::find(names.begin(), names.end(), c) - names.begin())]);
  return values;
}

void runVariant(Variant& v, const std::vector<std::string>& columns, int threads) {
  WorldDef def;
  def.threads = threads;
  World world(v.scene, def);
  v.initial = initialValues(world, columns);
  clearOutputs(v.folder);
  Outputs outputs(v.folder, world);
  outputs.keepScene(v.sceneText);  // a variant stopped part-way: fibra run --resume FOLDER
  while (!world.finished()) {
    const auto start = std::chrono::steady_clock::now();
    const StepReport r = world.step();
    v.wall += secondsSince(start);
    if (r.status == StepStatus::Finished) break;
    v.iterations += r.totalIterations;
    if (r.status != StepStatus::Converged) {
      v.cutbacks += std::min(r.cutbacks, v.scene.steps[size_t(r.step)].maxCutbacks);
      v.message = r.message;
      outputs.finish(world);
      return;
    }
    ++v.increments;
    v.cutbacks += r.cutbacks;
    outputs.increment(world, r);
  }
  outputs.finish(world);
  for (const std::string& m : outputs.plotMessages())
    std::fprintf(stderr, "fibra: warning: %s: plot not drawn: %s\n", v.folder.c_str(), m.c_str());
  v.converged = true;
}

// ---- Errors against the reference ----

// A run's observed columns against pseudo-time, from its history.csv.
struct Curves {
  std::vector<double> t;
  std::vector<std::vector<double>> y;  // y[column][row]
};

Curves readCurves(const std::string& csv, const std::vector<std::string>& columns) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string name; std::getline(h, name, ',');) header.push_back(name);
  const auto index = [&](const std::string& name) {
    return size_t(findColumn(header, name, csv, "--observe"));
  };
  std::vector<size_t> at{index("time")};
  for (const std::string& c : columns) at.push_back(index(c));
  Curves curves{{}, std::vector<std::vector<double>>(columns.size())};
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream r(line);
    for (std::string cell; std::getline(r, cell, ',');)
      row.push_back(std::strtod(cell.c_str(), nullptr));
    if (row.size() != header.size()) continue;
    curves.t.push_back(row[at[0]]);
    for (size_t c = 0; c < columns.size(); ++c) curves.y[c].push_back(row[at[c + 1]]);
  }
  return curves;
}

// y(at) by linear interpolation between the rows around `at` (clamped to the ends).
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double at) {
  const size_t hi = size_t(std::upper_bound(t.begin(), t.end(), at) - t.begin());
  if (hi == 0) return y.front();
  if (hi == t.size()) return y.back();
  const double w = (at - t[hi - 1]) / (t[hi] - t[hi - 1]);
  return (1 - w) * y[hi - 1] + w * y[hi];
}

double relative(double difference, double scale) {
  return scale > 0 ? difference / scale : difference;
}

// error = max_k |y(t_k) - y_ref(t_k)| / max_k |y_ref(t_k)| over the reference's times inside
// the variant's span (a relative slack of 1e-9 absorbs pseudo-times summed from increments).
double curveError(const Curves& v, const Curves& ref, size_t c) {
  if (v.t.empty() || ref.t.empty()) return kNaN;
  const double slack = 1e-9 * std::max(1.0, std::abs(ref.t.back()));
  double worst = 0, scale = 0;
  bool any = false;
  for (size_t k = 0; k < ref.t.size(); ++k) {
    scale = std::max(scale, std::abs(ref.y[c][k]));
    if (ref.t[k] < v.t.front() - slack || ref.t[k] > v.t.back() + slack) continue;
    worst = std::max(worst, std::abs(interpolate(v.t, v.y[c], ref.t[k]) - ref.y[c][k]));
    any = true;
  }
  return any ? relative(worst, scale) : kNaN;
}

// The curve from the initial state on: the history has no row at t = 0.
void startAtZero(Curves& curves, const std::vector<double>& initial) {
  if (!curves.t.empty() && !(curves.t.front() > 0)) return;
  curves.t.insert(curves.t.begin(), 0.0);
  for (size_t c = 0; c < curves.y.size(); ++c) curves.y[c].insert(curves.y[c].begin(), initial[c]);
}

void measureErrors(Study& s) {
  const Variant& refVariant = s.variants[s.reference];
  Curves ref = readCurves((fs::path(refVariant.folder) / "history.csv").string(), s.columns);
  startAtZero(ref, refVariant.initial);
  for (Variant& v : s.variants) {
    const size_t n = s.columns.size();
    v.last.assign(n, kNaN);
    v.error.assign(n, kNaN);
    v.final.assign(n, kNaN);
    Curves mine = readCurves((fs::path(v.folder) / "history.csv").string(), s.columns);
    startAtZero(mine, v.initial);
    for (size_t c = 0; c < n && !mine.t.empty(); ++c) v.last[c] = mine.y[c].back();
    if (!v.converged || !refVariant.converged || ref.t.empty()) continue;
    for (size_t c = 0; c < n; ++c) {
      v.error[c] = curveError(mine, ref, c);
      v.final[c] = relative(std::abs(v.last[c] - ref.y[c].back()), std::abs(ref.y[c].back()));
    }
  }
}

// ---- Outputs ----

// error_max: the largest of a variant's errors over the observed columns (NaN when none).
double errorMax(const std::vector<double>& errors) {
  double worst = kNaN;
  for (const double e : errors)
    if (!std::isnan(e)) worst = std::isnan(worst) ? e : std::max(worst, e);
  return worst;
}

std::string cell(double v) {
  std::string out;
  if (!std::isnan(v)) appendNumber(out, v);
  return out;
}

// A wall time to the microsecond (its noise is larger).
std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", s);
  return text;
}

// DIR/study.csv: one row per variant, in the order given.
void writeCsv(const Study& s, const std::string& path) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "field,value,reference,status,wall_s,iterations,increments,cutbacks";
  for (const std::string& c : s.columns) out << ",value_" << c << ",error_" << c << ",final_" << c;
  out << ",error_max\n";
  for (size_t i = 0; i < s.variants.size(); ++i) {
    const Variant& v = s.variants[i];
    out << s.field << "," << v.text << "," << (i == s.reference) << ","
        << (v.converged ? "converged" : "failed") << "," << seconds(v.wall) << "," << v.iterations
        << "," << v.increments << "," << v.cutbacks;
    for (size_t c = 0; c < s.columns.size(); ++c)
      out << "," << cell(v.last[c]) << "," << cell(v.error[c]) << "," << cell(v.final[c]);
    out << "," << cell(errorMax(v.error)) << "\n";
  }
  file.commit();
}

PlotData plotData(const Study& s) {
  PlotData d;
  d.field = s.field;
  d.columns = s.columns;
  d.reference = s.variants[s.reference].text;
  for (size_t i = 0; i < s.variants.size(); ++i) {
    const Variant& v = s.variants[i];
    if (i != s.reference && v.converged)
      d.points.push_back({v.text, v.wall, double(v.iterations), v.error});
  }
  return d;
}

void printHeader(const Study& s, const Arguments& a) {
  std::vector<std::string> texts;
  for (const Variant& v : s.variants) texts.push_back(v.text);
  const std::string values = joined(texts), columns = joined(s.columns);
  std::fprintf(stderr,
               "fibra study: %s, %zu variants of %s (%s); reference %s=%s (%s); observing %s; "
               "in %s\n",
               a.scene.c_str(), s.variants.size(), s.field.c_str(), values.c_str(), s.field.c_str(),
               s.variants[s.reference].text.c_str(), s.why.c_str(), columns.c_str(), a.out.c_str());
}

void printProgress(const Study& s, size_t i) {
  const Variant& v = s.variants[i];
  std::fprintf(stderr,
               "fibra: variant %zu/%zu %s=%s: %.3g s, %d iterations, %d increments, "
               "%d cutbacks, %s%s\n",
               i + 1, s.variants.size(), s.field.c_str(), v.text.c_str(), v.wall, v.iterations,
               v.increments, v.cutbacks, v.converged ? "converged" : "failed: ", v.message.c_str());
}

// Runs every variant, then writes the CSV and the picture; returns the exit status.
int runStudy(Study& s, const Arguments& a) {
  printHeader(s, a);
  fs::create_directories(a.out);
  fs::remove(fs::path(a.out) / "study.png");  // a picture left is this study's
  for (size_t i = 0; i < s.variants.size(); ++i) {
    runVariant(s.variants[i], s.columns, a.threads);
    printProgress(s, i);
  }
  measureErrors(s);
  const std::string csv = (fs::path(a.out) / "study.csv").string();
  writeCsv(s, csv);
  std::printf("fibra: wrote %s\n", csv.c_str());
  if (!s.variants[s.reference].converged) {
    std::fprintf(stderr, "fibra: error: the reference %s=%s failed: no errors measured\n",
                 s.field.c_str(), s.variants[s.reference].text.c_str());
    return kFailed;
  }
  for (const Variant& v : s.variants)
    if (!v.converged)
      std::fprintf(stderr, "fibra: warning: %s=%s failed: left out of the errors and the plot\n",
                   s.field.c_str(), v.text.c_str());
  return drawStudy((fs::path(a.out) / "study.png").string(), plotData(s));
}

}  // namespace

int study(int argc, char** argv) {
  const Arguments a = parse(argc, argv);
  Study s;
  try {
    s = prepareStudy(a);
  } catch (const InputError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  }
  try {
    return runStudy(s, a);
  } catch (const std::runtime_error& e) {  // outputs not written, a history not readable
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kFailed;
  }
}

}  // namespace fibra::study
