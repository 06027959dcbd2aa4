#include "io/outputs.h"

#include "io/state_writer.h"

#include <filesystem>
#include <regex>
#include <stdexcept>

namespace fibra {

namespace fs = std::filesystem;

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
