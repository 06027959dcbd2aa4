// fibra, the command-line program: a thin shell over the library (engine/world.h, io/outputs.h)
// that solves a scene file and writes its results.
//
//   fibra run SCENE.json --out DIR [options]   solve (fibra --help lists the options)
//   fibra run --resume DIR [options]           go on from DIR's last converged increment
//   fibra check SCENE.json                     validate, print the problem's size, no solve
//   fibra describe SCENE.json                  the stages of an iteration, as Markdown
//   fibra expand SCENE.json [--out FILE]       the scene with its generators expanded
//   fibra plot RUN_DIR --x C --y C[,C...]      history curves as a PNG (app/pictures.h)
//   fibra section RUN_DIR [--plane z=VALUE]    the fibres' cross-sections as a PNG
//   fibra study SCENE.json --vary F=V1,V2 ...  speed against error of variants (app/study.h)
//   fibra --version
//
// Order of work: the scene is loaded, validated and the World built before anything is
// created, so bad input leaves no trace on disk (exit 2). Then DIR is locked for the run's life
// (a second run into it exits 1), fibra's own files from an earlier run in DIR are removed
// (io/outputs.h: clearOutputs; other files stay) and DIR is filled by fibra::Outputs. Progress
// goes to stderr: a header, one line per converged increment (per Newton iteration too with
// --verbose; none with --quiet), a summary (app/terminal.h).
//
// Exit status: 0 solved; 1 an increment failed (after its cutbacks) or output could not be
// written; 2 bad usage or a bad scene; 130 interrupted by SIGINT, 143 by SIGTERM. On failure and
// interruption the last converged state is written (a frame, the final state) and the history
// closed. After every converged increment the state is checkpointed (DIR/resume_state.bin, with
// the scene kept as DIR/resume_scene.json), so that `fibra run --resume DIR` goes on from the
// last converged increment of a run that was stopped, failed or killed, and ends bitwise where
// the uninterrupted run ends (docs/SCENE.md "Stopping and resuming a run").
//
// SIGINT and SIGTERM set the program's one process-level flag; the World polls it through its
// cancel callback between Newton iterations and returns the last converged state. A second
// signal kills the program at once.
#include "app/arguments.h"
#include "app/pictures.h"
#include "app/study.h"
#include "app/terminal.h"
#include "core/allocator.h"
#include "core/format.h"
#include "engine/world.h"
#include "fibra/version.h"
#include "io/output_file.h"
#include "io/outputs.h"
#include "io/scene_loader.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace fibra;
using terminal::Verbosity;

constexpr int kSolved = 0, kFailed = 1, kBadInput = 2;

std::atomic<int> stopSignal{0};  // the signal that asked the run to stop, 0 while none has
static_assert(std::atomic<int>::is_always_lock_free, "the signal flag must be signal-safe");

extern "C" void onStopSignal(int signal) {
  stopSignal.store(signal);
  std::signal(SIGINT, SIG_DFL);  // a second signal ends the program at once
  std::signal(SIGTERM, SIG_DFL);
}

