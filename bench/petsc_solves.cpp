// PETSc's solvers on fibra's own tangents (issue 11), beside fibra's own strategies in the same
// run: the tangents of bench/linear_solves.cpp (bench/tangent_cases.h), copied to a sequential
// PETSc AIJ matrix (one MPI rank, PETSC_COMM_SELF, no launcher) and solved by
//   mumps        KSPPREONLY + PCLU by MUMPS (direct)
//   mumps-ldlt   KSPPREONLY + PCCHOLESKY by MUMPS: LDL^T, symmetric indefinite (symmetric K only)
//   petsc-lu     KSPPREONLY + PCLU by PETSc's own LU, nested dissection (direct)
//   ilu0, ilu1.. GMRES + ILU(k)
//   hypre        GMRES + hypre BoomerAMG
//   gamg         GMRES + GAMG (no block size, no near-null space: fibra's free DOFs are not whole
//                nodes once ends are held)
//   gmres-mumps  GMRES + MUMPS's LU: with PETSC_OPTIONS="-gmres_mumps_mat_mumps_icntl_35 1
//                -gmres_mumps_mat_mumps_cntl_7 1e-6", MUMPS's block low-rank (inexact) factor
// and by the references "umfpack" (fibra's default from 7 000 equations) and "cholmod" (the
// issue's reference: CHOLMOD of the symmetric part, which solves (K + K^T)/2, not K), or any
// other strategy of systems/linear_solver.h ("direct", "krylov-lu", ...; "none": no reference).
//
//   build/bench_petsc_solves --case bundle19|yarn61|yarn250|... [--friction on|off]
//       [--solver mumps,petsc-lu,ilu0,hypre,gamg] [--reference cholmod,umfpack]
//       [--threads 1] [--repeats 3] [--warm 3] [--warm-strategy umfpack]
//       [--max-krylov 200] [--restart 40] [--rtol 1e-8] [--reuse N] [--csv FILE]
//
// Built only when CMake finds PETSc (Debian petsc-dev: FIBRA_WITH_PETSC=1 bash scripts/setup.sh).
// Per solver, a fresh Mat and KSP each repeat (medians of --repeats), in seconds: convert (Eigen
// to AIJ), set-up (KSPSetUp: ordering, symbolic and numeric factorisation, or the AMG hierarchy;
// for fibra's strategies analyse + factorise), one solve of K x = b (b random, seeded); GMRES
// iterations, PETSc's converged reason, the residual |K x - b| / |b| computed here with fibra's K
// (not PETSc's norm); in GiB the peak resident memory of that repeat (VmHWM after a reset) and
// "above": that peak less the resident memory before the solve (after malloc_trim), what the
// solve itself needed. GMRES: right preconditioning, the true residual to --rtol, restart and
// iteration limit as fibra's Krylov (components/solver_settings.h).
// Threads: OpenBLAS (MUMPS, CHOLMOD, UMFPACK) and the warm-up's assembly at --threads; one rank.
// PETSC_OPTIONS reaches each solver by its prefix, the name with '_' for '-' (e.g.
// "-mumps_mat_mumps_icntl_7 5", "-petsc_lu_pc_factor_mat_ordering_type rcm").
// --reuse N: the tangents of the last N + 1 warm-up iterations; the first is factorised by MUMPS
// (gmres-mumps) and kept as the preconditioner of GMRES on the N that follow (what a re-used factor costs).
// Exit status 1 when a direct solve (mumps, mumps-ldlt, petsc-lu, umfpack, direct) leaves a
// residual above 1e-6: the correctness check of the copy to PETSc.
#include "core/allocator.h"
#include "bench/tangent_cases.h"

#include <malloc.h>
#include <petscksp.h>

using namespace fibra;
using namespace fibra::bench;

