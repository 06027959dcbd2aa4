// fibra's own tangents for the linear-solve benches (bench/linear_solves.cpp,
// bench/petsc_solves.cpp): the scene of a case, the world warmed up to the tangent Newton meets
// on the way, the residual check with the full K, peak memory, and the two references every
// table carries (a fresh CHOLMOD factorisation of the symmetric part; any strategy of
// systems/linear_solver.h, e.g. "umfpack", fibra's default from 7 000 equations).
#pragma once

#include "bench/bench_util.h"
#include "bench/contact_scenes.h"
#include "bench/paper_scenes.h"
#include "engine/world_state.h"
#include "io/scene_loader.h"

#include <Eigen/CholmodSupport>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>

namespace fibra::bench {

// Which tangent: the scene, friction, and how far into its first increment.
struct TangentCase {
  std::string name = "yarn61";  // yarn61|yarn250|fabric480|bundle7|bundle19|bundle37
  bool friction = true;         // mu 0.1, or frictionless
  int warm = 3;                 // Newton iterations before the matrices are taken
  std::string warmStrategy = "umfpack";
  bool grip = false;            // yarns: the held ends also hold the director g1 (no free spin)
  std::string scene;            // a scene file instead of a built-in case ("--scene FILE")
  std::string checkpoint;       // its run's resume_state.bin: the tangents from that state on
  std::string checkpointScene;  // the scene that wrote it, when its steps end or divide otherwise
};

inline std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

// Reads a case option (--case, --friction on|off, --warm, --warm-strategy) into c; false for
// any other option.
inline bool parseCaseOption(TangentCase& c, const std::string& k, const std::string& v) {
  if (k == "--case") c.name = v;
  else if (k == "--friction") c.friction = v == "on";
  else if (k == "--warm") c.warm = std::stoi(v);
  else if (k == "--warm-strategy") c.warmStrategy = v;
  else if (k == "--grip") c.grip = v == "on";
  else if (k == "--scene") c.scene = c.name = v;
  else if (k == "--checkpoint") c.checkpoint = v;
  else if (k == "--checkpoint-scene") c.checkpointScene = v;
  else return false;
  return true;
}

// Restores w (built from the case's scene) from c.checkpoint. With c.checkpointScene, the
// checkpoint was written by a run of that scene, which may differ from w's only in its steps
// (e.g. a copy of a sample whose last step stops half-way, with half its increments: the same
// increments up to there): its steps stand in for w's while the state is read, then w's own
// steps go on from its time. Exits with the error when the checkpoint does not fit.
inline void restoreFrom(WorldState& w, const TangentCase& c) {
  std::ifstream in(c.checkpoint, std::ios::binary);
  std::vector<StepDef> steps = w.scene.steps;
  if (!c.checkpointScene.empty()) w.scene.steps = loadScene(c.checkpointScene).steps;
  try {
    restoreCheckpoint(w, in);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "--checkpoint %s: %s\n", c.checkpoint.c_str(), e.what());
    std::exit(2);
  }
  w.scene.steps = std::move(steps);
  if (c.checkpointScene.empty()) return;
  // w's step and increment at its time (a whole number of that step's increments)
  for (int k = 0; k < int(w.scene.steps.size()); ++k) {
    const double start = k == 0 ? 0.0 : w.scene.steps[size_t(k) - 1].endTime;
    const StepDef& st = w.scene.steps[size_t(k)];
    if (w.time >= st.endTime - 1e-12) continue;
    const double n = (w.time - start) / (st.endTime - start) * st.increments;
    if (std::abs(n - std::round(n)) > 1e-6) {
      std::fprintf(stderr, "--checkpoint-scene: t = %g is not an increment of step %d\n", w.time, k + 1);
      std::exit(2);
    }
    w.step = k, w.increment = int(std::round(n));
    return;
  }
  w.step = int(w.scene.steps.size());
}

inline SceneDef sceneOf(const TangentCase& c, int increments) {
  if (!c.scene.empty()) return loadScene(c.scene);
  const double mu = c.friction ? 0.1 : 0;
  auto grip = [&](SceneDef s) {
    if (c.grip)
      for (BcDef& b : s.bcs) b.dofs[G1X] = b.dofs[G1Y] = b.dofs[G1Z] = true;
    return s;
  };
  if (c.name == "yarn61") return grip(scenes::yarnScene(61, mu, 0.002, increments));
  if (c.name == "yarn250") return grip(scenes::yarnScene(250, mu, 0.002, increments));
  if (c.name == "fabric480") return scenes::fabricScene(mu, increments);
  // smaller sizes for the rule of `auto`: squeezed bundles (bench/contact_scenes.h)
  if (c.name == "bundle7") return scenes::bundle(1, 10, 0.01, 5e-4, mu);
  if (c.name == "bundle19") return scenes::bundle(2, 20, 0.01, 5e-4, mu);
  if (c.name == "bundle37") return scenes::bundle(3, 40, 0.01, 5e-4, mu);
  std::fprintf(stderr, "unknown case %s\n", c.name.c_str());
  std::exit(2);
}

