// Block preconditioners on fibra's contact tangents (issue: linear solves at paper scale,
// "fibre/yarn block preconditioners with the contact coupling applied as a sparse product"):
// GMRES (systems/krylov.h) on the true tangent K, right-preconditioned by a two-level Schwarz
// method whose pieces follow the fibres, against the direct solves of systems/linear_solver.h
// on the same matrix.
//
// Local level, one of:
// - fibre: block Jacobi, a dense LU of each fibre's diagonal block (its free equations are
//   contiguous, engine numbering); the contact between fibres is applied only through K;
// - patch: fibres grouped into aggregates (greedily: a fibre not yet taken and all its untaken
//   neighbours, where neighbours are fibres coupled in K, i.e. in contact; fibres left over
//   join a neighbour's aggregate), each patch an aggregate plus `overlap` layers of neighbouring
//   fibres, factorised by UMFPACK (no iterative refinement); restricted additive Schwarz: an
//   equation takes its value from the patch of its own aggregate.
// Coarse level (optional): Phi = per group (a fibre, or an aggregate) and per hat function of
// the node index (`segments` pieces along the fibres, hats at segments + 1 points), the three
// translations of x0 and, with rotations, the three infinitesimal rotations of the group's
// sections about their centre at that node index (x0 - c and both directors turned); the
// coarse matrix Ac = Phi^T K Phi factorised by UMFPACK. Applied multiplicatively:
//   y_c = Phi Ac^-1 Phi^T v,   y = y_c + B^-1 (v - K y_c)   (B^-1: the local level).
// Reported per variant: set-up (local factorisations + coarse), the time of one application,
// GMRES iterations to |K x - b| <= 1e-8 |b|, GMRES time, the total; and, on the same K, the
// reference strategies (analyse + factorise + solve; "cholmod" the fresh CHOLMOD
// factorisation of the symmetric part that the goal is stated against).
//
//   build/bench_block_preconditioners [--case yarn61 | --scene FILE [--checkpoint FILE]]
//       [--warm 3] [--warm-strategy umfpack] [--friction on|off] [--grip on|off]
//       [--local fibre,patch] [--overlap 1] [--coarse none,fibre,aggregate]
//       [--segments 8,15] [--rotations on|off] [--restart 60] [--max 600]
//       [--reference umfpack,mumps,cholmod]
// One thread (OpenBLAS at 1), b random (seeded).
#include "core/allocator.h"
#include "bench/tangent_cases.h"
#include "systems/krylov.h"

#include <Eigen/LU>
#include <Eigen/UmfPackSupport>

using namespace fibra;
using namespace fibra::bench;

