// fibra, the command-line program: solves a scene file and writes its results.
//
//   fibra run SCENE.json --out DIR [--threads N] [--trace FILE]
//   fibra describe SCENE.json     the stages of an iteration for the scene, as Markdown
//
// Order of work: the scene is loaded, validated and the World built before anything is
// created, so bad input leaves no trace on disk (exit 2). Then DIR is created and filled:
// result.pvd + result_NNNN.vtu (the initial state and every output_every-th converged increment,
// with each step's last), history.csv (a row per converged increment), final_state.csv.
// Progress goes to stderr, one line per Newton iteration and per increment.
//
// Exit status: 0 solved; 1 an increment failed (after its cutbacks) or output could not be
// written; 2 bad usage or a bad scene; 130 interrupted by SIGINT. On failure and interruption the
// last converged state is written (a frame, the final state) and the history closed.
//
// SIGINT sets the program's one process-level flag; the World polls it through its cancel
// callback between Newton iterations and returns the last converged state. A second SIGINT
// kills the program at once.
#include "io/scene_loader.h"
#include "engine/world.h"
#include "io/history_writer.h"
#include "io/state_writer.h"
#include "io/vtu_writer.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace fibra;

constexpr int kSolved = 0, kFailed = 1, kBadInput = 2, kInterrupted = 130;

std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT flag must be signal-safe");

extern "C" void onInterrupt(int) {
  interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the program at once
}

const char* const kUsage =
    "usage: fibra run SCENE.json --out DIR [--threads N] [--trace FILE]\n"
    "       fibra describe SCENE.json\n"
    "       fibra --help\n"
    "\n"
    "describe: prints the stages of an iteration for the scene (Markdown): every system, the\n"
    "stores it reads and writes, the systems it waits for (docs/ARCHITECTURE.md).\n"
    "\n"
    "Solves the scene (format: docs/SCENE.md) and writes into DIR (created if needed):\n"
    "  result.pvd, result_NNNN.vtu  the fibres (centrelines and surfaces) for ParaView\n"
    "  history.csv                  one row per converged increment: counters, reactions, probes\n"
    "  final_state.csv              every node's x0, g1, g2 at the last converged state\n"
    "Options:\n"
    "  --out DIR       output directory (required)\n"
    "  --threads N     worker threads (default: all cores)\n"
    "  --trace FILE    profile: Chrome trace JSON in FILE (open in Perfetto), per-stage\n"
    "                  times in FILE without .json plus .stages.csv\n"
    "Exit status: 0 solved, 1 an increment failed or output failed, 2 bad usage or scene,\n"
    "130 interrupted (Ctrl-C; the last converged state is written).\n";

struct Options {
  std::string scene, out, trace;
  int threads = 0;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

int positiveInt(const std::string& text, const std::string& option) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || v < 1)
    throw UsageError(option + ": expected a positive integer, got '" + text + "'");
  return v;
}

Options parseRun(int argc, char** argv) {
  Options o;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--out" || a == "--threads" || a == "--trace") {
      if (!hasValue) throw UsageError(a + ": missing value");
      const std::string v = argv[++i];
      if (a == "--out")
        o.out = v;
      else if (a == "--threads")
        o.threads = positiveInt(v, a);
      else
        o.trace = v;
    } else if (a.starts_with("-")) {
      throw UsageError("unknown option '" + a + "'");
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw UsageError("more than one scene file ('" + o.scene + "', '" + a + "')");
    }
  }
  if (o.scene.empty()) throw UsageError("missing the scene file");
  if (o.out.empty()) throw UsageError("missing --out DIR");
  if (fs::exists(o.out) && !fs::is_directory(o.out))
    throw UsageError("--out: '" + o.out + "' exists and is not a directory");
  const fs::path traceDir = fs::path(o.trace).parent_path();
  if (!o.trace.empty() && !traceDir.empty() && !fs::is_directory(traceDir))
    throw UsageError("--trace: no directory '" + traceDir.string() + "'");
  return o;
}

std::string stageCsvPath(std::string trace) {
  if (trace.ends_with(".json")) trace.resize(trace.size() - 5);
  return trace + ".stages.csv";
}

void printIteration(const Progress& p, int steps) {
  std::fprintf(stderr, "step %d/%d  t = %-10.6g load %5.1f%%  iteration %2d  residual %.3e\n",
               p.step + 1, steps, p.time, 100 * p.loadFactor, p.iteration, p.residual);
}

void printIncrement(const StepReport& r, const SceneDef& scene) {
  std::fprintf(stderr,
               "step %d/%zu  increment %d/%d  t = %.6g  converged: %d iterations, %d cutbacks, "
               "residual %.3e, %.3f s\n",
               r.step + 1, scene.steps.size(), r.increment, scene.steps[r.step].increments, r.time,
               r.iterations, r.cutbacks, r.residual, r.timings.total);
  if (r.cutbacks > 0) std::fprintf(stderr, "  %s\n", r.message.c_str());
  const StepDef& st = scene.steps[r.step];
  if (st.damping > 0 && r.increment == st.increments && r.viscousForce > 1e-2)
    std::fprintf(stderr,
                 "  note: the step ends %.3g of the reference force away from static equilibrium "
                 "(viscous_force); hold the loads in a step with damping to let the state settle\n",
                 r.viscousForce);
  if (!scene.contact.enabled && scene.tools.empty()) return;
  const ContactReport& c = r.contact;
  std::fprintf(stderr,
               "  contact: %d zones, %d + %d tool elements (%d active, %d sliding), max "
               "penetration %.3g mm (%.2f p_max), loops A %d B %d, %d restarts; detection: %d "
               "passes, %d broadphase rebuilds, %d candidate pairs\n",
               c.zones, c.elements, c.toolElements, c.active, c.sliding, c.maxPenetration,
               c.maxPenetrationRatio, c.detectionLoops, c.normalLoops, c.restarts, c.detections,
               c.broadphaseRebuilds, c.candidatePairs);
}