// A field of /proc/self/status in kB ("VmHWM:", "VmRSS:"), as GiB (Linux).
inline double statusGiB(const char* field) {
  std::ifstream in("/proc/self/status");
  const size_t n = std::strlen(field);
  for (std::string line; std::getline(in, line);)
    if (line.compare(0, n, field) == 0) return std::stod(line.substr(n)) / (1024.0 * 1024.0);
  return NAN;
}
// Peak resident memory since the last reset, and resident memory now, GiB.
inline void resetPeak() { std::ofstream("/proc/self/clear_refs") << "5"; }
inline double peakGiB() { return statusGiB("VmHWM:"); }
inline double residentGiB() { return statusGiB("VmRSS:"); }

// |K x - b| / |b| with the full K (the stored upper triangle when symmetric).
inline double relativeResidual(const LinearSystem& ls, const Eigen::VectorXd& x,
                               const Eigen::VectorXd& b) {
  Eigen::VectorXd Kx = ls.symmetric ? Eigen::VectorXd(ls.K.selfadjointView<Eigen::Upper>() * x)
                                    : Eigen::VectorXd(ls.K * x);
  return (Kx - b).norm() / b.norm();
}

inline double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One solve of K x = b by one strategy: seconds, Krylov iterations, residual, peak GiB.
struct SolveRow {
  double analyse = 0, factorise = 0, solve = 0, residual = 0, memory = 0;
  int iterations = 0, shifted = 0;  // shifted: < 0 not positive definite, > 0 shifted/LDL^T
};

// The reference: a fresh CHOLMOD supernodal LL^T of the symmetric part, one solve;
// with `metis`, ordered by METIS alone ("cholmod-metis"; CHOLMOD's default tries AMD, and
// METIS as well when AMD fills heavily).
inline SolveRow cholmodReference(const LinearSystem& ls, const Eigen::VectorXd& b,
                                 bool metis = false) {
  SolveRow r;
  SparseMatrix S;
  if (ls.symmetric) S = ls.K;
  else S = (0.5 * (ls.K + SparseMatrix(ls.K.transpose()))).triangularView<Eigen::Upper>();
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  llt.cholmod().print = 0;
  if (metis) {
    llt.cholmod().nmethods = 1;
    llt.cholmod().method[0].ordering = CHOLMOD_METIS;
  }
  r.analyse = seconds([&] { llt.analyzePattern(S); });
  r.factorise = seconds([&] { llt.factorize(S); });
  if (llt.info() != Eigen::Success) r.shifted = -1;  // not positive definite
  Eigen::VectorXd x;
  r.solve = seconds([&] { x = llt.solve(b); });
  r.residual = relativeResidual(ls, x, b);
  return r;
}

// "mumps-blr<eps>" (e.g. "mumps-blr1e-6"; "mumps-blr" alone: 1e-6): the mumps strategy with
// solver.blr_tolerance eps; "mumps-full": the mumps strategy given a symmetric K in full (LU,
// MUMPS sym = 0, instead of its LDL^T). Writes the base strategy's name to `base`.
inline void mumpsVariant(std::string& base, KrylovSettings& k, bool& full) {
  if (base == "mumps-full") base = "mumps", full = true;
  if (base.rfind("mumps-blr", 0) != 0) return;
  const std::string eps = base.substr(9);
  k.blrTolerance = eps.empty() ? 1e-6 : std::stod(eps);
  base = "mumps";
}