const char* const kUsage =
    "usage: fibra run SCENE.json --out DIR [--threads N] [--trace FILE] [--vtu-format F]\n"
    "                 [--quiet | --verbose]\n"
    "       fibra run --resume DIR [--threads N] [--trace FILE] [--vtu-format F]\n"
    "                 [--quiet | --verbose]\n"
    "       fibra check SCENE.json\n"
    "       fibra describe SCENE.json\n"
    "       fibra expand SCENE.json [--out FILE]\n"
    "       fibra plot RUN_DIR --x COLUMN --y COLUMN[,COLUMN...] [--out FILE.png] [--title T]\n"
    "       fibra section RUN_DIR [--plane AXIS[=VALUE]] [--frame N[,N...]|last]\n"
    "                     [--out FILE.png] [--title T]\n"
    "       fibra study SCENE.json --vary FIELD=V1,V2,... --observe COLUMN[,COLUMN...]\n"
    "                   --out DIR [--reference V] [--threads N]\n"
    "       fibra --version | --help\n"
    "\n"
    "run: solves the scene (format: docs/SCENE.md) and writes into DIR (created if needed; the\n"
    "files of an earlier run there are replaced):\n"
    "  result.pvd, result_NNNN.vtu  the fibres (centrelines and surfaces) for ParaView, with\n"
    "                               result_contacts_NNNN.vtu, result_tools_NNNN.vtu\n"
    "  history.csv                  one row per converged increment: counters, reactions, probes\n"
    "  final_state.csv              every node's x0, g1, g2 at the last converged state\n"
    "  resume_state.bin             the last converged state (output.checkpoint), with the\n"
    "                               scene as resume_scene.json: for --resume\n"
    "check: validates the scene and prints the problem's size and contact parameters.\n"
    "describe: prints the stages of an iteration for the scene (Markdown): every system, the\n"
    "stores it reads and writes, the systems it waits for (docs/ARCHITECTURE.md).\n"
    "expand: writes the scene with its generators expanded as plain JSON (to FILE, else to\n"
    "stdout); it loads to the same scene (docs/SCENE.md, Generators).\n"
    "plot: draws history columns of a run (RUN_DIR/history.csv) against one another with\n"
    "gnuplot: FILE.png (default RUN_DIR/Y_vs_X.png) and its script FILE.gp (docs/PLOTS.md).\n"
    "section: cuts the fibres of a frame (default: the last) by the plane AXIS = VALUE (default:\n"
    "normal to the fibres' longest span, at its middle) and draws the sections: FILE.png\n"
    "(default RUN_DIR/section.png; FILE_NNNN.png per frame for several frames), the outlines\n"
    "FILE.dat, the script FILE.gp.\n"
    "study: runs the scene once per value of FIELD (a path in the scene: fibres[0].elements,\n"
    "steps[0].increments, solver.strategy), each into DIR/FIELD=VALUE; measures wall time,\n"
    "Newton iterations and the error of the observed history columns against the reference\n"
    "(--reference V, else the finest value of a known numeric field): DIR/study.csv, and\n"
    "DIR/study.png with its script DIR/study.gp (docs/PLOTS.md).\n"
    "Options of run:\n"
    "  --out DIR         output directory (required)\n"
    "  --resume DIR      go on from the last converged increment of the run in DIR (stopped,\n"
    "                    failed or killed), with its scene; its files are continued\n"
    "  --threads N       worker threads (default: all cores)\n"
    "  --trace FILE      profile: Chrome trace JSON in FILE (open in Perfetto), per-stage\n"
    "                    times in FILE without .json plus .stages.csv\n"
    "  --vtu-format F    binary (zlib-compressed, the default) or ascii; overrides the scene's\n"
    "                    output.vtu_format\n"
    "  --quiet           only errors and the summary\n"
    "  --verbose         a line per Newton iteration, and contact details per increment\n"
    "Exit status: 0 solved, 1 an increment failed or output failed, 2 bad usage or scene,\n"
    "130 interrupted (Ctrl-C), 143 terminated (SIGTERM; `timeout` then reports its own 124);\n"
    "the last converged state and the history are written; --resume goes on from there.\n";

// The usage line of `command` ("fibra plot RUN_DIR ..."), or of run for any other (both of its
// forms).
std::string usageLine(const std::string& command) {
  const std::string usage = kUsage;
  // The entry starting at `from`, with its continuation lines (indented past "       fibra").
  const auto entry = [&usage](size_t from) {
    size_t end = usage.find('\n', from);
    while (usage.compare(end, 9, "\n        ") == 0) end = usage.find('\n', end + 1);
    return usage.substr(from, end - from);
  };
  size_t at = command.empty() ? std::string::npos : usage.find("fibra " + command + " ");
  if (at == std::string::npos || at > usage.find("\n\n") || command == "run")
    return entry(usage.find("fibra run")) + "\n       " + entry(usage.find("fibra run --resume"));
  return entry(at);
}

