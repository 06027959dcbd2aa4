// Embedding fibra: a scene solved on a worker thread while the main thread draws a progress bar
// and may cancel the run (a timer stands in for a Cancel button), the outputs written through the
// library's writers (fibra/io/outputs.h).
//
//   fibra_embed SCENE.json OUTDIR [--cancel-after SECONDS]
//
// Prints one report line per converged increment and ends with "finished", "cancelled" (the last
// converged state written) or "failed"; exit status 0, 0 and 1.
#include <fibra/fibra.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

// What the worker shares with the main thread.
struct Shared {
  std::atomic<double> progress{0};  // fraction of the scene's pseudo-time solved, 0..1
  std::atomic<bool> cancel{false}, done{false};
  std::mutex mutex;
  std::vector<std::string> lines;  // report lines not yet printed
  fibra::StepStatus outcome = fibra::StepStatus::Finished;
  std::string error;
};

std::string reportLine(const fibra::StepReport& r) {
  char line[256];
  std::snprintf(line, sizeof line, "step %d increment %d: t = %g, %d iterations, residual %.2e",
                r.step + 1, r.increment, r.time, r.iterations, r.residual);
  return line;
}

// The worker: every increment of the scene, a report line and the outputs for each.
void solve(fibra::World& world, fibra::Outputs& outputs, Shared& shared) {
  const double end = world.scene().steps.back().endTime;
  try {
    while (!world.finished()) {
      const fibra::StepReport r = world.step();
      if (r.status != fibra::StepStatus::Converged) {
        shared.outcome = r.status;
        break;
      }
      outputs.increment(world, r);
      shared.progress = world.time() / end;
      std::lock_guard lock(shared.mutex);
      shared.lines.push_back(reportLine(r));
    }
    outputs.finish(world);  // the last converged state, whatever the outcome
  } catch (const std::exception& e) {
    shared.outcome = fibra::StepStatus::Failed;
    shared.error = e.what();
  }
  shared.done = true;
}

void drawBar(double fraction) {
  const int width = 30, filled = int(fraction * width + 0.5);
  std::fprintf(stderr, "\r[%s%s] %3.0f%%", std::string(filled, '#').c_str(),
               std::string(width - filled, '.').c_str(), 100 * fraction);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && !(argc == 5 && std::string(argv[3]) == "--cancel-after")) {
    std::fprintf(stderr, "usage: fibra_embed SCENE.json OUTDIR [--cancel-after SECONDS]\n");
    return 2;
  }
  const double cancelAfter = argc == 5 ? std::atof(argv[4]) : -1;
  std::printf("fibra %s (embedded)\n", FIBRA_VERSION_STRING);
  Shared shared;
  fibra::WorldDef def;
  def.threads = 2;
  def.cancel = [&shared] { return shared.cancel.load(); };
  try {
    fibra::World world(fibra::loadScene(argv[1]), def);
    fibra::Outputs outputs(argv[2], world);
    const Clock::time_point start = Clock::now();
    if (cancelAfter == 0) shared.cancel = true;  // pressed before the run starts
    std::thread worker(solve, std::ref(world), std::ref(outputs), std::ref(shared));
    while (!shared.done) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      if (cancelAfter >= 0 && elapsed >= cancelAfter) shared.cancel = true;  // "Cancel" pressed
      {
        std::lock_guard lock(shared.mutex);
        for (const std::string& line : shared.lines) std::printf("\r%s\n", line.c_str());
        shared.lines.clear();
      }
      std::fflush(stdout);
      drawBar(shared.progress);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    worker.join();
    for (const std::string& line : shared.lines) std::printf("%s\n", line.c_str());
    std::fprintf(stderr, "\n");
    // An Eigen vector made by the library and freed here: the ABI holds (docs/EMBEDDING.md).
    std::printf("residual of the last converged state on all DOFs, the held ones' reactions "
                "included: |r| = %.3g (N and N mm)\n",
                world.residual().norm());
    switch (shared.outcome) {
      case fibra::StepStatus::Finished:
        std::printf("finished: t = %g, %d frames in %s\n", world.time(), outputs.frames(), argv[2]);
        return 0;
      case fibra::StepStatus::Cancelled:
        std::printf("cancelled: t = %g, the last converged state written to %s\n", world.time(),
                    argv[2]);
        return 0;
      default:
        std::printf("failed: t = %g %s\n", world.time(), shared.error.c_str());
        return 1;
    }
  } catch (const std::exception& e) {  // fibra::SceneError: the scene's file, field and reason
    std::fprintf(stderr, "fibra_embed: %s\n", e.what());
    return 2;
  }
}
