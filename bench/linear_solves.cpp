// Linear solves at paper scale: fibra's own tangents of the paper's twisted yarn (61 and 250
// fibres) and woven fabric (480 fibres), built on the fly (bench/paper_scenes.h), solved by each
// strategy of systems/linear_solver.h on the same matrices; then whole increments of the
// squeezed yarn with each strategy (Newton iterations, refactorisations, time per iteration).
//
//   build/bench_linear_solves --case yarn61|yarn250|fabric480|bundle7|bundle19|bundle37
//       [--friction on|off]
//       [--strategy cholmod,direct,umfpack,krylov] [--threads 1,2] [--repeats 3]
//       (a strategy may end in -amd or -metis for that ordering; also cholmod-metis and
//       umfpack-best, UMFPACK trying several orderings and keeping the best; mumps-blr<eps>,
//       e.g. mumps-blr1e-6, the mumps strategy with a block low-rank factor of accuracy eps
//       inside GMRES (mumps-blr alone: 1e-6); mumps-full, mumps given a symmetric K in full,
//       LU instead of LDL^T; any name ending in -nz, e.g. cholmod-nz: that one on K without
//       its explicit zeros, analysis included; any ending in -stored: that one with
//       solver.pattern_slack 0, on K's stored pattern with its zeros)
//       [--newton INCREMENTS] [--newton-strategy krylov,umfpack] [--refactor-above 40]
//       [--coarse-segments 8] [--coarse-rotations auto|on|off] (schwarz)
//       [--krylov-restart 40] [--krylov-max 200] (GMRES: basis per cycle, iterations per solve) [--pattern-slack 1.5] (solver.pattern_slack)
//       [--forcing-max 0,1e-2] (inexact Newton, each value
//       with each Newton strategy; 0: every solve to the Krylov tolerance)
//       [--scene FILE [--checkpoint FILE [--checkpoint-scene FILE]]] (a scene file, from a
//       stopped run's state, instead of a built-in case; the run's own scene when its steps
//       differ, bench/tangent_cases.h restoreFrom)
//       [--max-iterations 30] [--cutbacks 8] [--warm 3] [--warm-strategy umfpack] [--csv FILE]
//
// Matrices: the tangent Newton assembled after --warm iterations of the first increment (see
// warmWorld), b random (seeded). Per
// strategy, a fresh solver each repeat (medians): analyse, numeric factorisation, one solve of
// K x = -r (with Krylov: its iterations), the residual |K x - b| / |b| checked here with the
// full K, and the peak resident memory of that repeat (VmHWM after a reset of the peak).
// "cholmod" is the reference of the goal: a fresh CHOLMOD supernodal factorisation of
// the symmetric part (K + K^T)/2 and one solve with it (of the symmetric part; not of K).
// Newton (--newton N): the first N increments of the scene with each strategy, per increment
// the Newton iterations, wall time, and the solver's counts.
#include "bench/tangent_cases.h"
#include "core/allocator.h"

#include <Eigen/UmfPackSupport>

#include <cstring>

using namespace fibra;
using namespace fibra::bench;