// "cholmod" / "cholmod-metis" (the reference above) or a strategy of systems/linear_solver.h,
// fresh solver; any of them ending in "-nz" is given K without its explicit zeros (the
// candidate contact elements that carry no stiffness; the copy is not timed), any ending in
// "-stored" runs with solver.pattern_slack 0 (K's stored pattern, explicit zeros included, as
// the strategies saw it before systems/nonzero_pattern.h); a strategy's name may end in "-amd"
// or "-metis" to impose that ordering
// (solver.ordering; "umfpack-metis"); MUMPS's variants: mumpsVariant.
inline SolveRow strategyRun(const std::string& name, const LinearSystem& ls0,
                            const Eigen::VectorXd& b, int threads,
                            const KrylovSettings& settings = {}) {
  if (name.size() > 3 && name.ends_with("-nz")) {  // the same on K without its explicit zeros
    LinearSystem nz = ls0;
    nz.K.prune([](Index, Index, double v) { return v != 0; });
    ++nz.revision;
    std::printf("    %s: K without explicit zeros, %ld of %ld entries\n", name.c_str(),
                long(nz.K.nonZeros()), long(ls0.K.nonZeros()));
    return strategyRun(name.substr(0, name.size() - 3), nz, b, threads, settings);
  }
  if (name.size() > 7 && name.ends_with("-stored")) {  // K's stored pattern, zeros included
    KrylovSettings k;
    k.patternSlack = 0;
    return strategyRun(name.substr(0, name.size() - 7), ls0, b, threads, k);
  }
  if (name == "cholmod" || name == "cholmod-metis")
    return cholmodReference(ls0, b, name != "cholmod");
  std::string base = name;
  Ordering ordering = Ordering::Auto;
  for (const auto& [suffix, o] : {std::pair(std::string("-amd"), Ordering::Amd),
                                  std::pair(std::string("-metis"), Ordering::Metis)}) {
    if (name.size() > suffix.size() && name.ends_with(suffix)) {
      base = name.substr(0, name.size() - suffix.size());
      ordering = o;
    }
  }
  KrylovSettings krylov = settings;
  bool full = false;
  mumpsVariant(base, krylov, full);
  LinearStrategy s;
  if (!parseStrategy(base, s)) {
    std::fprintf(stderr, "unknown strategy %s\n", name.c_str());
    std::exit(2);
  }
  LinearSystem copy;
  if (full && ls0.symmetric) {
    copy.K = SparseMatrix(ls0.K.selfadjointView<Eigen::Upper>());
    copy.freeCount = ls0.freeCount, copy.symmetric = false, copy.revision = ls0.revision;
  }
  const LinearSystem& ls = full && ls0.symmetric ? copy : ls0;
  LinearSolver solver;
  solver.setStrategy(s);
  solver.setOrdering(ordering);
  solver.setKrylov(krylov);
  solver.setBlasThreads(threads);
  std::string msg;
  SolveRow r;
  if (!solver.factorise(ls, msg)) std::printf("    %s: %s\n", name.c_str(), msg.c_str());
  Eigen::VectorXd x;
  solver.solve(b, x);
  const LinearSolveStats& st = solver.stats();
  r.analyse = st.analyse + st.pattern;  // with the non-zero pattern's pass over K
  r.factorise = st.factorise;
  r.solve = st.solve;
  r.iterations = st.krylovIterations;
  r.shifted = st.fallbacks + st.shifted;
  r.residual = relativeResidual(ls, x, b);
  return r;
}

// A world whose linear system holds a tangent met on the way: after `warm` Newton iterations of
// the scene's first increment (solved by `warmStrategy`; the attempt then stops, and the tangent
// Newton assembled last stays in ls: contact detected, friction sliding), or, with warm = 0, the
// tangent at the start (contact detected, no slip yet: symmetric even with friction).
// `assemble`: seconds per assembly. `onIteration`, when set, sees the linear system after every
// warm-up Newton iteration (the tangents met on the way, for re-use experiments).
inline std::unique_ptr<WorldState> warmWorld(
    const TangentCase& c, int threads, double& assemble,
    const std::function<void(const LinearSystem&)>& onIteration = {}) {
  auto w = std::make_unique<WorldState>();
  w->scene = sceneOf(c, 5);
  w->def.threads = threads;
  LinearStrategy s;
  if (!parseStrategy(c.warmStrategy, s)) {
    std::fprintf(stderr, "--warm-strategy %s: not a Newton strategy (auto, direct, umfpack, "
                 "krylov, krylov-lu, mumps, schwarz; the bench's variants such as mumps-blr1e-8 "
                 "are strategies to measure, not to warm up with)\n", c.warmStrategy.c_str());
    std::exit(2);
  }
  w->def.linearStrategy = s;
  if (onIteration)
    w->def.progress = [&ws = *w, onIteration](const Progress&) { onIteration(ws.system); };
  for (StepDef& st : w->scene.steps) st.maxIterations = std::max(c.warm, 1), st.maxCutbacks = 0;
  buildWorld(*w);
  if (!c.checkpoint.empty()) {
    restoreFrom(*w, c);
    std::printf("checkpoint %s: t = %g, step %d, increment %d\n", c.checkpoint.c_str(), w->time,
                w->step + 1, w->increment);
  }
  const double t = seconds([&] {
    if (c.warm == 0) {
      runStage(*w, w->pipeline.detect, 0);
      assemble = median(3, [&] { runStage(*w, w->pipeline.assemble, 0, true); });
      return;
    }
    const StepReport r = advance(*w);
    assemble = r.timings.assemble / std::max(r.totalIterations, 1);
    std::printf("warm-up (%s, %d threads): %d Newton iterations, %d contact elements, ",
                c.warmStrategy.c_str(), threads, r.totalIterations, int(r.contact.elements));
  });
  std::printf("%.1f s; assembly %.3f s per iteration\n", t, assemble);
  return w;
}

}  // namespace fibra::bench
