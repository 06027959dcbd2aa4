// Speed against error for the cantilever under a dead tip load (PL^2/EI = 3, L/R = 100 and
// 1000): elements per fibre x element order x axial rule x section integration -> tip error
// against the elastica, Newton iterations, set-up time and solve time (medians); then a
// helical spring, where the two section rules differ.
//
//   build/bench_cantilever [--repeats N] [--csv FILE]
#include "core/allocator.h"
#include "bench/bench_util.h"
#include "bench/elastica.h"
#include "engine/world.h"

#include <cmath>
#include <cstring>
#include <numbers>

using namespace fibra;

namespace {

struct Config {
  int elements, order;
  AxialRule axial;
  SectionRule section;
  double slenderness;
};

SceneDef cantilever(const Config& c, double lambda) {
  const double L = 10, R = L / c.slenderness, E = 4000;
  const double EI = E * std::numbers::pi * std::pow(R, 4) / 4;
  SceneDef s;
  s.materials.push_back({"m", E, 0.3, 1, 1});
  FibreDef f;
  f.name = "b";
  f.material = "m";
  f.radius = R;
  f.elements = c.elements;
  f.order = c.order;
  f.geometry.points = {Vec3::Zero(), Vec3(L, 0, 0)};
  f.integration = {c.axial, c.section, 3, 8};
  s.fibres.push_back(f);
  BcDef clamp;
  clamp.group = "b.start";
  s.bcs.push_back(clamp);
  s.loads.push_back({LoadKind::Force, "b.end", Vec3(0, -lambda * EI / (L * L), 0), {{0, 1}, {0, 1}}});
  StepDef st;
  st.increments = 10;
  s.steps.push_back(st);
  return s;
}

struct Result {
  double error = NAN, setup = 0, solve = 0;
  int iterations = 0;
  bool converged = true;
};

Result run(const Config& c, double lambda, const Eigen::Vector2d& ref, int repeats) {
  Result r;
  const SceneDef scene = cantilever(c, lambda);
  r.setup = bench::median(repeats, [&] { World w(scene, {.threads = 1}); });
  r.solve = bench::median(repeats, [&] {
    World w(scene, {.threads = 1});
    r.iterations = 0;
    while (!w.finished()) {
      const StepReport rep = w.step();
      r.iterations += rep.totalIterations;
      if (rep.status != StepStatus::Converged) {
        r.converged = false;
        return;
      }
    }
    const Vec3 tip = x0Of(w.fibres().q, w.fibres().nodes() - 1);
    const double L = 10;
    r.error = std::max(std::abs((L - tip.x()) / (L * (1 - ref.x())) - 1),
                       std::abs(tip.y() / (L * ref.y()) - 1));
  });
  r.solve -= r.setup;
  return r;
}

// A helical spring (coil radius 1 mm, pitch 1 mm, 3 turns, wire R = 0.1 mm: curvature x R =
// 0.1) pulled along its axis: where the section rules differ (the reference metric varies over
// a curved section). Returns the tip's axial displacement.
double helixTip(const BeamIntegration& integ, double& seconds) {
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  FibreDef f;
  f.name = "h";
  f.material = "m";
  f.radius = 0.1;
  f.elements = 48;
  f.geometry.kind = GeometryKind::Helix;
  f.geometry.helixRadius = 1;
  f.geometry.pitch = 1;
  f.geometry.turns = 3;
  f.integration = integ;
  s.fibres.push_back(f);
  BcDef clamp;
  clamp.group = "h.start";
  s.bcs.push_back(clamp);
  s.loads.push_back({LoadKind::Force, "h.end", Vec3(0, 0, 0.01), {{0, 1}, {0, 1}}});
  s.steps.push_back(StepDef{});
  double tip = 0;
  seconds = bench::median(3, [&] {
    World w(s, {.threads = 1});
    w.step();
    const Index n = w.fibres().nodes() - 1;
    tip = x0Of(w.fibres().q, n).z() - x0Of(w.fibres().qRef, n).z();
  });
  return tip;
}

void helixTable() {
  double t;
  const double ref = helixTip({AxialRule::Reduced, SectionRule::Quadrature, 4, 32}, t);
  std::printf("\nhelical spring, axial tip displacement against quadrature 4 x 32 (%.6e mm)\n", ref);
  std::printf("%22s %12s %9s\n", "section rule", "rel. diff", "time ms");
  const std::pair<const char*, BeamIntegration> rules[] = {
      {"moments", {AxialRule::Reduced, SectionRule::Moments, 3, 8}},
      {"quadrature 2 x 6", {AxialRule::Reduced, SectionRule::Quadrature, 2, 6}},
      {"quadrature 3 x 8", {AxialRule::Reduced, SectionRule::Quadrature, 3, 8}},
      {"quadrature 4 x 16", {AxialRule::Reduced, SectionRule::Quadrature, 4, 16}}};
  for (const auto& [name, integ] : rules) {
    const double tip = helixTip(integ, t);
    std::printf("%22s %12.3e %9.3f\n", name, tip / ref - 1, 1e3 * t);
  }
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  int repeats = 3;
  std::string csv = "cantilever.csv";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--csv")) csv = argv[i + 1];
  }
  bench::setBlasThreads(1);
  const double lambda = 3;
  const Eigen::Vector2d ref = elasticaTip(lambda);
  std::FILE* out = bench::openCsv(csv, "slenderness,order,axial,section,elements,tip_error,"
                                       "newton_iterations,setup_ms,solve_ms");
  std::printf("%6s %5s %8s %10s %4s %11s %6s %9s %9s\n", "L/R", "order", "axial", "section",
              "n_e", "tip error", "iters", "setup ms", "solve ms");
  for (double slenderness : {100.0, 1000.0})
    for (int order : {2, 1})
      for (AxialRule axial : {AxialRule::Reduced, AxialRule::Full})
        for (SectionRule section : {SectionRule::Moments, SectionRule::Quadrature})
          for (int n : {2, 4, 8, 16, 32, 64}) {
            const Config c{n, order, axial, section, slenderness};
            const Result r = run(c, lambda, ref, repeats);
            const char* ax = axial == AxialRule::Reduced ? "reduced" : "full";
            const char* sec = section == SectionRule::Moments ? "moments" : "quadrature";
            std::printf("%6.0f %5d %8s %10s %4d %11.3e %6d %9.3f %9.3f%s\n", slenderness, order,
                        ax, sec, n, r.error, r.iterations, 1e3 * r.setup, 1e3 * r.solve,
                        r.converged ? "" : "  (did not converge)");
            if (out)
              std::fprintf(out, "%.0f,%d,%s,%s,%d,%.6e,%d,%.4f,%.4f\n", slenderness, order, ax,
                           sec, n, r.error, r.iterations, 1e3 * r.setup, 1e3 * r.solve);
          }
  if (out) std::fclose(out);
  helixTable();
  return 0;
}
