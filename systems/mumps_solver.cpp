#include "systems/mumps_solver.h"

#include <cholmod.h>
#include <dmumps_c.h>
#include <stdio.h>  // scotch.h needs FILE

#include <scotch.h>

#include <vector>

namespace fibra {
namespace {

constexpr int kJobInit = -1, kJobEnd = -2, kJobAnalyse = 1, kJobFactorise = 2, kJobSolve = 3;
constexpr int kUseCommWorld = -987654;  // MUMPS's code for "the default communicator"

// MUMPS's control and information arrays are 1-based in its documentation.
int& icntl(DMUMPS_STRUC_C& id, int k) { return id.icntl[k - 1]; }
double& cntl(DMUMPS_STRUC_C& id, int k) { return id.cntl[k - 1]; }
int infog(const DMUMPS_STRUC_C& id, int k) { return id.infog[k - 1]; }

// MUMPS's orderings (ICNTL(7)).
constexpr int kOrderAmd = 0, kOrderGiven = 1;

// Silences MUMPS: no error, diagnostic, global or statistics output.
void silence(DMUMPS_STRUC_C& id) {
  icntl(id, 1) = -1;
  icntl(id, 2) = -1;
  icntl(id, 3) = -1;
  icntl(id, 4) = 0;
}

// The METIS nested-dissection pivot order of the pattern of A + A^T (CHOLMOD's interface to
// METIS), as MUMPS's PERM_IN: perm[i] = 1-based position of variable i in the pivot order.
// A: full, or upper triangle when `upper`. Empty on failure (METIS out of memory).
std::vector<int> metisOrder(const SparseMatrix& A, bool upper) {
  SparseMatrix P = A;
  for (Index k = 0; k < P.nonZeros(); ++k) P.valuePtr()[k] = 1;
  SparseMatrix S = upper ? P : SparseMatrix((P + SparseMatrix(P.transpose())).triangularView<Eigen::Upper>());
  S.makeCompressed();
  cholmod_sparse c{};
  c.nrow = c.ncol = size_t(S.rows());
  c.nzmax = size_t(S.nonZeros());
  c.p = S.outerIndexPtr();
  c.i = S.innerIndexPtr();
  c.x = S.valuePtr();
  c.stype = 1;  // symmetric, upper triangle stored
  c.itype = CHOLMOD_INT;
  c.xtype = CHOLMOD_PATTERN;
  c.dtype = CHOLMOD_DOUBLE;
  c.sorted = 1;
  c.packed = 1;
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  std::vector<int> order(S.rows()), perm;
  if (cholmod_metis(&c, nullptr, 0, 1, order.data(), &common)) {
    perm.resize(order.size());
    for (size_t k = 0; k < order.size(); ++k) perm[order[k]] = int(k) + 1;
  }
  cholmod_finish(&common);
  return perm;
}

}  // namespace

std::string mumpsErrorMessage(int code, int detail) {
  const char* meaning = "see the MUMPS users' guide, section \"Error diagnostics\"";
  switch (code) {
    case -5: case -13: meaning = "out of memory (allocation failed)"; break;
    case -6: meaning = "matrix structurally singular"; break;
    case -7: case -8: case -14: meaning = "integer workspace too small (out of memory)"; break;
    case -9: case -15: meaning = "real workspace too small (out of memory, even with ICNTL(14) raised)"; break;
    case -10: meaning = "matrix numerically singular"; break;
    case -11: meaning = "real workspace for the solution too small"; break;
    case -16: meaning = "N out of range"; break;
    case -17: case -20: meaning = "internal send buffer too small"; break;
    case -19: meaning = "maximum memory (ICNTL(23)) too small"; break;
  }
  return "MUMPS error " + std::to_string(code) + " (INFOG(2) " + std::to_string(detail) +
         "): " + meaning;
}

struct MumpsFactor::Impl {
  DMUMPS_STRUC_C id{};
  bool alive = false;           // job -1 done with id.sym
  MumpsAnalysis analysed;       // what the last successful analysis was for
  bool valid = false;           // analysis valid
  bool factorised = false;
  std::vector<int> irn, jcn, permIn;
  std::vector<double> a;

  void start(int sym) {
    end();
    id = DMUMPS_STRUC_C{};
    id.sym = sym;
    id.par = 1;  // the host works (one process)
    id.comm_fortran = kUseCommWorld;
    id.job = kJobInit;
    dmumps_c(&id);
    silence(id);
    alive = true;
  }
  void end() {
    if (!alive) return;
    id.job = kJobEnd;
    dmumps_c(&id);
    alive = false;
  }
  ~Impl() { end(); }

