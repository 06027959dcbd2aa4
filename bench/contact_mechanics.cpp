// Contact mechanics benches: iterations and time per increment, split per system, for the
// paper's two-beam sliding test (samples/two_beams_sliding.json) and for hexagonal fibre bundles
// pressed between two plane tools; speed against error for p_max and for the loop limits
// n_A, n_B; the non-symmetric linear solver (UMFPACK, Eigen SparseLU, or the symmetrised
// tangent solved by CHOLMOD).
//
//   build/bench_contact_mechanics [--part all|solvers|pmax|loops|bundle] [--threads N]
//                                 [--rings 1..3] [--line-search on|off]
#include "core/allocator.h"
#include "bench/bench_util.h"
#include "bench/contact_scenes.h"
#include "io/scene_loader.h"
#include "engine/world.h"

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>

using namespace fibra;

namespace {

struct Run {
  int increments = 0, iterations = 0, minIt = 1 << 30, maxIt = 0, cutbacks = 0;
  double wall = 0, assemble = 0, factorise = 0, solve = 0;
  double maxPenetration = 0;
  bool ok = true;
  std::vector<double> series;  // per increment: the measured force of the case
};

// Runs the scene to its end; `measure` gives the force recorded per increment.
Run run(const SceneDef& scene, const WorldDef& def,
        const std::function<double(const World&)>& measure) {
  Run r;
  r.wall = bench::seconds([&] {
    World w(scene, def);
    while (!w.finished()) {
      const StepReport s = w.step();
      if (s.status != StepStatus::Converged) {
        r.ok = s.status == StepStatus::Finished;
        if (!r.ok) std::printf("  failed: %s\n", s.message.c_str());
        break;
      }
      ++r.increments;
      r.iterations += s.totalIterations;
      r.minIt = std::min(r.minIt, s.iterations);
      r.maxIt = std::max(r.maxIt, s.iterations);
      r.cutbacks += s.cutbacks;
      r.assemble += s.timings.assemble;
      r.factorise += s.timings.factorise;
      r.solve += s.timings.solve;
      r.maxPenetration = std::max(r.maxPenetration, s.contact.maxPenetration);
      r.series.push_back(measure(w));
    }
  });
  return r;
}

// --- the two-beam test ---

SceneDef twoBeams() { return loadScene(FIBRA_SOURCE_DIR "/samples/two_beams_sliding.json"); }

// Horizontal force of B's end holds, N.
double horizontal(const World& w) { return (w.reaction(2).force + w.reaction(3).force).y(); }

using scenes::bundle;

double topForce(const World& w) { return w.toolReaction(1).z(); }

void print(const char* name, const Run& r, double error) {
  std::printf("  %-34s %4d incr %5d it (%2d-%2d/incr) %2d cut  %7.3f s  asm %6.3f fac %6.3f "
              "sol %6.3f  pen %.2e  err %.2e%s\n",
              name, r.increments, r.iterations, r.minIt, r.maxIt, r.cutbacks, r.wall, r.assemble,
              r.factorise, r.solve, r.maxPenetration, error, r.ok ? "" : "  FAILED");
}

// Largest |a - b| over the increments, relative to the largest |b|; the mean in `mean`.
double seriesError(const std::vector<double>& a, const std::vector<double>& b,
                   double* mean = nullptr) {
  if (a.size() != b.size()) return NAN;
  double d = 0, sum = 0, peak = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    sum += std::abs(a[i] - b[i]);
    peak = std::max(peak, std::abs(b[i]));
  }
  if (mean) *mean = sum / a.size() / peak;
  return d / peak;
}