namespace {

struct Options : TangentCase {
  std::vector<std::string> solvers{"mumps", "petsc-lu", "ilu0", "hypre", "gamg"};
  std::vector<std::string> references{"cholmod", "umfpack"};
  int threads = 1;
  int repeats = 3;
  int maxKrylov = KrylovSettings{}.maxIterations;  // GMRES iterations per solve
  int restart = KrylovSettings{}.restart;          // GMRES basis vectors per cycle
  double rtol = KrylovSettings{}.tolerance;        // |K x - b| / |b|
  int reuse = 0;
  std::string csv = "petsc_solves.csv";
};

constexpr double kDirectTolerance = 1e-6;  // |K x - b| / |b| a direct solve must reach

#define CHECK(call) PetscCallAbort(PETSC_COMM_SELF, call)

bool isDirect(const std::string& s) {
  return s == "mumps" || s == "mumps-ldlt" || s == "petsc-lu" || s == "umfpack" || s == "direct";
}

// K on the free DOFs as a sequential AIJ matrix (CSR), full: the stored upper triangle is
// mirrored when K is symmetric.
Mat toPetsc(const LinearSystem& ls) {
  Eigen::SparseMatrix<double, Eigen::RowMajor, PetscInt> R;
  if (ls.symmetric) R = SparseMatrix(ls.K.selfadjointView<Eigen::Upper>());
  else R = ls.K;
  R.makeCompressed();
  const PetscInt n = PetscInt(ls.freeCount);
  Mat A;
  CHECK(MatCreate(PETSC_COMM_SELF, &A));
  CHECK(MatSetSizes(A, n, n, n, n));
  CHECK(MatSetType(A, MATSEQAIJ));
  CHECK(MatSeqAIJSetPreallocationCSR(A, R.outerIndexPtr(), R.innerIndexPtr(), R.valuePtr()));
  if (ls.symmetric) CHECK(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  return A;
}

// |K - K^T|_F / |K|_F: 0 for a symmetric tangent, whatever its storage.
double asymmetry(const LinearSystem& ls) {
  if (ls.symmetric) return 0;
  return (ls.K - SparseMatrix(ls.K.transpose())).norm() / ls.K.norm();
}

// The options prefix of a solver: "petsc-lu" -> "petsc_lu_".
std::string prefixOf(const std::string& name) {
  std::string p = name + "_";
  std::replace(p.begin(), p.end(), '-', '_');
  return p;
}

// ksp set to the named solver; false when the name is unknown.
bool configure(KSP ksp, const std::string& name, const Options& o) {
  PC pc;
  CHECK(KSPGetPC(ksp, &pc));
  if (name == "mumps" || name == "mumps-ldlt" || name == "petsc-lu") {
    CHECK(KSPSetType(ksp, KSPPREONLY));
    CHECK(PCSetType(pc, name == "mumps-ldlt" ? PCCHOLESKY : PCLU));
    CHECK(PCFactorSetMatSolverType(pc, name == "petsc-lu" ? MATSOLVERPETSC : MATSOLVERMUMPS));
  } else {
    CHECK(KSPSetType(ksp, KSPGMRES));
    CHECK(KSPGMRESSetRestart(ksp, o.restart));
    CHECK(KSPSetPCSide(ksp, PC_RIGHT));
    CHECK(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
    CHECK(KSPSetTolerances(ksp, o.rtol, 0.0, PETSC_DEFAULT, o.maxKrylov));
    if (name == "gmres-mumps") {  // MUMPS's LU inside GMRES: for inexact (BLR) factors
      CHECK(PCSetType(pc, PCLU));
      CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    } else if (name.rfind("ilu", 0) == 0 && name.size() > 3) {
      CHECK(PCSetType(pc, PCILU));
      CHECK(PCFactorSetLevels(pc, std::stoi(name.substr(3))));
    } else if (name == "hypre") {
      CHECK(PCSetType(pc, PCHYPRE));
      CHECK(PCHYPRESetType(pc, "boomeramg"));
    } else if (name == "gamg") {
      CHECK(PCSetType(pc, PCGAMG));
    } else {
      return false;
    }
  }
  CHECK(KSPSetOptionsPrefix(ksp, prefixOf(name).c_str()));
  CHECK(KSPSetFromOptions(ksp));
  return true;
}

// One PETSc solve: seconds, iterations, reason, residual by fibra's K, peak GiB.
struct PetscRow {
  double convert = 0, setup = 0, solve = 0, residual = 0, memory = 0;
  PetscInt iterations = 0;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  std::string note;  // the MUMPS ordering, a failed set-up
};

Eigen::VectorXd toEigen(Vec v) {
  PetscInt n;
  const PetscScalar* a;
  CHECK(VecGetLocalSize(v, &n));
  CHECK(VecGetArrayRead(v, &a));
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(a, n);
  CHECK(VecRestoreArrayRead(v, &a));
  return x;
}

// MUMPS's ordering (INFOG(7)) after a MUMPS factorisation, else "".
std::string mumpsOrdering(PC pc) {
  MatSolverType type;
  CHECK(PCFactorGetMatSolverType(pc, &type));
  if (!type || std::string(type) != MATSOLVERMUMPS) return "";
  Mat F;
  CHECK(PCFactorGetMatrix(pc, &F));
  PetscInt ordering = -1;
  CHECK(MatMumpsGetInfog(F, 7, &ordering));
  static const char* names[] = {"AMD", "given", "AMF", "SCOTCH", "PORD", "METIS", "QAMD"};
  return ordering >= 0 && ordering <= 6 ? std::string("ordering ") + names[ordering] : "";
}

PetscRow petscRun(const std::string& name, const LinearSystem& ls, const Eigen::VectorXd& b,
                  const Options& o) {
  PetscRow r;
  Mat A;
  r.convert = seconds([&] { A = toPetsc(ls); });
  KSP ksp;
  CHECK(KSPCreate(PETSC_COMM_SELF, &ksp));
  if (!configure(ksp, name, o)) {
    std::fprintf(stderr, "unknown solver %s\n", name.c_str());
    std::exit(2);
  }
  CHECK(KSPSetOperators(ksp, A, A));
  Vec vb, vx;
  CHECK(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, b.size(), b.data(), &vb));
  CHECK(VecDuplicate(vb, &vx));
  r.setup = seconds([&] { CHECK(KSPSetUp(ksp)); });
  r.solve = seconds([&] { CHECK(KSPSolve(ksp, vb, vx)); });
  CHECK(KSPGetIterationNumber(ksp, &r.iterations));
  CHECK(KSPGetConvergedReason(ksp, &r.reason));
  PC pc;
  CHECK(KSPGetPC(ksp, &pc));
  PCFailedReason failed;
  CHECK(PCGetFailedReason(pc, &failed));
  if (failed != PC_NOERROR) r.note = std::string("set-up failed: ") + PCFailedReasons[failed];
  else if (name.find("mumps") != std::string::npos) r.note = mumpsOrdering(pc);
  r.residual = relativeResidual(ls, toEigen(vx), b);
  CHECK(VecDestroy(&vx));
  CHECK(VecDestroy(&vb));
  CHECK(KSPDestroy(&ksp));
  CHECK(MatDestroy(&A));
  return r;
}

template <class Row>
double med(const std::vector<Row>& rows, double Row::*f) {
  std::vector<double> v;
  for (const Row& r : rows) v.push_back(r.*f);
  return medianOf(v);
}

// One line per solver, medians of o.repeats; false when a direct solve misses kDirectTolerance.
bool table(const Options& o, const LinearSystem& ls, const Eigen::VectorXd& b, std::FILE* csv) {
  std::printf("%-9s %-11s %7s %10s %8s %8s %8s %6s %9s %6s %6s  %s\n", "case", "solver", "dofs",
              "nonzeros", "convert", "setup", "solve", "its", "residual", "peak", "above",
              "outcome");
  const long nnz = ls.symmetric ? 2 * ls.K.nonZeros() - ls.freeCount : ls.K.nonZeros();  // full K
  bool ok = true;
  double above = 0;  // median GiB of the peak above the resident memory before the solve
  auto line = [&](const std::string& s, double convert, double setup, double solve, int its,
                  double residual, double memory, const std::string& outcome) {
    std::printf("%-9s %-11s %7d %10ld %8.3f %8.3f %8.3f %6d %9.1e %6.2f %6.2f  %s\n",
                o.name.c_str(), s.c_str(), int(ls.freeCount), nnz, convert, setup, solve, its,
                residual, memory, above, outcome.c_str());
    if (csv)
      std::fprintf(csv, "%s,%s,%d,%s,%d,%ld,%.4f,%.4f,%.4f,%d,%.3e,%.3f,%.3f,\"%s\"\n",
                   o.name.c_str(), o.friction ? "on" : "off", o.threads, s.c_str(),
                   int(ls.freeCount), nnz, convert, setup, solve, its, residual, memory, above,
                   outcome.c_str());
    if (isDirect(s) && !(residual <= kDirectTolerance)) {
      std::printf("  FAILED: %s residual %.1e above %.0e\n", s.c_str(), residual, kDirectTolerance);
      ok = false;
    }
  };
  auto repeat = [&](auto run) {
    std::vector<decltype(run())> rows;
    std::vector<double> extra;
    for (int k = 0; k < o.repeats; ++k) {
      malloc_trim(0);  // freed heap back to the system: `before` is what is in use
      const double before = residentGiB();
      resetPeak();
      rows.push_back(run());
      rows.back().memory = peakGiB();
      extra.push_back(rows.back().memory - before);
    }
    above = medianOf(extra);
    return rows;
  };
  for (const std::string& s : o.references) {
    const std::vector<SolveRow> rows = repeat([&] { return strategyRun(s, ls, b, o.threads); });
    const SolveRow& r0 = rows.front();
    const std::string outcome = r0.shifted < 0 ? "not positive definite"
                                : r0.shifted > 0 ? "shifted/LDLT" : "";
    line(s, 0, med(rows, &SolveRow::analyse) + med(rows, &SolveRow::factorise),
         med(rows, &SolveRow::solve), r0.iterations, med(rows, &SolveRow::residual),
         med(rows, &SolveRow::memory), outcome);
  }
  for (const std::string& s : o.solvers) {
    if (s == "mumps-ldlt" && !ls.symmetric) {
      std::printf("%-9s %-11s (K not symmetric: skipped)\n", o.name.c_str(), s.c_str());
      continue;
    }
    const std::vector<PetscRow> rows = repeat([&] { return petscRun(s, ls, b, o); });
    const PetscRow& r0 = rows.front();
    std::string outcome = std::string(KSPConvergedReasons[r0.reason]);
    if (!r0.note.empty()) outcome += ", " + r0.note;
    line(s, med(rows, &PetscRow::convert), med(rows, &PetscRow::setup), med(rows, &PetscRow::solve),
         r0.iterations, med(rows, &PetscRow::residual), med(rows, &PetscRow::memory), outcome);
  }
  return ok;
}

// MUMPS's LU of the first tangent (as gmres-mumps factorises it) as the preconditioner of GMRES
// on each later one, not refactorised: per tangent the GMRES iterations, solve seconds, residual.
void reuse(const Options& o, const std::vector<LinearSystem>& tangents, const Eigen::VectorXd& b) {
  std::printf("re-use: MUMPS LU of the tangent after warm-up iteration %d as the preconditioner of "
              "GMRES on the next %d\n", o.warm - o.reuse, o.reuse);
  Mat P = toPetsc(tangents.front());
  KSP ksp;
  CHECK(KSPCreate(PETSC_COMM_SELF, &ksp));
  configure(ksp, "gmres-mumps", o);  // its PETSC_OPTIONS (BLR) apply
  PC pc;
  CHECK(KSPGetPC(ksp, &pc));
  CHECK(PCSetReusePreconditioner(pc, PETSC_TRUE));
  CHECK(KSPSetOperators(ksp, P, P));
  const double factor = seconds([&] { CHECK(KSPSetUp(ksp)); });
  std::printf("  factorisation %.3f s\n", factor);
  Vec vb, vx;
  CHECK(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, b.size(), b.data(), &vb));
  CHECK(VecDuplicate(vb, &vx));
  for (size_t k = 1; k < tangents.size(); ++k) {
    Mat A = toPetsc(tangents[k]);
    CHECK(KSPSetOperators(ksp, A, P));
    const double t = seconds([&] { CHECK(KSPSolve(ksp, vb, vx)); });
    PetscInt its;
    KSPConvergedReason reason;
    CHECK(KSPGetIterationNumber(ksp, &its));
    CHECK(KSPGetConvergedReason(ksp, &reason));
    std::printf("  tangent +%zu: %4d GMRES iterations, solve %.3f s, residual %.1e (%s)\n", k,
                int(its), t, relativeResidual(tangents[k], toEigen(vx), b),
                KSPConvergedReasons[reason]);
    CHECK(MatDestroy(&A));
  }
  CHECK(VecDestroy(&vx));
  CHECK(VecDestroy(&vb));
  CHECK(KSPDestroy(&ksp));
  CHECK(MatDestroy(&P));
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (parseCaseOption(o, k, v)) continue;
    if (k == "--solver") o.solvers = split(v);
    else if (k == "--reference") o.references = split(v == "none" ? "" : v);
    else if (k == "--threads") o.threads = std::stoi(v);
    else if (k == "--repeats") o.repeats = std::stoi(v);
    else if (k == "--max-krylov") o.maxKrylov = std::stoi(v);
    else if (k == "--restart") o.restart = std::stoi(v);
    else if (k == "--rtol") o.rtol = std::stod(v);
    else if (k == "--reuse") o.reuse = std::stoi(v);
    else if (k == "--csv") o.csv = v;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CHECK(PetscInitializeNoArguments());  // one rank; PETSC_OPTIONS still read
  setBlasThreads(o.threads);
  std::printf("case %s, friction %s, OpenBLAS threads %d, one MPI rank\n", o.name.c_str(),
              o.friction ? "on (mu 0.1)" : "off", o.threads);
  std::vector<LinearSystem> tangents;  // the last o.reuse + 1 warm-up tangents (--reuse)
  double assemble = 0;
  std::function<void(const LinearSystem&)> keep;  // the warm-up's tangents, with --reuse
  if (o.reuse > 0)
    keep = [&](const LinearSystem& t) {
      tangents.push_back(t);
      if (int(tangents.size()) > o.reuse + 1) tangents.erase(tangents.begin());
    };
  auto w = warmWorld(o, o.threads, assemble, keep);
  setBlasThreads(o.threads);
  const LinearSystem& ls = w->system;  // the tangent met on the way (warmWorld)
  std::printf("tangent: %d equations, %ld stored non-zeros (%s), |K - K^T| / |K| = %.1e\n",
              int(ls.freeCount), long(ls.K.nonZeros()),
              ls.symmetric ? "upper triangle, symmetric" : "full", asymmetry(ls));
  Eigen::VectorXd b = Eigen::VectorXd::Random(ls.freeCount);  // seeded: as bench_linear_solves
  std::FILE* csv = openCsv(o.csv, "case,friction,threads,solver,dofs,nonzeros,convert_s,setup_s,"
                                  "solve_s,krylov_iterations,residual,peak_gib,above_gib,outcome");
  const bool ok = table(o, ls, b, csv);
  if (csv) std::fclose(csv);
  if (o.reuse > 0 && int(tangents.size()) == o.reuse + 1) reuse(o, tangents, b);
  w.reset();
  CHECK(PetscFinalize());
  return ok ? 0 : 1;
}
