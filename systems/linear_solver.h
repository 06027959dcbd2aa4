// Linear solver system: solves K dq = -r on the free DOFs, by one of several strategies.
//
// Reads  LinearSystem (K, revision, symmetric). Owns its factorisations; no shared state.
// Strategies (LinearStrategy; docs/RESULTS.md "Linear solves at paper scale" has the figures):
// - Direct: symmetric K by CHOLMOD supernodal LL^T (a tangent that is not positive definite
//   falls back to CHOLMOD's simplicial LDL^T for that call, counted in `fallbacks`);
//   non-symmetric K (friction) by sparse LU, UMFPACK or Eigen's SparseLU (LuSolver). Fresh
//   numeric factorisation every call; the symbolic analysis only when the pattern changes.
// - Umfpack: UMFPACK LU of the full K whatever its symmetry (no positive-definite requirement).
// - Krylov: the symmetric part S = (K + K^T)/2, shifted when it is not positive definite,
//   S_s = S + sigma diag(|S_ii|), is factorised by CHOLMOD supernodal LL^T and used as the
//   right preconditioner of GMRES (systems/krylov.h) on the true K, to a relative residual
//   |K x - b| <= tolerance |b|. The factor is re-used across calls to factorise (Newton
//   iterations, contact passes) and refactorised only when the pattern revision changes, when
//   the last solve needed more than `refactorAbove` Krylov iterations, or when GMRES with a
//   re-used factor does not converge within `refactorAbove` iterations (then at once, with the
//   K at hand, and the solve redone with up to `maxIterations`).
//   sigma starts at 0 (a tenth of the last shift that worked) and grows by 100x up to 1.
// - KrylovLu: the same, preconditioned by UMFPACK's LU of the full K (re-used likewise).
// - Mumps: MUMPS 5.5's LU of the full K (sequential, systems/mumps_solver.h), or its LDL^T
//   (symmetric indefinite) of a symmetric K; analysis when the pattern revision changes, numeric
//   factorisation every call. With KrylovSettings::blrTolerance eps > 0 the factor is block
//   low-rank at accuracy eps (approximate, cheaper) and the solve is GMRES on the true K,
//   right-preconditioned by it, to KrylovSettings::tolerance (iterations in krylovIterations;
//   refactorAbove does not apply: the factor is fresh every call). MUMPS errors (singular, out
//   of memory after one retry with more workspace) return false with MUMPS's code.
// - Schwarz: GMRES on the true K, right-preconditioned by the two-level fibre preconditioner of
//   systems/schwarz_preconditioner.h (banded LU per fibre, a coarse level of per-fibre segment
//   translations and rotations, KrylovSettings::coarseSegments and coarseRotations, the latter's
//   Auto choice made again after forgetPattern), built afresh at every call to
//   factorise: on the contact tangents neither a factor nor this preconditioner survives a
//   Newton iteration (docs/RESULTS.md "Fibre-block preconditioners"). Needs the fibres
//   (setFibres). A preconditioner that cannot be built (a singular block) or a GMRES that misses
//   the tolerance within maxIterations falls back to MUMPS's exact LU for that call (counted in
//   fallbacks; the failed GMRES in krylovFailures).
// - Inexact Newton (KrylovSettings::forcingMax > 0): the GMRES strategies (Krylov, KrylovLu,
//   BLR Mumps, Schwarz) stop a solve at the forcing term Newton passes to solve(b, x, forcing)
//   (systems/newton.h), clamped to [tolerance, forcingMax]; the exact ones ignore it. A
//   Schwarz solve that misses such a forcing term within maxIterations but comes within 10x
//   of it, and to kInexactMissBound, keeps its iterate instead of falling back to MUMPS
//   (keepsInexactMiss; counted in krylovFailures, not in fallbacks): |K x - b| < |b| still
//   makes it a descent direction of |r|^2.
// - Auto: Direct below kMumpsFromEquations equations, Mumps from there (measured rule:
//   docs/RESULTS.md "MUMPS inside fibra"; on the contact tangents measured neither Krylov
//   preconditioner pays); a tangent MUMPS fails on goes to Direct for that call (counted in
//   fallbacks). Auto's Mumps follows KrylovSettings::blrTolerance (0 by default: exact). From
//   kMumpsFromEquations, a pattern whose MUMPS analysis estimates kSchwarzFromFlopsPerEntry
//   factorisation flops per non-zero of K or more (packed yarns and bundles; not fabrics,
//   whose fill is light) goes to Schwarz instead (autoTakesSchwarz; counted in
//   schwarzChoices), decided at the first pattern after forgetPattern (each increment) and
//   kept until the next.
// Pattern: every strategy but Schwarz factorises (and multiplies by) K on the non-zero pattern
// of systems/nonzero_pattern.h, with KrylovSettings::patternSlack (0: K's stored pattern). Its
// revision, not K's, decides the analyses ("the pattern changes" above); Schwarz drops K's
// zeros itself.
// Ordering (setOrdering, components/solver_settings.h): auto orders UMFPACK's factorisations by
// METIS nested dissection from kMetisFromEquations equations and by AMD below, MUMPS's by METIS
// from kMumpsMetisFromEquations and by AMD below, and leaves CHOLMOD its default;
// amd or metis impose that one on all (measured: docs/RESULTS.md "Orderings", "MUMPS inside
// fibra").
// Time is spent in BLAS: link OpenBLAS (reference BLAS is ~17x slower here). OpenBLAS's thread
// count is a process-wide setting: with setBlasThreads(n), every factorisation and solve first
// sets it to n (the world passes its own thread count); 0 leaves it alone.
// Determinism: the same K, b and OpenBLAS thread count give bitwise the same x with every
// strategy (sequential factorisations; GMRES has no threads of its own). Across OpenBLAS thread
// counts the dense kernels of CHOLMOD, UMFPACK and MUMPS may sum in another order: equal to
// round-off, not guaranteed bitwise.
// Trace spans (setTrace): "factorise" (items: equations), "solve" (items: right-hand sides) and
// "krylov" (items: GMRES iterations), category "solver".
#pragma once