struct Options {
  std::string scene, out, trace;
  bool resume = false;  // --resume DIR: scene and state from DIR, outputs continued there
  int threads = 0;
  std::optional<VtuEncoding> vtuEncoding;
  Verbosity verbosity = Verbosity::Normal;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

VtuEncoding vtuFormat(const std::string& text) {
  if (text == "binary") return VtuEncoding::Binary;
  if (text == "ascii") return VtuEncoding::Ascii;
  throw UsageError("--vtu-format: expected binary or ascii, got '" + text + "'");
}

// An option with a value: stores it and returns true; false for any other argument.
bool valueOption(Options& o, const std::string& a, const std::string& v) {
  if (a == "--out")
    o.out = v;
  else if (a == "--resume")
    o.out = v, o.resume = true;
  else if (a == "--threads")
    o.threads = arguments::positiveInt(v, a);
  else if (a == "--trace")
    o.trace = v;
  else if (a == "--vtu-format")
    o.vtuEncoding = vtuFormat(v);
  else
    return false;
  return true;
}

void checkPaths(const Options& o) {
  if (o.resume && !o.scene.empty())
    throw UsageError("--resume: the scene is the one in DIR, give no scene file");
  if (o.resume && !fs::is_directory(o.out))
    throw UsageError("--resume: no directory '" + o.out + "'");
  if (o.scene.empty() && !o.resume) throw UsageError("missing the scene file");
  if (o.out.empty()) throw UsageError("missing --out DIR");
  if (fs::exists(o.out) && !fs::is_directory(o.out))
    throw UsageError("--out: '" + o.out + "' exists and is not a directory");
  const fs::path traceDir = fs::path(o.trace).parent_path();
  if (!o.trace.empty() && !traceDir.empty() && !fs::is_directory(traceDir))
    throw UsageError("--trace: no directory '" + traceDir.string() + "'");
  if (!o.trace.empty()) {  // find out now, not after a long run, whether it can be written
    const std::string probe = o.trace + ".part";
    const bool existed = fs::exists(probe);
    const bool writable = std::ofstream(probe, std::ios::app).good();
    if (!existed) fs::remove(probe);
    if (!writable) throw UsageError("--trace: cannot write '" + o.trace + "'");
  }
}

Options parseRun(int argc, char** argv) {
  Options o;
  std::set<std::string> seen;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.starts_with("--") && !seen.insert(a == "--verbose" ? "--quiet" : a).second)
      throw UsageError(a == "--quiet" || a == "--verbose"
                           ? "--quiet and --verbose: give at most one of them"
                           : a + ": given twice");
    if (seen.count("--out") && seen.count("--resume"))
      throw UsageError("--out and --resume: give one of them (a resumed run writes into DIR)");
    if (a == "--out" || a == "--resume" || a == "--threads" || a == "--trace" ||
        a == "--vtu-format") {
      if (i + 1 >= argc) throw UsageError(a + ": missing value");
      valueOption(o, a, argv[++i]);
    } else if (a == "--quiet" || a == "--verbose") {
      o.verbosity = a == "--quiet" ? Verbosity::Quiet : Verbosity::Verbose;
    } else if (a.starts_with("-")) {
      throw UsageError("unknown option '" + a + "'");
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw UsageError("more than one scene file ('" + o.scene + "', '" + a + "')");
    }
  }
  checkPaths(o);
  return o;
}

