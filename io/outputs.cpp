#include "io/outputs.h"

#include "core/errors.h"
#include "core/format.h"
#include "io/output_file.h"
#include "io/plot.h"
#include "io/state_writer.h"
#include "io/vtu_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>

namespace fibra {

namespace fs = std::filesystem;

void checkScenePlots(const World& world) {
  const std::vector<PlotDef>& plots = world.scene().output.plots;
  if (plots.empty()) return;
  std::vector<std::string> columns;
  for (const HistoryColumns& family : standardHistoryColumns(world))
    columns.insert(columns.end(), family.names.begin(), family.names.end());
  const auto check = [&](const std::string& name, const std::string& path) {
    if (std::find(columns.begin(), columns.end(), name) == columns.end())
      throw SceneError(path + ": " + unknownColumn(columns, name));
  };
  for (size_t i = 0; i < plots.size(); ++i) {
    const std::string p = "output.plots[" + std::to_string(i) + "]";
    check(plots[i].x, p + ".x");
    for (size_t k = 0; k < plots[i].y.size(); ++k)
      for (const std::string& term : columnTerms(plots[i].y[k]))
        check(term, p + ".y[" + std::to_string(k) + "]");
  }
}

int clearOutputs(const std::string& dir) {
  if (!fs::is_directory(dir)) return 0;
  static const std::regex own(
      R"((result\.pvd|result(_contacts|_tools)?_[0-9]+\.vtu|history\.csv|final_state\.csv|)"
      R"(resume_state\.bin|resume_scene\.json)(\.part)?)");
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && std::regex_match(entry.path().filename().string(), own))
      doomed.push_back(entry.path());
  for (const fs::path& p : doomed) {
    std::error_code ec;
    fs::remove(p, ec);
    if (ec) throw std::runtime_error("cannot remove " + p.string() + ": " + ec.message());
  }
  return int(doomed.size());
}

Outputs::Outputs(const std::string& dir, const World& world, std::optional<VtuEncoding> encoding)
    : dir_(dir), def_(world.scene().output) {
  checkScenePlots(world);  // before anything is created
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create '" + dir + "': " + ec.message());
  if (def_.vtu) {
    VtuDef vtu;
    vtu.encoding = encoding.value_or(def_.vtuEncoding);
    vtu_.emplace(dir, "result", vtu);
  }
  if (def_.history)
    history_.emplace((fs::path(dir) / "history.csv").string(), standardHistoryColumns(world));
  frame(world);
  checkpoint(world);
}

Outputs::Outputs(const std::string& dir, const World& world, ResumeOutputs,
                 std::optional<VtuEncoding> encoding)
    : dir_(dir), def_(world.scene().output) {
  checkScenePlots(world);
  if (!fs::is_directory(dir)) throw std::runtime_error("no directory '" + dir + "'");
  if (def_.history) resumeHistory(world);
  if (def_.vtu) {
    VtuDef vtu;
    vtu.encoding = encoding.value_or(def_.vtuEncoding);
    resumeFrames(world, vtu);
  }
  // Without checkpoints from here on, the old one would resume from a state now overwritten.
  if (!def_.checkpoint) fs::remove(fs::path(dir_) / kCheckpointFile);
}

void Outputs::keepScene(const std::string& sceneText) {
  if (!def_.checkpoint) return;
  OutputFile copy((fs::path(dir_) / kResumeSceneFile).string());
  copy.stream() << sceneText;
  copy.commit();
}

namespace {

std::vector<std::string> readLines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  if (in.bad() || lines.empty()) throw std::runtime_error("cannot read " + path.string());
  return lines;
}

// The first field of a CSV row (the time column) as a number; NaN when it is not one.
double firstNumber(const std::string& row) {
  try {
    size_t used = 0;
    const std::string field = row.substr(0, row.find(','));
    const double v = std::stod(field, &used);
    return used == field.size() ? v : std::nan("");
  } catch (const std::exception&) {
    return std::nan("");
  }
}

}  // namespace

// The history of the stopped run (history.csv, or history.csv.part when it was killed): its
// rows up to the world's time, under the same header.
void Outputs::resumeHistory(const World& world) {
  const fs::path done = fs::path(dir_) / "history.csv", part = done.string() + ".part";
  // A .part is the newest: left by the last run, killed (a closed history.csv beside it is from
  // an earlier stop).
  const fs::path from = fs::exists(part) ? part : done;
  if (!fs::exists(from)) throw std::runtime_error("no history.csv in '" + dir_ + "'");
  std::vector<std::string> lines = readLines(from);
  std::vector<HistoryColumns> columns = standardHistoryColumns(world);
  std::string header;
  for (const HistoryColumns& family : columns)
    for (const std::string& name : family.names) header += (header.empty() ? "" : ",") + name;
  if (lines[0] != header)
    throw std::runtime_error(from.string() + ": its columns are not this scene's");
  // Rows up to the checkpoint, their times increasing, the last one the checkpoint's; what
  // follows it (rows of increments after the checkpoint, a line cut by a kill) is dropped.
  std::vector<std::string> rows;
  double last = 0;
  const auto fields = [](const std::string& line) {
    return std::count(line.begin(), line.end(), ',');
  };
  for (size_t i = 1; i < lines.size(); ++i) {
    const double t = firstNumber(lines[i]);
    if (t > world.time() || (!(t > last) && last >= world.time())) break;
    if (!(t > last) || fields(lines[i]) != fields(header))
      throw std::runtime_error(from.string() + ": line " + std::to_string(i + 1) +
                               " is not a whole row after t = " + number(last));
    rows.push_back(lines[i]);
    last = t;
  }
  if (last != world.time())
    throw std::runtime_error(from.string() + ": its rows end at t = " + number(last) +
                             ", before the checkpoint's t = " + number(world.time()) +
                             " (rows are missing)");
  history_.emplace(done.string(), std::move(columns), rows);
}