namespace {

using Umfpack = Eigen::UmfPackLU<SparseMatrix>;

// UMFPACK keeps a view of the matrix it factorised: both live together, at a fixed address.
struct Factor {
  SparseMatrix A;
  Umfpack lu;
  void compute(SparseMatrix&& m) {
    A = std::move(m);
    lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
    lu.compute(A);
  }
};

struct Tangent {
  SparseMatrix K;                  // full storage
  std::vector<Index> first;        // per fibre its first equation, then the equation count
  std::vector<std::vector<Index>> neighbours;  // per fibre the fibres coupled to it in K
};

Tangent tangentOf(const WorldState& w) {
  const LinearSystem& ls = w.system;
  Tangent t;
  t.K = ls.symmetric ? SparseMatrix(ls.K.selfadjointView<Eigen::Upper>()) : ls.K;
  const FibreStore& F = w.fibres;
  for (Index f = 0; f < F.fibres(); ++f) {
    Index e = -1;
    for (Index d = kNodeDofs * F.firstNode[f]; e < 0 && d < kNodeDofs * (F.firstNode[f] + F.nodeCount[f]); ++d)
      e = ls.equation[d];
    t.first.push_back(e);
  }
  t.first.push_back(ls.freeCount);
  const Index nf = F.fibres();
  std::vector<Index> fibreOf(ls.freeCount);
  for (Index f = 0; f < nf; ++f)
    for (Index e = t.first[f]; e < t.first[f + 1]; ++e) fibreOf[e] = f;
  t.neighbours.resize(nf);
  for (Index f = 0; f < nf; ++f) {
    std::vector<char> seen(nf, 0);
    seen[f] = 1;
    for (Index c = t.first[f]; c < t.first[f + 1]; ++c)
      for (SparseMatrix::InnerIterator it(t.K, c); it; ++it)
        if (!seen[fibreOf[it.row()]]) seen[fibreOf[it.row()]] = 1, t.neighbours[f].push_back(fibreOf[it.row()]);
  }
  return t;
}

// Aggregates of fibres (see the header); per fibre its aggregate.
std::vector<int> aggregates(const Tangent& t) {
  const auto& nb = t.neighbours;
  std::vector<int> a(nb.size(), -1);
  int n = 0;
  for (size_t f = 0; f < nb.size(); ++f) {
    bool free = a[f] < 0;
    for (Index g : nb[f]) free = free && a[g] < 0;
    if (!free) continue;
    a[f] = n;
    for (Index g : nb[f]) a[g] = n;
    ++n;
  }
  for (size_t f = 0; f < nb.size(); ++f)
    if (a[f] < 0) {
      for (Index g : nb[f])
        if (a[g] >= 0) {
          a[f] = a[g];
          break;
        }
      if (a[f] < 0) a[f] = n++;
    }
  return a;
}

// One piece of the local level: its equations (ascending), which of them it owns, its factor.
struct Piece {
  std::vector<Index> eq;
  std::vector<char> owned;
  std::unique_ptr<Factor> sparse;           // patch
  Eigen::PartialPivLU<Eigen::MatrixXd> dense;  // fibre block
};

SparseMatrix submatrix(const SparseMatrix& K, const std::vector<Index>& eq) {
  std::vector<Index> local(K.cols(), -1);
  for (size_t i = 0; i < eq.size(); ++i) local[eq[i]] = Index(i);
  std::vector<Eigen::Triplet<double>> t;
  for (Index c : eq)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (local[it.row()] >= 0) t.emplace_back(local[it.row()], local[c], it.value());
  SparseMatrix A(Index(eq.size()), Index(eq.size()));
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

std::vector<Piece> fibreBlocks(const Tangent& t) {
  std::vector<Piece> pieces(t.first.size() - 1);
  for (size_t f = 0; f + 1 < t.first.size(); ++f) {
    const Index a = t.first[f], n = t.first[f + 1] - a;
    for (Index e = a; e < a + n; ++e) pieces[f].eq.push_back(e), pieces[f].owned.push_back(1);
    pieces[f].dense.compute(Eigen::MatrixXd(t.K.block(a, a, n, n)));
  }
  return pieces;
}

std::vector<Piece> patches(const Tangent& t, const std::vector<int>& aggregate, int overlap) {
  const size_t nf = t.neighbours.size();
  const int n = *std::max_element(aggregate.begin(), aggregate.end()) + 1;
  std::vector<Piece> pieces(n);
  for (int a = 0; a < n; ++a) {
    std::vector<char> in(nf, 0), own(nf, 0);
    for (size_t f = 0; f < nf; ++f) in[f] = own[f] = aggregate[f] == a;
    for (int layer = 0; layer < overlap; ++layer) {
      std::vector<char> next = in;
      for (size_t f = 0; f < nf; ++f)
        if (in[f])
          for (Index g : t.neighbours[f]) next[g] = 1;
      in = next;
    }
    Piece& p = pieces[a];
    for (size_t f = 0; f < nf; ++f)
      if (in[f])
        for (Index e = t.first[f]; e < t.first[f + 1]; ++e) p.eq.push_back(e), p.owned.push_back(own[f]);
    p.sparse = std::make_unique<Factor>();
    p.sparse->compute(submatrix(t.K, p.eq));
  }
  return pieces;
}

void applyLocal(const std::vector<Piece>& pieces, const Eigen::VectorXd& v, Eigen::VectorXd& y) {
  y.setZero(v.size());
  Eigen::VectorXd r, z;
  for (const Piece& p : pieces) {
    r.resize(Index(p.eq.size()));
    for (size_t i = 0; i < p.eq.size(); ++i) r(Index(i)) = v(p.eq[i]);
    z = p.sparse ? Eigen::VectorXd(p.sparse->lu.solve(r)) : Eigen::VectorXd(p.dense.solve(r));
    for (size_t i = 0; i < p.eq.size(); ++i)
      if (p.owned[i]) y(p.eq[i]) = z(Index(i));
  }
}

// The coarse basis of the header for groups `group` (per fibre).
SparseMatrix coarseBasis(const WorldState& w, const std::vector<int>& group, int segments,
                         bool rotations) {
  const FibreStore& F = w.fibres;
  const int modes = rotations ? 6 : 3;
  const int groups = *std::max_element(group.begin(), group.end()) + 1;
  Index maxNodes = 0;
  for (Index f = 0; f < F.fibres(); ++f) maxNodes = std::max(maxNodes, F.nodeCount[f]);
  std::vector<Vec3> centre(size_t(groups * maxNodes), Vec3::Zero());
  std::vector<int> count(centre.size(), 0);
  for (Index f = 0; f < F.fibres(); ++f)
    for (Index k = 0; k < F.nodeCount[f]; ++k) {
      centre[group[f] * maxNodes + k] += x0Of(F.q, F.firstNode[f] + k);
      ++count[group[f] * maxNodes + k];
    }
  for (size_t i = 0; i < centre.size(); ++i)
    if (count[i]) centre[i] /= count[i];
  std::vector<Eigen::Triplet<double>> t;
  for (Index f = 0; f < F.fibres(); ++f)
    for (Index k = 0; k < F.nodeCount[f]; ++k) {
      const Index node = F.firstNode[f] + k;
      const double at = double(k) / double(F.nodeCount[f] - 1) * segments;
      for (int c = std::max(0, int(at) - 1); c <= std::min(segments, int(at) + 1); ++c) {
        const double phi = std::max(0.0, 1 - std::abs(at - c));
        if (phi == 0) continue;
        const Index col = (Index(group[f]) * (segments + 1) + c) * modes;
        auto add = [&](int dof, int m, double v) {
          const Index e = w.system.equation[kNodeDofs * node + dof];
          if (e >= 0 && v != 0) t.emplace_back(e, col + m, v);
        };
        for (int m = 0; m < 3; ++m) add(m, m, phi);
        if (!rotations) continue;
        const Vec3 arm = x0Of(F.q, node) - centre[group[f] * maxNodes + k];
        for (int m = 0; m < 3; ++m) {
          const Vec3 om = Vec3::Unit(m) * phi;
          const Vec3 dx = om.cross(arm), d1 = om.cross(Vec3(g1Of(F.q, node))),
                     d2 = om.cross(Vec3(g2Of(F.q, node)));
          for (int i = 0; i < 3; ++i) add(i, 3 + m, dx(i)), add(3 + i, 3 + m, d1(i)), add(6 + i, 3 + m, d2(i));
        }
      }
    }
  SparseMatrix Phi(w.system.freeCount, Index(groups) * (segments + 1) * modes);
  Phi.setFromTriplets(t.begin(), t.end());
  return Phi;
}

struct Coarse {
  SparseMatrix Phi;
  Factor factor;
};

void coarseFactor(const Tangent& t, Coarse& c) {
  SparseMatrix Ac = SparseMatrix(c.Phi.transpose()) * (t.K * c.Phi);
  for (Index j = 0; j < Ac.cols(); ++j)  // a column of Phi with no free entry
    if (c.Phi.col(j).norm() == 0) Ac.coeffRef(j, j) = 1;
  c.factor.compute(std::move(Ac));
}

struct Options : TangentCase {
  std::vector<std::string> local{"fibre", "patch"}, coarse{"none", "fibre", "aggregate"},
      rotations{"on"}, references{"umfpack", "mumps", "cholmod"};
  std::vector<int> segments{8, 15};
  int overlap = 1, restart = 60, maxIterations = 600;
  int sequence = 0;  // tangents of this many further Newton iterations, solved with a re-used factor
};

// A preconditioner of the header built on one tangent.
struct Preconditioner {
  std::vector<Piece> pieces;
  Coarse coarse;
  bool withCoarse = false;
  double setLocal = 0, setCoarse = 0;  // s
  void apply(const SparseMatrix& K, const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
    if (!withCoarse) return applyLocal(pieces, v, y);
    const Eigen::VectorXd yc =
        coarse.Phi * coarse.factor.lu.solve(Eigen::VectorXd(coarse.Phi.transpose() * v));
    applyLocal(pieces, v - K * yc, y);
    y += yc;
  }
};

std::unique_ptr<Preconditioner> build(const Options& o, const WorldState& w, const Tangent& t,
                                      const std::string& local, const std::string& coarse,
                                      int segments, bool rotations) {
  auto p = std::make_unique<Preconditioner>();
  const std::vector<int> aggregate = aggregates(t);
  p->setLocal = seconds([&] {
    if (local == "full")  // the exact LU: one patch holding every fibre
      p->pieces = patches(t, std::vector<int>(aggregate.size(), 0), 0);
    else
      p->pieces = local == "fibre" ? fibreBlocks(t) : patches(t, aggregate, o.overlap);
  });
  p->withCoarse = coarse != "none";
  if (p->withCoarse) {
    std::vector<int> group(t.neighbours.size());
    for (size_t f = 0; f < group.size(); ++f) group[f] = coarse == "fibre" ? int(f) : aggregate[f];
    p->setCoarse = seconds([&] {
      p->coarse.Phi = coarseBasis(w, group, segments, rotations);
      coarseFactor(t, p->coarse);
    });
  }
  return p;
}

// GMRES on K x = b preconditioned by p (built on this K or an earlier one, whose K products
// it applies: `Kp`).
GmresResult solveWith(const Options& o, const SparseMatrix& K, const SparseMatrix& Kp,
                      const Preconditioner& p, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                      double& time) {
  const LinearOperator A = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y.noalias() = K * v; };
  const LinearOperator M = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) { p.apply(Kp, v, y); };
  GmresSettings g;
  g.tolerance = 1e-8;
  g.restart = o.restart;
  g.maxIterations = o.maxIterations;
  GmresWorkspace ws;
  GmresResult r;
  time = seconds([&] { r = gmres(A, M, b, x, g, ws); });
  return r;
}

