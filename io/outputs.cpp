#include "io/outputs.h"

#include "core/errors.h"
#include "io/plot.h"
#include "io/state_writer.h"

#include <algorithm>
#include <filesystem>
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
      R"((result\.pvd|result(_contacts|_tools)?_[0-9]+\.vtu|history\.csv|final_state\.csv)(\.part)?)");
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
}

Outputs::~Outputs() = default;

void Outputs::increment(const World& world, const StepReport& r) {
  if (history_) history_->append(world, r);
  const StepDef& st = world.scene().steps[r.step];
  if (r.increment % st.outputEvery == 0 || r.increment == st.increments) frame(world);
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