std::string stageCsvPath(std::string trace) {
  if (trace.ends_with(".json")) trace.resize(trace.size() - 5);
  return trace + ".stages.csv";
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The run's last files, and the scene's plots: a plot not drawn is a warning, not a failure.
void finishOutputs(const World& world, Outputs& outputs, Verbosity verbosity) {
  outputs.finish(world);
  for (const std::string& message : outputs.plotMessages())
    std::fprintf(stderr, "fibra: warning: plot not drawn: %s\n", message.c_str());
  if (verbosity != Verbosity::Quiet)
    for (const std::string& png : outputs.plotsDrawn())
      std::fprintf(stderr, "fibra: plot %s\n", png.c_str());
}

// Solves every increment; returns the exit status.
int solve(World& world, Outputs& outputs, Verbosity verbosity) {
  const SceneDef& scene = world.scene();
  const auto start = std::chrono::steady_clock::now();
  int increments = 0, iterations = 0, cutbacks = 0;
  terminal::Explained explained;
  const auto summary = [&](const char* what) {
    std::fprintf(stderr,
                 "fibra: %s: t = %g, %s, %s, %s, %.3g s; %s, history and final state in %s\n",
                 what, world.time(), counted(increments, "increment").c_str(),
                 counted(iterations, "Newton iteration").c_str(),
                 counted(cutbacks, "cutback").c_str(), secondsSince(start),
                 counted(outputs.frames(), "frame").c_str(), outputs.dir().c_str());
  };
  while (!world.finished()) {
    const StepReport r = world.step();
    if (r.status == StepStatus::Converged) {
      ++increments;
      iterations += r.totalIterations;
      cutbacks += r.cutbacks;
      terminal::printIncrement(r, scene, verbosity, explained);
      outputs.increment(world, r);
      continue;
    }
    if (r.status == StepStatus::Finished) break;
    // The failed or cancelled increment's attempts count too; a failure's last attempt is the
    // failure, not a cutback.
    iterations += r.totalIterations;
    cutbacks += r.status == StepStatus::Failed
                    ? std::min(r.cutbacks, scene.steps[size_t(r.step)].maxCutbacks)
                    : r.cutbacks;
    finishOutputs(world, outputs, verbosity);
    if (r.status == StepStatus::Cancelled) {
      const int signal = stopSignal.load();
      summary(signal == SIGTERM ? "terminated (SIGTERM), wrote the last converged state"
                                : "interrupted, wrote the last converged state");
      return 128 + (signal ? signal : SIGINT);
    }
    std::fprintf(stderr, "fibra: step %d/%zu, increment %d failed: %s\n", r.step + 1,
                 scene.steps.size(), r.increment, r.message.c_str());
    if (!r.normalChanges.empty() && verbosity != Verbosity::Quiet)
      terminal::printNormalChanges(r, false, explained);
    summary("failed, wrote the last converged state");
    return kFailed;
  }
  finishOutputs(world, outputs, verbosity);
  summary("solved");
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

// The scene loaded and its World built; SceneError messages name the file.
std::unique_ptr<World> buildWorld(const std::string& path, WorldDef def) {
  const SceneDef scene = loadScene(path);  // its errors name the file
  try {
    auto world = std::make_unique<World>(scene, def);
    checkScenePlots(*world);  // the plots' columns, known once the World is built
    return world;
  } catch (const SceneError& e) {
    throw SceneError(path + ": " + e.what());
  }
}

WorldDef worldDef(const Options& o, Trace* trace) {
  WorldDef def;
  def.threads = o.threads;
  def.trace = trace;
  if (o.verbosity == Verbosity::Verbose)
    def.progress = [](const Progress& p) { terminal::printIteration(p); };
  def.cancel = [] { return stopSignal.load() != 0; };
  return def;
}

// An exclusive lock on the output directory for the run's life (flock on the directory itself:
// no file is added, and the lock goes with the process however it ends), so that two runs
// cannot write, clear or resume the same DIR at once.
class DirectoryLock {
 public:
  DirectoryLock() = default;
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  ~DirectoryLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  // Creates `dir` when needed; std::runtime_error when another run holds it.
  void take(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create '" + dir + "': " + ec.message());
    fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error("cannot open '" + dir + "'");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw std::runtime_error("another fibra run is writing into '" + dir +
                               "' (wait for it to end, or stop it)");
  }

 private:
  int fd_ = -1;
};

// A resumed run's world: the scene kept in DIR, restored from DIR's checkpoint; SceneError
// messages name the file.
std::unique_ptr<World> resumeWorld(const std::string& dir, WorldDef def) {
  const fs::path scene = fs::path(dir) / kResumeSceneFile, state = fs::path(dir) / kCheckpointFile;
  if (!fs::exists(state))
    throw SceneError(state.string() + ": missing: '" + dir +
                     "' is not the directory of a fibra run, or its scene has "
                     "output.checkpoint false");
  if (!fs::exists(scene))
    throw SceneError(scene.string() + ": missing: the checkpoint is there but not the scene (a "
                     "run written by a program embedding fibra): copy its scene file there "
                     "under that name");
  std::unique_ptr<World> world = buildWorld(scene.string(), std::move(def));
  std::ifstream in(state, std::ios::binary);
  try {
    world->restoreCheckpoint(in);
  } catch (const CheckpointError& e) {
    throw SceneError(state.string() + ": " + e.what());
  }
  return world;
}

int run(const Options& o) {
  std::unique_ptr<Trace> trace = o.trace.empty() ? nullptr : std::make_unique<Trace>();
  std::unique_ptr<World> world;
  try {
    world = o.resume ? resumeWorld(o.out, worldDef(o, trace.get()))
                     : buildWorld(o.scene, worldDef(o, trace.get()));
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  }
  if (o.verbosity != Verbosity::Quiet) {
    std::fputs(terminal::describeProblem(*world, o.resume ? o.out : o.scene, o.threads).c_str(),
               stderr);
    const int steps = int(world->scene().steps.size());
    if (o.resume)
      std::fprintf(stderr, "fibra: resuming %s at t = %g (step %d of %d)\n", o.out.c_str(),
                   world->time(), std::min(world->currentStep() + 1, steps), steps);
  } else {
    std::fputs(terminal::startWarnings(*world).c_str(), stderr);
  }
  // From here on a signal stops the run cleanly: one that arrives while the outputs are being
  // created cancels the first increment, so the initial state is written and no .part is left.
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::optional<Outputs> outputs;
  DirectoryLock lock;
  try {
    lock.take(o.out);
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kFailed;
  }
  try {
    if (o.resume) {
      outputs.emplace(o.out, *world, ResumeOutputs{}, o.vtuEncoding);
    } else {
      clearOutputs(o.out);  // a previous run's frames must not mix with this run's
      outputs.emplace(o.out, *world, o.vtuEncoding);
      outputs->keepScene(readWholeFile(o.scene));
    }
  } catch (const std::runtime_error& e) {  // a damaged run directory is bad input
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return o.resume ? kBadInput : kFailed;
  }

  const int status = solve(*world, *outputs, o.verbosity);
  if (trace) writeTrace(*trace, o.trace);
  return status;
}

// fibra describe|check SCENE.json: the scene built exactly as `run` builds it, then its stages
// (describe) or its size and parameters (check) on stdout.
int inspect(int argc, char** argv, bool describe) {
  const std::string command = argv[1];
  for (int i = 2; i < argc; ++i)
    if (std::string(argv[i]).starts_with("-"))
      throw UsageError(command + ": unknown option '" + argv[i] + "' (it takes a scene file only)");
  if (argc != 3) throw UsageError(command + ": expected exactly one scene file");
  try {
    const std::unique_ptr<World> world = buildWorld(argv[2], WorldDef{});
    const std::string text =
        describe ? world->describe() : terminal::describeProblem(*world, argv[2], -1);
    std::fputs(text.c_str(), stdout);
    if (!describe) std::printf("fibra: %s: the scene is valid\n", argv[2]);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  }
  return kSolved;
}

// fibra expand SCENE.json [--out FILE]: the plain scene, checked, on stdout or in FILE
// (written as FILE.part, then renamed).
int expand(int argc, char** argv) {
  const bool toFile = argc == 5 && std::string(argv[3]) == "--out";
  if (!(argc == 3 || toFile) || std::string(argv[2]).starts_with("-"))
    throw UsageError("expand: expected a scene file and optionally --out FILE");
  std::string text;
  try {
    text = expandScene(argv[2]);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kBadInput;
  }
  if (!toFile) return std::fputs(text.c_str(), stdout) >= 0 ? kSolved : kFailed;
  const std::string out = argv[4], part = out + ".part";
  if (!(std::ofstream(part, std::ios::binary) << text)) {
    std::fprintf(stderr, "fibra: error: cannot write '%s'\n", part.c_str());
    fs::remove(part);
    return kFailed;
  }
  fs::rename(part, out);
  return kSolved;
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kUsage, stdout);
    return kSolved;
  }
  if (command == "--version" || command == "version") {
    std::printf("fibra %s\n", FIBRA_VERSION_STRING);
    return kSolved;
  }
  try {
    if (command == "describe" || command == "check")
      return inspect(argc, argv, command == "describe");
    if (command == "expand") return expand(argc, argv);
    if (command == "plot" || command == "section") try {
        return command == "plot" ? pictures::plot(argc, argv) : pictures::section(argc, argv);
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    if (command == "study") try {
        return study::study(argc, argv);
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    if (command != "run")
      throw UsageError(command.empty() ? "missing command" : "unknown command '" + command + "'");
    Options options;
    try {
      options = parseRun(argc, argv);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    return run(options);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "fibra: %s\nusage: %s\n(fibra --help for more)\n", e.what(),
                 usageLine(command).c_str());
    return kBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "fibra: error: out of memory: an allocation failed (the machine's memory, "
                         "or a limit set on this process such as ulimit -v); a run stopped by it "
                         "goes on from its last converged increment with fibra run --resume DIR\n");
    return kFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fibra: error: %s\n", e.what());
    return kFailed;
  }
}