void variant(const Options& o, const WorldState& w, const Tangent& t, const std::string& local,
             const std::string& coarse, int segments, bool rotations, const Eigen::VectorXd& b,
             const std::vector<SparseMatrix>& later) {
  const auto p = build(o, w, t, local, coarse, segments, rotations);
  Eigen::VectorXd y;
  const double once = median(3, [&] { p->apply(t.K, b, y); });
  Eigen::VectorXd x;
  double solve = 0;
  const GmresResult r = solveWith(o, t.K, t.K, *p, b, x, solve);
  std::printf("| %s (%zu, overlap %d) | %s | %s | %s | %.3f + %.3f | %.4f | %d%s | %.1e | %.2f | **%.2f** |",
              local.c_str(), p->pieces.size(), local == "patch" ? o.overlap : 0, coarse.c_str(),
              coarse == "none" ? "—" : std::to_string(segments).c_str(),
              coarse == "none" ? "—" : rotations ? "on" : "off", p->setLocal, p->setCoarse, once,
              r.iterations, r.converged ? "" : " (fails)", relativeResidual(w.system, x, b), solve,
              p->setLocal + p->setCoarse + solve);
  // the same preconditioner on the tangents of the following Newton iterations
  for (const SparseMatrix& K : later) {
    double s = 0;
    Eigen::VectorXd xl;
    const GmresResult rl = solveWith(o, K, t.K, *p, b, xl, s);
    std::printf(" %d%s (%.2f s; |dK|/|K| %.1e)", rl.iterations, rl.converged ? "" : "!", s,
                (K - t.K).norm() / t.K.norm());
  }
  std::printf(later.empty() ? "\n" : " |\n");
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (parseCaseOption(o, k, v)) continue;
    if (k == "--local") o.local = split(v);
    else if (k == "--coarse") o.coarse = split(v);
    else if (k == "--rotations") o.rotations = split(v);
    else if (k == "--reference") o.references = split(v);
    else if (k == "--segments") { o.segments.clear(); for (auto& s : split(v)) o.segments.push_back(std::stoi(s)); }
    else if (k == "--overlap") o.overlap = std::stoi(v);
    else if (k == "--restart") o.restart = std::stoi(v);
    else if (k == "--max") o.maxIterations = std::stoi(v);
    else if (k == "--sequence") o.sequence = std::stoi(v);
    else { std::fprintf(stderr, "unknown option %s\n", k.c_str()); return 2; }
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  bench::setBlasThreads(1);
  double assemble = 0;
  // with --sequence S: the tangents of the last S + 1 warm-up iterations; the first of them is
  // the tangent every variant is built on, the others are solved with it re-used
  std::vector<SparseMatrix> seen;
  if (o.sequence > 0) o.warm += o.sequence;
  const auto w = warmWorld(o, 1, assemble, [&](const LinearSystem& ls) {
    if (o.sequence > 0)
      seen.push_back(ls.symmetric ? SparseMatrix(ls.K.selfadjointView<Eigen::Upper>()) : ls.K);
  });
  std::vector<SparseMatrix> later;
  if (o.sequence > 0) {
    if (int(seen.size()) < o.sequence + 1) {
      std::fprintf(stderr, "the warm-up made %zu iterations, fewer than --sequence + 1\n", seen.size());
      return 1;
    }
    seen.erase(seen.begin(), seen.end() - (o.sequence + 1));
    later.assign(seen.begin() + 1, seen.end());
    w->system.K = seen.front(), w->system.symmetric = false;
  }
  const Tangent t = tangentOf(*w);
  const std::vector<int> aggregate = aggregates(t);
  std::printf("%ld equations, %ld non-zeros (full), %zu fibres, %d aggregates\n",
              long(t.K.rows()), long(t.K.nonZeros()), t.neighbours.size(),
              *std::max_element(aggregate.begin(), aggregate.end()) + 1);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(t.K.rows());
  std::printf("product K v: %.4f s\n", median(5, [&] { Eigen::VectorXd y = t.K * b; }));
  for (const std::string& s : o.references) {
    if (s == "none") continue;
    const SolveRow r = strategyRun(s, w->system, b, 1);
    std::printf("reference %s: analyse %.3f + factorise %.3f + solve %.3f = **%.2f** s, residual %.1e%s\n",
                s.c_str(), r.analyse, r.factorise, r.solve, r.analyse + r.factorise + r.solve,
                r.residual, r.shifted < 0 ? " (not positive definite)" : "");
  }
  std::printf("| local (pieces) | coarse | segments | rotations | set-up s (local + coarse) | one application s | GMRES it | residual | GMRES s | total s |%s\n",
              later.empty() ? "" : " re-used on the next tangents: GMRES it (s) |");
  std::printf("|---|---|---|---|---|---|---|---|---|---|%s\n", later.empty() ? "" : "---|");
  for (const std::string& local : o.local)
    for (const std::string& coarse : o.coarse) {
      if (coarse == "none") {
        variant(o, *w, t, local, coarse, 0, false, b, later);
        continue;
      }
      for (int segments : o.segments)
        for (const std::string& rot : o.rotations) variant(o, *w, t, local, coarse, segments, rot == "on", b, later);
    }
  return 0;
}
