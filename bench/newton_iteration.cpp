// Time per Newton iteration, split into assembly, factorisation and solve, for one fibre and for
// 1000 unconnected fibres of 40 quadratic elements, with 1 and 2 threads (TBB and BLAS alike).
// Also: scattering element blocks into the fixed pattern against rebuilding the matrix from
// triplets every iteration.
//
//   build/bench_newton_iteration [--repeats N] [--csv FILE]
#include "core/allocator.h"
#include "bench/bench_util.h"
#include "engine/world_state.h"
#include "systems/beam_element.h"

#include <Eigen/SparseCore>
#include <cstring>

using namespace fibra;

namespace {

// n fibres of 40 quadratic elements, 10 mm long, R = 0.05 mm, on a square grid 1 mm apart,
// each clamped at its start with a tip force; measured at the converged loaded state.
SceneDef fibresScene(int n) {
  SceneDef s;
  s.materials.push_back({"m", 73000, 0.3, 0.12, 1});
  const int side = int(std::ceil(std::sqrt(double(n))));
  for (int i = 0; i < n; ++i) {
    FibreDef f;
    f.name = "f" + std::to_string(i);
    f.material = "m";
    f.radius = 0.05;
    f.elements = 40;
    const Vec3 o((i % side) * 1.0, (i / side) * 1.0, 0);
    f.geometry.points = {o, o + Vec3(0, 0, 10)};
    s.fibres.push_back(f);
    BcDef c;
    c.group = f.name + ".start";
    s.bcs.push_back(c);
    s.loads.push_back({LoadKind::Force, f.name + ".end", Vec3(1e-3, 5e-4, 0), {{0, 1}, {0, 1}}});
  }
  s.steps.push_back(StepDef{});
  return s;
}

void assemble(WorldState& w) { runStage(w, w.pipeline.assemble, 1, true); }

// The same tangent rebuilt from triplets (what a scatter into a fixed pattern avoids).
double tripletRebuild(WorldState& w, int repeats) {
  std::vector<Eigen::Triplet<double>> trip;
  SparseMatrix K(w.system.freeCount, w.system.freeCount);
  return bench::median(repeats, [&] {
    trip.clear();
    for (Index e = 0; e < w.fibres.elements(); ++e) {
      const Index d0 = kNodeDofs * w.fibres.elementFirstNode[e];
      ElementVector<2> f;
      ElementMatrix<2> Ke;
      beamElement<2>(elementPoints(w.beams, e), w.fibres.q.segment<27>(d0), f, &Ke);
      for (int i = 0; i < 27; ++i)
        for (int j = 0; j < 27; ++j) {
          const Index I = w.system.equation[d0 + i], J = w.system.equation[d0 + j];
          if (I >= 0 && J >= 0 && I <= J) trip.emplace_back(I, J, Ke(i, j));
        }
    }
    K.setFromTriplets(trip.begin(), trip.end());
  });
}

struct Row {
  int fibres, threads;
  Index dofs, nonzeros;
  double assemble, factorise, solve, triplets;
};

Row measure(int fibres, int threads, int repeats) {
  bench::setBlasThreads(threads);
  tbb::task_arena arena(threads);
  WorldState w;
  w.scene = fibresScene(fibres);
  w.def.arena = &arena;
  buildWorld(w);
  if (advance(w).status != StepStatus::Converged) std::fprintf(stderr, "warning: load step failed\n");
  assemble(w);
  Row r{fibres, threads, w.system.freeCount, Index(w.system.K.nonZeros()), 0, 0, 0, 0};
  r.assemble = bench::median(repeats, [&] { assemble(w); });
  std::string msg;
  w.solver.factorise(w.system, msg);  // analysis once, outside the timing
  r.factorise = bench::median(repeats, [&] { w.solver.factorise(w.system, msg); });
  if (w.solver.stats().fallbacks > 0) std::fprintf(stderr, "warning: LDL^T fallback used\n");
  Eigen::VectorXd b = Eigen::VectorXd::Ones(w.system.freeCount), x;
  r.solve = bench::median(repeats, [&] { w.solver.solve(b, x); });
  r.triplets = tripletRebuild(w, repeats);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  int repeats = 7;
  std::string csv = "newton_iteration.csv";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--csv")) csv = argv[i + 1];
  }
  std::FILE* out = bench::openCsv(
      csv, "fibres,threads,dofs,nonzeros,assemble_ms,factorise_ms,solve_ms,iteration_ms,"
           "triplet_rebuild_ms");
  std::printf("%7s %7s %9s %10s %11s %12s %9s %12s %14s\n", "fibres", "threads", "dofs",
              "nonzeros", "assemble ms", "factorise ms", "solve ms", "iteration ms",
              "triplets ms");
  for (int fibres : {1, 1000})
    for (int threads : {1, 2}) {
      const Row r = measure(fibres, threads, repeats);
      const double it = r.assemble + r.factorise + r.solve;
      std::printf("%7d %7d %9d %10d %11.3f %12.3f %9.3f %12.3f %14.3f\n", r.fibres, r.threads,
                  r.dofs, r.nonzeros, 1e3 * r.assemble, 1e3 * r.factorise, 1e3 * r.solve,
                  1e3 * it, 1e3 * r.triplets);
      if (out)
        std::fprintf(out, "%d,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f\n", r.fibres, r.threads, r.dofs,
                     r.nonzeros, 1e3 * r.assemble, 1e3 * r.factorise, 1e3 * r.solve, 1e3 * it,
                     1e3 * r.triplets);
    }
  if (out) std::fclose(out);
  return 0;
}
