// Time per Newton iteration split per system, for the paper's two-beam sliding test
// (samples/two_beams_sliding.json) and the 7-fibre bundle squeezed between two tools
// (bench/contact_scenes.h), with 1 and 2 threads (TBB and BLAS alike).
//
//   build/bench_iteration_systems [--repeats N] [--csv FILE]
//
// Each run solves the whole scene with a Trace; a system's time is the sum of its spans'
// exclusive wall time (a span minus the spans nested in it on the same thread), divided by the
// run's Newton iterations (all attempts). Factorisation and solve come from the step reports.
// Systems that run side by side on two threads overlap, so with 2 threads the rows may add up
// to more than the wall time per iteration. Medians over the repeats.
#include "core/allocator.h"
#include "bench/bench_util.h"
#include "bench/contact_scenes.h"
#include "io/scene_loader.h"
#include "engine/world.h"

#include <cstring>
#include <map>

using namespace fibra;

namespace {

using Clock = std::chrono::steady_clock;

// Exclusive seconds per span name.
std::map<std::string, double> exclusiveTimes(const Trace& trace) {
  std::map<int, std::vector<Trace::Event>> byThread;
  for (const Trace::Event& e : trace.events()) byThread[e.thread].push_back(e);
  std::map<std::string, double> out;
  for (auto& [thread, events] : byThread) {
    std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) {
      return a.begin < b.begin || (a.begin == b.begin && a.end > b.end);
    });
    std::vector<const Trace::Event*> open;
    for (const Trace::Event& e : events) {
      while (!open.empty() && open.back()->end <= e.begin) open.pop_back();
      const double d = std::chrono::duration<double>(e.end - e.begin).count();
      out[e.name] += d;
      if (!open.empty()) out[open.back()->name] -= d;
      open.push_back(&e);
    }
  }
  return out;
}

struct Sample {
  int iterations = 0;
  std::map<std::string, double> perIteration;  // ms per Newton iteration
};

Sample runOnce(const SceneDef& scene, int threads) {
  Trace trace;
  WorldDef def;
  def.threads = threads;
  def.trace = &trace;
  double wall = 0, factorise = 0, solve = 0;
  int iterations = 0;
  wall = bench::seconds([&] {
    World w(scene, def);
    while (!w.finished()) {
      const StepReport r = w.step();
      if (r.status != StepStatus::Converged) {
        std::printf("  failed: %s\n", r.message.c_str());
        break;
      }
      iterations += r.totalIterations;
      factorise += r.timings.factorise;
      solve += r.timings.solve;
    }
  });
  Sample s;
  s.iterations = iterations;
  for (const auto& [name, t] : exclusiveTimes(trace)) s.perIteration[name] = 1e3 * t / iterations;
  s.perIteration["(factorise)"] = 1e3 * factorise / iterations;
  s.perIteration["(solve)"] = 1e3 * solve / iterations;
  s.perIteration["(wall)"] = 1e3 * wall / iterations;
  return s;
}

// Median per name over the repeats.
Sample runMedian(const SceneDef& scene, int threads, int repeats) {
  std::map<std::string, std::vector<double>> all;
  Sample out;
  for (int i = 0; i < repeats; ++i) {
    const Sample s = runOnce(scene, threads);
    out.iterations = s.iterations;
    for (const auto& [name, t] : s.perIteration) all[name].push_back(t);
  }
  for (auto& [name, v] : all) {
    v.resize(repeats, 0.0);  // a span missing from a repeat counts as 0
    std::sort(v.begin(), v.end());
    out.perIteration[name] = v[v.size() / 2];
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  int repeats = 5;
  std::string csvPath;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--csv")) csvPath = argv[i + 1];
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::FILE* csv = csvPath.empty() ? nullptr
                                   : bench::openCsv(csvPath, "scene,threads,system,ms_per_iteration");
  const std::vector<std::pair<const char*, SceneDef>> cases{
      {"two beams", loadScene(FIBRA_SOURCE_DIR "/samples/two_beams_sliding.json")},
      {"bundle 7x10", scenes::bundle(1, 10, 0.01, 5e-4, 0.1)}};
  for (const auto& [name, scene] : cases) {
    std::map<int, Sample> byThreads;
    for (int threads : {1, 2}) {
      bench::setBlasThreads(threads);
      byThreads[threads] = runMedian(scene, threads, repeats);
    }
    std::printf("%s: %d Newton iterations; ms per iteration (median of %d)\n", name,
                byThreads[1].iterations, repeats);
    std::printf("  %-28s %10s %10s\n", "system", "1 thread", "2 threads");
    for (const auto& [system, t1] : byThreads[1].perIteration) {
      const double t2 = byThreads[2].perIteration[system];
      std::printf("  %-28s %10.4f %10.4f\n", system.c_str(), t1, t2);
      if (csv) {
        std::fprintf(csv, "%s,1,%s,%.6g\n", name, system.c_str(), t1);
        std::fprintf(csv, "%s,2,%s,%.6g\n", name, system.c_str(), t2);
      }
    }
  }
  if (csv) std::fclose(csv);
}