#include "components/fibres.h"
#include "components/linear_system.h"
#include "components/solver_settings.h"
#include "systems/schwarz_preconditioner.h"
#include "core/trace.h"

#include <memory>
#include <string>

namespace fibra {

struct LinearSolveStats {
  double analyse = 0, factorise = 0, solve = 0;  // seconds, accumulated (solve: with Krylov)
  int analyses = 0, factorisations = 0;
  int fallbacks = 0;           // LL^T -> LDL^T (Direct), or MUMPS -> Direct (Auto)
  int solves = 0;              // right-hand sides solved
  // Krylov strategy
  int krylovIterations = 0;    // GMRES iterations, summed over solves
  int maxKrylovIterations = 0; // most GMRES iterations of one solve
  int reuses = 0;              // calls to factorise that kept the factor
  int refactorisations = 0;    // factorisations forced by the Krylov count or a failure
  int shifted = 0;             // factorisations that needed sigma > 0
  int krylovFailures = 0;      // solves that missed the tolerance even with a fresh factor
  double shift = 0;            // sigma of the last factorisation
  // the last solve (0 for a direct one): its GMRES iterations (all tries), the relative
  // tolerance asked and the relative residual |K x - b| / |b| its last GMRES reached
  int lastKrylovIterations = 0;
  double lastTolerance = 0, lastReached = 0;
  // MUMPS analyses (Mumps, Schwarz's fallback, Auto)
  double flopsPerEntry = 0;    // the last analysis's estimated factorisation flops (RINFOG(1))
                               // per non-zero of K (dimensionless)
  int schwarzChoices = 0;      // Auto: calls to factorise that took Schwarz by the fill rule
  SchwarzTimes schwarz;        // Schwarz: its builds' and GMRES's parts, accumulated (s)
  // the non-zero pattern (systems/nonzero_pattern.h): the patterns it built, and the entries of
  // the one the last call to factorise saw (K's stored ones when it is off or for Schwarz)
  int patterns = 0;
  long patternEntries = 0;
  double pattern = 0;          // seconds in its passes over K, accumulated
};


// Auto's rule: MUMPS from this many equations, Direct below (measured, docs/RESULTS.md "MUMPS
// inside fibra", analyse + factorise + solve, 1 thread: MUMPS against UMFPACK, the rule's
// previous choice from 7 000, 2.09 against 2.12 s on the frictional 16.8k yarn tangent and
// 47.2 against 48.1 s on the frictional 68.8k one (a tie), 1.43 against 2.41 s and 28.4
// against 46.5 s on the frictionless ones (LDL^T); at 6.9k it beats Direct too (0.23 against
// 0.26 s with friction, 0.16 against 0.44 s frictionless), but smaller systems were not
// measured and Direct stays there).
inline constexpr Index kMumpsFromEquations = 7000;
// Auto's rule from kMumpsFromEquations: Schwarz instead of MUMPS when MUMPS's analysis estimates
// at least this many factorisation flops per non-zero of K on its non-zero pattern
// (dimensionless; measured, docs/RESULTS.md "The exact strategies on the non-zero pattern":
// 561 on bundle19 and 1 290-1 400 on bundle37, where Schwarz is 1.4x and 1.9x faster; light on
// the woven sample, where MUMPS is; 1 250-1 380 mid-crush on the 250-fibre yarn, where exact
// MUMPS beats exact GMRES but not inexact: the rule cannot tell these apart).
inline constexpr double kSchwarzFromFlopsPerEntry = 500;
// Auto's choice from kMumpsFromEquations: Schwarz (true) or MUMPS, for a K whose MUMPS analysis
// estimates flopsPerEntry factorisation flops per non-zero, haveFibres when the solver knows
// the fibres (setFibres).
bool autoTakesSchwarz(double flopsPerEntry, bool haveFibres);
// Inexact Newton: the largest relative residual a missed Schwarz solve may keep
// (dimensionless; keepsInexactMiss).
inline constexpr double kInexactMissBound = 0.1;
// A GMRES solve asked to reach `asked` (a forcing term; the strategy's own tolerance is
// `tolerance`) that stopped at `reached` without converging: kept when asked > tolerance and
// reached <= min(kInexactMissBound, 10 asked).
bool keepsInexactMiss(double asked, double tolerance, double reached);
// Auto ordering's rule: UMFPACK by METIS from this many equations (measured, docs/RESULTS.md
// "Orderings": on frictional yarn tangents METIS factorises 1.25x faster than AMD at 16.8k
// equations and 3.1x at 68.8k; at 6.9k AMD is 1.3x faster).
inline constexpr Index kMetisFromEquations = 12000;
// The Mumps strategy's auto ordering: METIS (computed by CHOLMOD, given to MUMPS) from this many
// equations, AMD below (measured: docs/RESULTS.md "MUMPS inside fibra").
inline constexpr Index kMumpsMetisFromEquations = 12000;

// The strategy's name as the scene file spells it ("auto", "direct", "umfpack", "krylov",
// "krylov-lu", "mumps", "schwarz").
const char* strategyName(LinearStrategy s);
// Parses a name of strategyName; false when it is none.
bool parseStrategy(const std::string& name, LinearStrategy& s);

class LinearSolver {
 public:
  LinearSolver();
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Prepares to solve with ls.K (factorises, or keeps a preconditioner); false (with a
  // message) if K is singular. Krylov, Mumps and Auto keep a pointer to ls: it must stay
  // alive, and solve() uses the values of ls.K at the time of the solve.
  bool factorise(const LinearSystem& ls, std::string& message);
  // x = K^-1 b (free DOFs, size freeCount); after a successful factorise.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // The same, where an iterative strategy may stop at |K x - b| <= eta |b|, the forcing term of
  // inexact Newton (dimensionless): with KrylovSettings::forcingMax > 0 the GMRES strategies
  // solve to clamp(forcing, tolerance, forcingMax); otherwise, and for the exact strategies,
  // as solve(b, x).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double forcing);

  const LinearSolveStats& stats() const;
  void resetStats();
  // The non-zero pattern starts afresh from K's non-zeros at the next factorise, and Auto's
  // choice between MUMPS and Schwarz is made again (the step driver calls it at each increment:
  // neither then reaches back past an increment, and a run resumed from a checkpoint factorises
  // on the same patterns with the same strategies as the run that wrote it, bitwise the same).
  void forgetPattern();
  void setLuSolver(LuSolver lu);  // Direct, non-symmetric K; default EigenSparseLu
  void setStrategy(LinearStrategy s);  // default Auto
  void setKrylov(const KrylovSettings& k);
  void setOrdering(Ordering o);      // default Auto; takes effect at the next analysis
  void setBlasThreads(int threads);  // > 0: OpenBLAS threads set before each factorisation
  void setTrace(Trace* trace);       // spans recorded when set
  // The fibres the Schwarz strategy follows (node ranges, current state); must stay alive.
  void setFibres(const FibreStore* fibres);
  LinearStrategy strategy() const;   // as set (Auto stays Auto)
  // The strategy used for a system of n equations (Auto resolved).
  LinearStrategy resolved(Index n) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fibra