namespace {

using Row = SolveRow;  // one strategy's solve (bench/tangent_cases.h)

// UMFPACK's LU of the full K with UMFPACK_ORDERING_BEST (several orderings tried, the best
// kept), which systems/linear_solver.h does not offer: "umfpack-best".
Row umfpackBest(const LinearSystem& ls, const Eigen::VectorXd& b) {
  Row r;
  const SparseMatrix K = ls.symmetric ? SparseMatrix(ls.K.selfadjointView<Eigen::Upper>()) : ls.K;
  Eigen::UmfPackLU<SparseMatrix> lu;
  lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_BEST;
  r.analyse = seconds([&] { lu.analyzePattern(K); });
  r.factorise = seconds([&] { lu.factorize(K); });
  if (lu.info() != Eigen::Success) r.shifted = -1;
  Eigen::VectorXd x;
  r.solve = seconds([&] { x = lu.solve(b); });
  r.residual = relativeResidual(ls, x, b);
  return r;
}

struct Options : TangentCase {
  std::vector<std::string> strategies{"cholmod", "umfpack", "krylov"};
  std::vector<int> threads{1, 2};
  int repeats = 3;
  int newton = 0;
  int refactorAbove = KrylovSettings{}.refactorAbove;
  int coarseSegments = KrylovSettings{}.coarseSegments;
  std::string coarseRotations = "auto";
  int krylovRestart = KrylovSettings{}.restart, krylovMax = KrylovSettings{}.maxIterations;
  double patternSlack = KrylovSettings{}.patternSlack;
  int maxIterations = 30;  // Newton iterations per attempt
  int cutbacks = 8;        // per increment
  std::vector<std::string> newtonStrategies{"krylov", "umfpack"};
  std::vector<double> forcingMax{0};  // KrylovSettings::forcingMax per Newton run
  std::string csv = "linear_solves.csv";
};

void matrices(const Options& o, std::FILE* csv) {
  std::printf("%-8s %3s %-16s %8s %10s %9s %9s %8s %6s %9s %8s %5s\n", "case", "thr", "strategy",
              "dofs", "nonzeros", "assemble", "analyse", "factor", "solve", "krylov_it",
              "residual", "mem GiB");
  double assemble = 0;  // s per iteration, on the most threads asked
  auto w = warmWorld(o, *std::max_element(o.threads.begin(), o.threads.end()), assemble);
  const LinearSystem ls = w->system;  // the tangent met on the way (warmWorld)
  // b: a residual-like right-hand side that does not vanish at convergence (seeded)
  Eigen::VectorXd b = Eigen::VectorXd::Random(ls.freeCount);
  for (int threads : o.threads) {
    bench::setBlasThreads(threads);
    for (const std::string& s : o.strategies) {
      std::vector<Row> rows;
      for (int k = 0; k < o.repeats; ++k) {
        resetPeak();
        rows.push_back(s == "umfpack-best" ? umfpackBest(ls, b) : strategyRun(s, ls, b, threads));
        rows.back().memory = peakGiB();
      }
      auto med = [&](double Row::*f) {
        std::vector<double> v;
        for (const Row& r : rows) v.push_back(r.*f);
        return medianOf(v);
      };
      const Row& r0 = rows.front();
      std::printf("%-8s %3d %-16s %8d %10ld %9.3f %9.3f %8.3f %6.3f %9d %8.1e %5.2f%s\n",
                  o.name.c_str(), threads, s.c_str(), int(ls.freeCount), long(ls.K.nonZeros()),
                  assemble, med(&Row::analyse), med(&Row::factorise), med(&Row::solve),
                  r0.iterations, med(&Row::residual), med(&Row::memory),
                  r0.shifted < 0 ? "  (not positive definite)" : r0.shifted > 0 ? "  (shifted/LDLT)" : "");
      if (csv)
        std::fprintf(csv, "%s,%s,%d,%s,%d,%ld,%.4f,%.4f,%.4f,%.4f,%d,%.3e,%.3f\n", o.name.c_str(),
                     o.friction ? "on" : "off", threads, s.c_str(), int(ls.freeCount),
                     long(ls.K.nonZeros()), assemble, med(&Row::analyse), med(&Row::factorise),
                     med(&Row::solve), r0.iterations, med(&Row::residual), med(&Row::memory));
    }
  }
}

// The first o.newton increments of the scene with each strategy.
void newton(const Options& o) {
  std::printf("Newton: %d increment(s), %s\n", o.newton, o.friction ? "friction 0.1" : "frictionless");
  Eigen::VectorXd firstQ;  // the final state of the first strategy run, to compare the others with
  for (int threads : o.threads)
    for (const std::string& name : o.newtonStrategies)
      for (double forcing : o.forcingMax) {
      bench::setBlasThreads(threads);
      resetPeak();
      WorldState w;
      w.scene = sceneOf(o, 5);
      w.scene.solver.krylov.refactorAbove = o.refactorAbove;
      w.scene.solver.krylov.coarseSegments = o.coarseSegments;
      w.scene.solver.krylov.coarseRotations = o.coarseRotations == "on"    ? CoarseRotations::On
                                              : o.coarseRotations == "off" ? CoarseRotations::Off
                                                                           : CoarseRotations::Auto;
      w.scene.solver.krylov.patternSlack = o.patternSlack;
      w.scene.solver.krylov.restart = o.krylovRestart;
      w.scene.solver.krylov.maxIterations = o.krylovMax;
      w.scene.solver.krylov.forcingMax = forcing;
      std::printf("  %s, forcing term <= %g\n", name.c_str(), forcing);
      for (StepDef& st : w.scene.steps) st.maxIterations = o.maxIterations, st.maxCutbacks = o.cutbacks;
      w.def.threads = threads;
      LinearStrategy s;
      if (!parseStrategy(name, s)) {
        std::fprintf(stderr, "--newton-strategy %s: not a Newton strategy (auto, direct, umfpack, "
                     "krylov, krylov-lu, mumps, schwarz)\n", name.c_str());
        std::exit(2);
      }
      w.def.linearStrategy = s;
      auto last = std::chrono::steady_clock::now();
      w.def.progress = [&](const Progress& p) {  // one line per Newton iteration
        const LinearSolveStats& st = w.solver.stats();
        const SchwarzTimes& sz = st.schwarz;  // so far in this increment
        std::printf("    t %.3f it %2d residual %.2e  %.2f s  (factorisations %d, krylov it %d, shift %.0e, "
                    "resident %.2f GiB; Schwarz so far: build %.2f, K v %.2f, blocks %.2f, coarse solves %.2f, "
                    "K y_c %.2f s)\n", p.time, p.iteration, p.residual, bench::seconds([] {}) +
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - last).count(),
                    st.factorisations, st.krylovIterations, st.shift, statusGiB("VmRSS:"),
                    sz.local + sz.coarse, sz.operatorProduct, sz.blockSolve, sz.coarseSolve, sz.product);
        last = std::chrono::steady_clock::now();
      };
      buildWorld(w);
      if (!o.checkpoint.empty()) restoreFrom(w, o);
      int iterations = 0, krylovIterations = 0, fallbacks = 0;
      double wall = 0, assemble = 0, factorise = 0, solve = 0;
      SchwarzTimes schwarz;  // LinearSolveStats::schwarz, summed over the increments
      for (int inc = 1; inc <= o.newton; ++inc) {
        StepReport rep;
        const double t = bench::seconds([&] { rep = advance(w); });
        const LinearSolveStats& st = w.solver.stats();
        std::printf("  thr %d %-8s incr %d: %-9s %3d it (%d cut) %8.2f s  asm %.2f fac %.2f sol %.2f | "
                    "factorisations %d refactor %d reuses %d krylov it %d (max %d) fail %d fallbacks %d shift %.0e "
                    "flops/nnz %.3g schwarz %d analyses %d patterns %d (%ld entries)\n",
                    threads, name.c_str(), inc, rep.status == StepStatus::Converged ? "converged" : "FAILED",
                    rep.totalIterations, rep.cutbacks, t, rep.timings.assemble, rep.timings.factorise,
                    rep.timings.solve, st.factorisations, st.refactorisations, st.reuses,
                    st.krylovIterations, st.maxKrylovIterations, st.krylovFailures, st.fallbacks, st.shift,
                    st.flopsPerEntry, st.schwarzChoices, st.analyses, st.patterns, st.patternEntries);
        iterations += rep.totalIterations;
        krylovIterations += st.krylovIterations, fallbacks += st.fallbacks;
        schwarz += st.schwarz;
        wall += t, assemble += rep.timings.assemble, factorise += rep.timings.factorise, solve += rep.timings.solve;
        if (rep.status != StepStatus::Converged) break;
      }
      std::printf("  thr %d %-8s total %d it, %.2f s: per iteration %.3f s (assemble %.3f, factorise %.3f, "
                  "solve %.3f), krylov it %d, fallbacks %d, peak %.2f GiB\n", threads, name.c_str(), iterations,
                  wall, wall / iterations, assemble / iterations, factorise / iterations, solve / iterations,
                  krylovIterations, fallbacks, peakGiB());
      if (schwarz.local + schwarz.coarse > 0)
        std::printf("  thr %d %-8s Schwarz per iteration: build blocks %.3f coarse %.3f (Phi and A_c %.3f, analysis %.3f); in GMRES coarse "
                    "solves %.3f, K y_c %.3f, block solves %.3f, K v %.3f s; rotations off in %d of %d builds\n", threads, name.c_str(),
                    schwarz.local / iterations, schwarz.coarse / iterations,
                    schwarz.coarseMatrix / iterations, schwarz.coarseAnalyse / iterations,
                    schwarz.coarseSolve / iterations, schwarz.product / iterations,
                    schwarz.blockSolve / iterations, schwarz.operatorProduct / iterations,
                    schwarz.withoutRotations, schwarz.builds);
      if (firstQ.size() == 0) firstQ = w.fibres.q;
      else if (firstQ.size() == w.fibres.q.size())
        std::printf("  max |q - q of the first strategy| = %.2e\n",
                    (w.fibres.q - firstQ).lpNorm<Eigen::Infinity>());
    }
}

}  // namespace