// The run's output files, as the scene's output section asks.
class Outputs {
 public:
  Outputs(const std::string& dir, const World& world) : dir_(dir), def_(world.scene().output) {
    if (def_.vtu) vtu_.emplace(dir);
    if (def_.history)
      history_.emplace((fs::path(dir) / "history.csv").string(), standardHistoryColumns(world));
    frame(world);
  }

  void increment(const World& world, const StepReport& r) {
    if (history_) history_->append(world, r);
    const StepDef& st = world.scene().steps[r.step];
    if (r.increment % st.outputEvery == 0 || r.increment == st.increments) frame(world);
  }

  // The last converged state: a frame if it has none yet, the final state, the history closed.
  void finish(const World& world) {
    if (world.time() != framed_) frame(world);
    if (def_.finalState)
      writeState((fs::path(dir_) / "final_state.csv").string(), world.fibres(), world.fibres().q);
    if (history_) history_->close();
  }

 private:
  void frame(const World& world) {
    framed_ = world.time();
    if (!vtu_) return;
    const SceneDef& s = world.scene();
    if (s.contact.enabled || !s.tools.empty()) {
      const ContactSnapshot contacts = world.contactSnapshot();
      vtu_->write(world.fibres(), world.fibres().q, world.time(), &contacts);
    } else {
      vtu_->write(world.fibres(), world.fibres().q, world.time());
    }
  }
  std::string dir_;
  OutputDef def_;
  std::optional<VtuSeries> vtu_;
  std::optional<HistoryWriter> history_;
  double framed_ = -1;
};

// Solves every increment; returns the exit status.
int solve(World& world, Outputs& outputs) {
  const SceneDef& scene = world.scene();
  int increments = 0, iterations = 0;
  while (!world.finished()) {
    const StepReport r = world.step();
    if (r.status == StepStatus::Converged) {
      ++increments;
      iterations += r.totalIterations;
      printIncrement(r, scene);
      outputs.increment(world, r);
      continue;
    }
    if (r.status == StepStatus::Finished) break;
    outputs.finish(world);
    if (r.status == StepStatus::Cancelled) {
      std::fprintf(stderr, "fibra: interrupted; wrote the last converged state, t = %g\n",
                   world.time());
      return kInterrupted;
    }
    std::fprintf(stderr,
                 "fibra: step %d/%zu, increment %d failed: %s\nfibra: wrote the last converged "
                 "state, t = %g\n",
                 r.step + 1, scene.steps.size(), r.increment, r.message.c_str(), world.time());
    return kFailed;
  }
  outputs.finish(world);
  std::fprintf(stderr, "fibra: solved: %d increments, %d Newton iterations, t = %g\n", increments,
               iterations, world.time());
  return kSolved;
}

void writeTrace(const Trace& trace, const std::string& path) {
  for (const auto& [target, write] : {std::pair{path, &Trace::writeChromeJson},
                                      std::pair{stageCsvPath(path), &Trace::writeStageCsv}}) {
    (trace.*write)(target + ".part");
    fs::rename(target + ".part", target);
  }
  std::fprintf(stderr, "fibra: trace in %s and %s\n", path.c_str(), stageCsvPath(path).c_str());
}

std::unique_ptr<World> buildWorld(const Options& o, const SceneDef& scene, Trace* trace) {
  WorldDef def;
  def.threads = o.threads;
  def.trace = trace;
  def.progress = [steps = int(scene.steps.size())](const Progress& p) { printIteration(p, steps); };
  def.cancel = [] { return interrupted.load(); };
  try {
    return std::make_unique<World>(scene, def);
  } catch (const SceneError& e) {
    throw SceneError(o.scene + ": " + e.what());
  }
}

int run(const Options& o) {
  std::unique_ptr<Trace> trace = o.trace.empty() ? nullptr : std::make_unique<Trace>();
  std::unique_ptr<World> world;
  try {
    world = buildWorld(o, loadScene(o.scene), trace.get());
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  }
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) {
    std::fprintf(stderr, "fibra: error: cannot create '%s': %s\n", o.out.c_str(),
                 ec.message().c_str());
    return kFailed;
  }
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);

  Outputs outputs(o.out, *world);
  const int status = solve(*world, outputs);
  if (trace) writeTrace(*trace, o.trace);
  return status;
}

// fibra describe SCENE.json: the scene's stages, built exactly as `run` builds them.
int describe(int argc, char** argv) {
  if (argc != 3 || std::string(argv[2]).starts_with("-"))
    throw UsageError("describe: expected exactly one scene file");
  try {
    const SceneDef scene = loadScene(argv[2]);  // its errors name the file
    try {
      std::fputs(World(scene).describe().c_str(), stdout);
    } catch (const SceneError& e) {
      throw SceneError(std::string(argv[2]) + ": " + e.what());
    }
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  }
  return kSolved;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kUsage, stdout);
    return kSolved;
  }
  try {
    if (command == "describe") return describe(argc, argv);
    if (command != "run")
      throw UsageError(command.empty() ? "missing command" : "unknown command '" + command + "'");
    return run(parseRun(argc, argv));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "fibra: %s\n%.*s(fibra --help for more)\n", e.what(),
                 int(std::strchr(kUsage, '\n') - kUsage + 1), kUsage);
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kFailed;
  }
}