  // 1-based COO triplets of A's pattern, in CSC storage order (so a is A's value array).
  void triplets(const SparseMatrix& A) {
    irn.resize(A.nonZeros());
    jcn.resize(A.nonZeros());
    for (Index j = 0; j < A.outerSize(); ++j)
      for (Index k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k) {
        irn[k] = A.innerIndexPtr()[k] + 1;
        jcn[k] = j + 1;
      }
  }
  void values(const SparseMatrix& A) { a.assign(A.valuePtr(), A.valuePtr() + A.nonZeros()); }
  void point() {
    id.nnz = MUMPS_INT8(irn.size());
    id.irn = irn.data();
    id.jcn = jcn.data();
    id.a = a.data();
  }
  bool run(int job, std::string& message) {
    id.job = job;
    dmumps_c(&id);
    if (infog(id, 1) >= 0) return true;
    message = mumpsErrorMessage(infog(id, 1), infog(id, 2));
    return false;
  }
};

MumpsFactor::MumpsFactor() : impl_(std::make_unique<Impl>()) {}
MumpsFactor::~MumpsFactor() = default;

bool MumpsFactor::needsAnalysis(const MumpsAnalysis& how) const {
  return !impl_->valid || !(impl_->analysed == how);
}

bool MumpsFactor::analyse(const SparseMatrix& A, const MumpsAnalysis& how, std::string& message) {
  Impl& m = *impl_;
  m.valid = m.factorised = false;
  const int sym = how.symmetric ? 2 : 0;
  if (!m.alive || m.id.sym != sym) m.start(sym);  // the symmetry is fixed at job -1
  m.triplets(A);
  m.values(A);  // values at analysis: MUMPS may use them to permute and scale (ICNTL(6), (8))
  m.id.n = int(A.rows());
  m.point();
  const bool metis = how.ordering == Ordering::Metis || how.metisAuto;
  m.permIn = metis ? metisOrder(A, how.symmetric) : std::vector<int>{};
  m.id.perm_in = m.permIn.empty() ? nullptr : m.permIn.data();
  icntl(m.id, 7) = m.permIn.empty() ? kOrderAmd : kOrderGiven;
  icntl(m.id, 35) = how.blrTolerance > 0 ? 2 : 0;  // BLR in factorisation and solve
  cntl(m.id, 7) = how.blrTolerance;
  if (!m.run(kJobAnalyse, message)) return false;
  m.analysed = how;
  m.valid = true;
  return true;
}

bool MumpsFactor::factorise(const SparseMatrix& A, std::string& message) {
  Impl& m = *impl_;
  m.factorised = false;
  if (!m.valid) {
    message = "MUMPS: no valid analysis";
    return false;
  }
  m.values(A);
  m.point();
  if (!m.run(kJobFactorise, message)) {
    if (infog(m.id, 1) != -9) return false;
    icntl(m.id, 14) = std::max(icntl(m.id, 14), 20) * 4;  // workspace margin, percent
    if (!m.run(kJobFactorise, message)) return false;
    message.clear();
  }
  m.factorised = true;
  return true;
}

void MumpsFactor::solve(Eigen::VectorXd& x) {
  Impl& m = *impl_;
  if (!m.factorised) {
    x.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  m.id.rhs = x.data();
  m.id.nrhs = 1;
  m.id.lrhs = int(x.size());
  icntl(m.id, 20) = 0;  // dense right-hand side
  icntl(m.id, 21) = 0;  // centralised solution, overwriting rhs
  std::string message;
  if (!m.run(kJobSolve, message)) x.setConstant(std::numeric_limits<double>::quiet_NaN());
}

int MumpsFactor::orderingUsed() const { return infog(impl_->id, 7); }
double MumpsFactor::estimatedFlops() const { return impl_->alive ? double(impl_->id.rinfog[0]) : 0.0; }

}  // namespace fibra

// Scotch's Fortran SCOTCHFGRAPHBUILD and SCOTCHFGRAPHPART, replaced for this process (the dynamic linker binds
// MUMPS's call here: CMake exports the symbol, cmake/FibraDependencies.cmake). MUMPS 5.5's block
// low-rank clustering (MUMPS_SCOTCH_KWAY_MIXEDto32, libmumps_common) builds a SCOTCH_Graph in
// uninitialised stack memory without SCOTCH_graphInit; Scotch 7 reads flags and a context from
// it, and stale stack contents crash the partition or corrupt the heap. Here the graph is
// initialised first, then built as Scotch's own wrapper does: an array passed equal to another
// means "absent" (vendtab = verttab + 1: compact; velotab, vlbltab = verttab; edlotab = edgetab).
// The partition (the clusters of the BLR blocks) runs in a Scotch context of one thread,
// deterministic, with its own generator seeded alike every call: Scotch's default (threads on
// every core, a clock-seeded generator) clusters differently from run to run.
extern "C" void scotchfgraphbuild_(SCOTCH_Graph* graph, const SCOTCH_Num* base,
                                   const SCOTCH_Num* vertnbr, const SCOTCH_Num* verttab,
                                   const SCOTCH_Num* vendtab, const SCOTCH_Num* velotab,
                                   const SCOTCH_Num* vlbltab, const SCOTCH_Num* edgenbr,
                                   const SCOTCH_Num* edgetab, const SCOTCH_Num* edlotab,
                                   int* status) {
  SCOTCH_graphInit(graph);
  *status = SCOTCH_graphBuild(graph, *base, *vertnbr, verttab,
                              vendtab == verttab + 1 ? nullptr : vendtab,
                              velotab == verttab ? nullptr : velotab,
                              vlbltab == verttab ? nullptr : vlbltab, *edgenbr, edgetab,
                              edlotab == edgetab ? nullptr : edlotab);
}

extern "C" void scotchfgraphpart_(const SCOTCH_Graph* graph, const SCOTCH_Num* parts,
                                  SCOTCH_Strat* strategy, SCOTCH_Num* parttab, int* status) {
  SCOTCH_Context context;
  SCOTCH_Graph bound;
  SCOTCH_contextInit(&context);
  SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1);
  SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1);
  SCOTCH_contextRandomClone(&context);
  SCOTCH_contextRandomSeed(&context, 1);
  SCOTCH_contextThreadSpawn(&context, 1, nullptr);
  SCOTCH_graphInit(&bound);
  *status = SCOTCH_contextBindGraph(&context, graph, &bound);
  if (*status == 0) *status = SCOTCH_graphPart(&bound, *parts, strategy, parttab);
  SCOTCH_graphExit(&bound);
  SCOTCH_contextExit(&context);
}