int main(int argc, char** argv) {
  fixAllocatorThreshold();
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (parseCaseOption(o, k, v)) continue;
    if (k == "--strategy") o.strategies = split(v);
    else if (k == "--threads") { o.threads.clear(); for (auto& t : split(v)) o.threads.push_back(std::stoi(t)); }
    else if (k == "--repeats") o.repeats = std::stoi(v);
    else if (k == "--newton") o.newton = std::stoi(v);
    else if (k == "--newton-strategy") o.newtonStrategies = split(v);
    else if (k == "--csv") o.csv = v;
    else if (k == "--cutbacks") o.cutbacks = std::stoi(v);
    else if (k == "--refactor-above") o.refactorAbove = std::stoi(v);
    else if (k == "--coarse-segments") o.coarseSegments = std::stoi(v);
    else if (k == "--coarse-rotations") o.coarseRotations = v;
    else if (k == "--krylov-restart") o.krylovRestart = std::stoi(v);
    else if (k == "--krylov-max") o.krylovMax = std::stoi(v);
    else if (k == "--pattern-slack") o.patternSlack = std::stod(v);
    else if (k == "--forcing-max") { o.forcingMax.clear(); for (auto& f : split(v)) o.forcingMax.push_back(std::stod(f)); }
    else if (k == "--max-iterations") o.maxIterations = std::stoi(v);
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::printf("case %s, friction %s\n", o.name.c_str(), o.friction ? "on (mu 0.1)" : "off");
  std::FILE* csv = o.strategies.empty() ? nullptr : bench::openCsv(o.csv,
      "case,friction,threads,strategy,dofs,nonzeros,assemble_s,analyse_s,factorise_s,solve_s,"
      "krylov_iterations,residual,peak_gib");
  if (!o.strategies.empty() && o.strategies[0] != "none") matrices(o, csv);
  if (csv) std::fclose(csv);
  if (o.newton > 0) newton(o);
  return 0;
}