// The frames of the stopped run up to the world's time; the files of later frames removed.
void Outputs::resumeFrames(const World& world, const VtuDef& vtu) {
  const fs::path pvd = fs::path(dir_) / "result.pvd";
  std::vector<double> times;
  const SceneDef& s = world.scene();
  const bool contacts = s.contact.enabled || !s.tools.empty(), tools = !s.tools.empty();
  // The frames listed up to the checkpoint, each with its files; the PVD is rewritten after
  // every frame, so at most one frame (the next, of an increment after the checkpoint) may be
  // on disk beyond them.
  try {
    for (const PvdFrame& f : readPvdFrames(readWholeFile(pvd.string()))) {
      if (f.time > world.time()) break;
      const int i = int(times.size());
      for (const char* part : {"", "_contacts", "_tools"}) {
        const bool expected = part[1] == 'c' ? contacts : part[1] == 't' ? tools : true;
        char name[64];
        std::snprintf(name, sizeof name, "result%s_%04d.vtu", part, i);
        if (expected && !fs::exists(fs::path(dir_) / name))
          throw std::runtime_error("lists frame " + std::to_string(i) + ", whose " + name +
                                   " is missing");
      }
      times.push_back(f.time);
    }
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(pvd.string() + ": " + e.what());
  }
  static const std::regex frameFile(R"(result(_contacts|_tools)?_([0-9]+)\.vtu(\.part)?)");
  std::vector<fs::path> later;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (!std::regex_match(name, m, frameFile)) continue;
    const long index = std::stol(m[2].str());
    if (index > long(times.size()))
      throw std::runtime_error(pvd.string() + ": lists " + std::to_string(times.size()) +
                               " frames up to the checkpoint, but " + name +
                               " is there too (a damaged PVD)");
    if (index == long(times.size())) later.push_back(entry.path());
  }
  for (const fs::path& p : later) fs::remove(p);
  vtu_.emplace(dir_, "result", vtu);
  vtu_->resume(times, contacts, tools,
               tools ? firstFrameExtents(world) : std::vector<ToolExtent>{});
  framed_ = times.empty() ? -1 : times.back();
}

// The tools are drawn over the extents of the first frame's fibres (io/vtu_writer.h): read back
// from result_0000.vtu.
std::vector<ToolExtent> Outputs::firstFrameExtents(const World& world) const {
  Eigen::VectorXd q = world.fibres().qRef;
  const fs::path first = fs::path(dir_) / "result_0000.vtu";
  const std::vector<double> points = readVtuArrays(readWholeFile(first.string()))["Points/"];
  if (points.size() < 3 * size_t(world.fibres().nodes()))
    throw std::runtime_error(first.string() + ": not this scene's first frame");
  for (Index n = 0; n < world.fibres().nodes(); ++n)
    x0Of(q, n) = Vec3(points[3 * n], points[3 * n + 1], points[3 * n + 2]);
  return toolExtents(world.tools(), world.fibres(), q);
}

Outputs::~Outputs() = default;

void Outputs::increment(const World& world, const StepReport& r) {
  if (history_) history_->append(world, r);
  const StepDef& st = world.scene().steps[r.step];
  if (r.increment % st.outputEvery == 0 || r.increment == st.increments) frame(world);
  checkpoint(world);
}

// resume_state.bin, replaced whole (io/output_file.h): a run killed at any moment leaves the
// previous checkpoint or this one.
void Outputs::checkpoint(const World& world) {
  if (!def_.checkpoint) return;
  OutputFile file((fs::path(dir_) / kCheckpointFile).string());
  world.saveCheckpoint(file.stream());
  file.commit();
}

void Outputs::finish(const World& world) {
  if (world.time() != framed_) frame(world);
  if (def_.finalState)
    writeState((fs::path(dir_) / "final_state.csv").string(), world.fibres(), world.fibres().q);
  if (history_) history_->close();
  if (!history_) return;
  for (size_t i = 0; i < def_.plots.size(); ++i) {
    const PlotDef& p = def_.plots[i];
    try {
      drawCurves(dir_, CurvePlot{p.x, p.y, p.title, p.file});
      plotsDrawn_.push_back((fs::path(dir_) / p.file).string());
    } catch (const std::runtime_error& e) {
      plotMessages_.push_back("output.plots[" + std::to_string(i) + "] (" + p.file +
                              "): " + e.what());
    }
  }
}

int Outputs::frames() const { return vtu_ ? vtu_->frames() : 0; }

void Outputs::frame(const World& world) {
  framed_ = world.time();
  if (!vtu_) return;
  const SceneDef& s = world.scene();
  VtuFrame f{world.fibres(), world.fibres().q, world.time()};
  std::optional<ContactSnapshot> contacts;
  if (s.contact.enabled || !s.tools.empty()) contacts = world.contactSnapshot();
  f.contacts = contacts ? &*contacts : nullptr;
  f.tools = s.tools.empty() ? nullptr : &world.tools();
  vtu_->write(f);
}

}  // namespace fibra
