// The output files of a run, as the scene's output section asks: what `fibra run` writes, as a
// library API, so that a program embedding fibra writes the same files in the same way.
//
//   fibra::World world(scene);
//   fibra::clearOutputs(dir);                 // optional: remove a previous run's files
//   fibra::Outputs out(dir, world);           // creates dir, writes frame 0, opens the history
//   while (!world.finished()) {
//     const fibra::StepReport r = world.step();
//     if (r.status != fibra::StepStatus::Converged) break;
//     out.increment(world, r);                // history row; a frame every output_every-th
//   }
//   out.finish(world);                        // last frame, final state, history closed
//
// Files in DIR (docs/SCENE.md, "What fibra run writes"): result.pvd with result_NNNN.vtu (the
// fibres, part 0), result_contacts_NNNN.vtu (contact elements, part 1, with contact or tools) and
// result_tools_NNNN.vtu (the tools' surfaces, part 2, with tools); history.csv (one row per
// converged increment; history.csv.part until finish()); final_state.csv; the PNGs of
// output.plots with their gnuplot scripts (NAME.gp); with output.checkpoint, resume_state.bin,
// the last converged state (World::saveCheckpoint), rewritten after every converged increment,
// from which `Outputs(dir, world, ResumeOutputs{})` continues the files. Every file appears
// whole or not at all (io/output_file.h). Serial: call from one thread, between world.step()
// calls (not concurrently with them). Errors: std::runtime_error when a file cannot be written.
#pragma once

#include "engine/world.h"
#include "io/history_writer.h"
#include "io/vtu_writer.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fibra {

// The history columns the scene's output.plots name, checked against the columns this World's
// history will have (before solving); SceneError "output.plots[i].y[k]: unknown column ...".
void checkScenePlots(const World& world);

// Removes from `dir` the files a run of fibra writes there (result.pvd, result_*.vtu,
// history.csv, final_state.csv and their .part files) and nothing else; returns how many. A
// missing directory is fine (0). Throws std::runtime_error when a file cannot be removed.
int clearOutputs(const std::string& dir);

// The checkpoint a run writes into its directory, and the scene `fibra run` keeps beside it.
inline constexpr const char* kCheckpointFile = "resume_state.bin";
inline constexpr const char* kResumeSceneFile = "resume_scene.json";

// Tag of the Outputs constructor that continues a stopped run's files.
struct ResumeOutputs {};

class Outputs {
 public:
  // Creates `dir` when needed, writes the initial frame and the history's header. The VTU
  // encoding is `encoding`, or the scene's output.vtu_format when nullopt. Throws
  // std::runtime_error when `dir` cannot be created or a file cannot be written.
  Outputs(const std::string& dir, const World& world,
          std::optional<VtuEncoding> encoding = std::nullopt);
  // Continues the files of a run in `dir` that stopped, for a world restored from its
  // checkpoint (World::restoreCheckpoint with dir's resume_state.bin): keeps the history rows and
  // frames up to world.time(), removes later ones (left by a run killed after its last
  // checkpoint), then goes on as above. Throws std::runtime_error when dir's history or PVD is
  // missing or unreadable, or its history has other columns than this world's.
  Outputs(const std::string& dir, const World& world, ResumeOutputs,
          std::optional<VtuEncoding> encoding = std::nullopt);
  ~Outputs();

  // After every converged increment: a history row, and a frame when the increment is an
  // output_every-th one of its step or the step's last.
  void increment(const World& world, const StepReport& report);
  // The scene's text (a scene file's, or its JSON) as DIR/resume_scene.json beside the
  // checkpoint, so that `fibra run --resume DIR` can go on from it; nothing without
  // output.checkpoint. Throws std::runtime_error when it cannot be written.
  void keepScene(const std::string& sceneText);
  // At the end of a run (solved, failed or cancelled): the last converged state as a frame
  // (unless it has one), final_state.csv, history.csv closed (renamed from .part), then the
  // scene's output.plots drawn (io/plot.h); a plot that cannot be drawn (no gnuplot, no row)
  // does not stop the others: its message is in plotMessages().
  void finish(const World& world);
  // "output.plots[i] (FILE): what went wrong", one per plot not drawn by finish().
  const std::vector<std::string>& plotMessages() const { return plotMessages_; }
  // The PNGs finish() drew.
  const std::vector<std::string>& plotsDrawn() const { return plotsDrawn_; }

  int frames() const;                       // VTU frames written so far
  const std::string& dir() const { return dir_; }

 private:
  void frame(const World& world);
  void checkpoint(const World& world);
  void resumeHistory(const World& world);
  void resumeFrames(const World& world, const VtuDef& vtu);
  std::vector<ToolExtent> firstFrameExtents(const World& world) const;
  std::string dir_;
  OutputDef def_;
  std::optional<VtuSeries> vtu_;
  std::optional<HistoryWriter> history_;
  double framed_ = -1;  // pseudo-time of the last frame
  std::vector<std::string> plotMessages_, plotsDrawn_;
};

}  // namespace fibra