void solvers(const WorldDef& base) {
  std::printf("Non-symmetric linear solver (error: largest force difference from UMFPACK, of the "
              "peak)\n");
  struct Case {
    const char* name;
    SceneDef scene;
    std::function<double(const World&)> measure;
  };
  std::vector<Case> cases{{"two beams", twoBeams(), horizontal},
                          {"bundle 7x10", bundle(1, 10, 0.01, 5e-4, 0.1), topForce},
                          };
  for (Case& c : cases) {
    std::printf(" %s (%zu fibres)\n", c.name, c.scene.fibres.size());
    WorldDef def = base;
    def.luSolver = LuSolver::Umfpack;
    const Run umf = run(c.scene, def, c.measure);
    print("UMFPACK", umf, 0);
    def.luSolver = LuSolver::EigenSparseLu;
    const Run slu = run(c.scene, def, c.measure);
    print("Eigen SparseLU", slu, seriesError(slu.series, umf.series));
    SceneDef sym = c.scene;
    sym.contact.frictionTangent = FrictionTangent::Symmetrised;
    const Run chol = run(sym, base, c.measure);
    print("symmetrised tangent, CHOLMOD", chol, seriesError(chol.series, umf.series));
  }
}

void pMaxSweep(const WorldDef& def) {
  std::printf("p_max (bundle 7x10 squeezed 0.01 mm, mu 0.1; error: final top force against "
              "p_max = 1e-6 mm)\n");
  const std::vector<double> pMax{5e-3, 1e-3, 5e-4, 1e-4, 1e-5};
  const Run ref = run(bundle(1, 10, 0.01, 1e-6, 0.1), def, topForce);
  print("p_max 1e-6 (reference)", ref, 0);
  for (double p : pMax) {
    const Run r = run(bundle(1, 10, 0.01, p, 0.1), def, topForce);
    char name[64];
    std::snprintf(name, sizeof name, "p_max %.0e mm", p);
    print(name, r, std::abs(r.series.back() - ref.series.back()) / std::abs(ref.series.back()));
  }
}

void loopSweep(const WorldDef& def) {
  std::printf("Loop limits n_A x n_B (two beams; error: horizontal force against n_A = n_B = 8, "
              "of the peak)\n");
  SceneDef s = twoBeams();
  s.contact.maxDetectionLoops = s.contact.maxNormalLoops = 8;
  const Run ref = run(s, def, horizontal);
  print("n_A 8, n_B 8 (reference)", ref, 0);
  for (int a : {1, 2, 3, 5})
    for (int b : {1, 3}) {
      s.contact.maxDetectionLoops = a;
      s.contact.maxNormalLoops = b;
      const Run r = run(s, def, horizontal);
      char name[64];
      double mean = 0;
      const double worst = seriesError(r.series, ref.series, &mean);
      std::snprintf(name, sizeof name, "n_A %d, n_B %d (mean err %.1e)", a, b, mean);
      print(name, r, worst);
    }
}

int maxRings = 3;
bool lineSearch = false;

void bundles(const WorldDef& def) {
  std::printf("Bundles between two plane tools (squeezed 0.01 mm in 10 increments, mu 0.1)\n");
  for (auto [rings, elements] : {std::pair{1, 10}, std::pair{2, 20}, std::pair{3, 40}}) {
    if (rings > maxRings) break;
    SceneDef s = bundle(rings, elements, 0.01, 5e-4, 0.1);
    for (StepDef& st : s.steps) st.lineSearch = lineSearch;
    const Run r = run(s, def, topForce);
    char name[64];
    std::snprintf(name, sizeof name, "%zu fibres x %d elements", s.fibres.size(), elements);
    print(name, r, 0);
    std::printf("    top tool force %.4f N; per iteration %.2f ms\n", r.series.back(),
                1e3 * r.wall / r.iterations);
  }
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  std::string part = "all";
  WorldDef def;
  def.threads = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--part")) part = argv[i + 1];
    if (!std::strcmp(argv[i], "--threads")) def.threads = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--rings")) maxRings = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--line-search")) lineSearch = !std::strcmp(argv[i + 1], "on");
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  bench::setBlasThreads(def.threads);
  std::printf("threads %d\n", def.threads);
  const std::map<std::string, std::function<void(const WorldDef&)>> parts{
      {"solvers", solvers}, {"pmax", pMaxSweep}, {"loops", loopSweep}, {"bundle", bundles}};
  for (const auto& [name, f] : parts)
    if (part == "all" || part == name) f(def);
}
