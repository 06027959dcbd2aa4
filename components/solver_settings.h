// Linear solver settings: which strategy solves the Newton systems and the Krylov method's
// parameters. Plain data, set by the scene's `solver` section (engine/scene.h SolverDef) or by
// WorldDef, read by the linear solver system (systems/linear_solver.h, which documents them).
#pragma once

namespace fibra {

enum class LuSolver { Umfpack, EigenSparseLu };
enum class LinearStrategy { Auto, Direct, Umfpack, Krylov, KrylovLu, Mumps, Schwarz };
// Fill-reducing ordering of the sparse factorisations. Auto: UMFPACK by METIS nested dissection
// from kMetisFromEquations (systems/linear_solver.h) and by AMD/COLAMD below; CHOLMOD by its own
// default (AMD, and METIS as well when AMD's fill is heavy, keeping the better). Amd, Metis:
// that one ordering for both.
enum class Ordering { Auto, Amd, Metis };

// Whether the Schwarz coarse level carries the sections' rotations beside the translations
// (systems/schwarz_preconditioner.h): Auto keeps them unless A_c's factorisation would cost more
// than kRotationsUpToFlopsPerNonzero flops per non-zero of K (decided once per increment).
enum class CoarseRotations { Auto, On, Off };

struct KrylovSettings {
  double tolerance = 1e-8;   // |K x - b| / |b| asked of every solve (dimensionless; LU reaches
                             // 1e-9 on the yarn tangents, docs/RESULTS.md)
  int restart = 40;          // GMRES basis vectors per cycle
  int maxIterations = 200;   // GMRES iterations per solve
  int refactorAbove = 40;    // a solve needing more iterations: refactorise at the next call
  double blrTolerance = 0;   // Mumps strategy: 0 exact LU; > 0 a block low-rank factor at this
                             // relative accuracy, the preconditioner of GMRES (dimensionless)
  int coarseSegments = 8;    // Schwarz strategy: hat functions per fibre of its coarse level
                             // over this many pieces of the node index (>= 1)
  CoarseRotations coarseRotations = CoarseRotations::Auto;  // Schwarz: the coarse rotations
  double patternSlack = 1.5; // the exact factorisations and the Krylov strategies see K on a
                             // pattern that holds its non-zeros and at most this many times as
                             // many entries (systems/nonzero_pattern.h; dimensionless, >= 1);
                             // 0: on K's stored pattern, explicit zeros included
  double forcingMax = 0;     // > 0: inexact Newton for the GMRES strategies (schwarz, krylov,
                             // krylov-lu, BLR mumps): a solve stops at the forcing term Newton
                             // passes (Eisenstat-Walker, systems/newton.h), at most this and at
                             // least `tolerance` (dimensionless, < 1); 0: every solve to
                             // `tolerance`
};

}  // namespace fibra
