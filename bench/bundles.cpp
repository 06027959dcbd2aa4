// Dense frictional bundles: does every increment converge, and at what cost? Hexagonal bundles
// (bench/contact_scenes.h) of 7, 19, 37, 61 fibres (R = 0.1 mm, L = 4 mm), squeezed 0.01 mm
// between two plane tools in 10 increments, or pulled to 0.1% strain and twisted 90 degrees
// under that tension in 10 increments; mu and p_max swept. Per run: the pseudo-time reached,
// converged increments, their Newton iterations (all attempts; mean and max) and cutbacks (a
// failed increment's are given with its message), the largest viscous force of the continuation
// (relative to the reference force: how far from static equilibrium; 0 without --damping), the
// most stick/slip statuses held in an increment, the top tool's force at the last converged
// increment (squeeze: N, along z; the error of a p_max against the finest one), the sum of the
// fibre-fibre friction forces' magnitudes there (N; what held statuses cost), wall time
// and its share per part (assembly, factorisation, solve, the rest: detection, normals,
// penalties, set-up). One markdown table row per run, as docs/RESULTS.md shows them.
//
//   build/bench_bundles [--rings 1,2,3,4] [--load squeeze,twist] [--mu 0.1,0.3]
//                       [--pmax 5e-4,1e-4] [--elements N] [--threads N] [--line-search on|off]
//                       [--damping C]  (viscous continuation on every step, StepDef::damping)
//                       [--hold-after N]  (contact.friction_hold_after; 0: statuses never held)
//                       [--normal-update auto|newton|loop|newton_frictionless]
//                       [--facing on|off]  (contact.facing_particles, default on)
//                       [--end-spin free|held]  (squeeze: the spin of the fibres' held ends;
//                       default free, bench/contact_scenes.h holdEndSpin)
//                       [--increments N]  (of the last step: the squeeze, or the twist)
//                       [--tolerance T]  (every step's forceTolerance, default 1e-8)
//                       [--cycle-damping on|off]  (solver.cycle_damping, default on)
//                       [--detail on|iterations|off]  (a line per increment: its Newton
//                       iterations, the last attempt's, cutbacks, loop A and B passes, restarts,
//                       retries, switches; `iterations` adds a line per Newton iteration on stderr)
#include "core/allocator.h"
#include "bench/bench_util.h"
#include "bench/contact_scenes.h"
#include "engine/world.h"

#include <algorithm>
#include <cstring>
#include <sstream>

using namespace fibra;

namespace {

std::vector<double> parseList(const char* text) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  return v;
}

std::vector<std::string> parseWords(const char* text) {
  std::vector<std::string> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(item);
  return v;
}

struct Outcome {
  double reached = 0, end = 0;
  int increments = 0, iterations = 0, maxIterations = 0, cutbacks = 0;  // converged increments
  double wall = 0, assemble = 0, factorise = 0, solve = 0;
  double viscous = 0;  // largest viscous force / reference force of a converged increment
  int held = 0;        // most elements with a held stick/slip status in an increment
  double toolForce = 0;  // the top tool's force along z at the last converged increment, N
  double friction = 0;   // sum of |friction force| over the fibre-fibre elements there, N
  std::string failure;
};

// One line per increment for --detail: where its Newton iterations went.
void printIncrement(const StepReport& r) {
  const ContactReport& c = r.contact;
  std::printf("  t %.4f: %d iterations (%d in the last attempt), %d cutbacks, %d sub-increments, "
              "loop A %d, loop B %d, restarts %d (normal %d), normal retries %d%s%s, consistency "
              "passes %d, active %d, sliding %d, held %d\n",
              r.time, r.totalIterations, r.iterations, r.cutbacks, r.subIncrements,
              c.detectionLoops, c.normalLoops, c.restarts, c.normalRestarts, r.normalRetries,
              r.normalsLinearised ? " (linearised)" : "", r.normalsSwitched ? " (switched)" : "", c.consistencyPasses, c.active,
              c.sliding, c.frictionHeld);
  if (r.cutbacks > 0) std::printf("    %s\n", r.message.c_str());
}

Outcome run(const SceneDef& scene, WorldDef def, bool detail, bool iterations) {
  Outcome o;
  if (iterations)
    def.progress = [](const Progress& p) {
      std::fprintf(stderr, "t %.5f it %d residual %.3e step %.3f active %d sliding %d\n", p.time,
                   p.iteration, p.residual, p.stepLength, p.activeElements, p.slidingElements);
    };
  o.end = scene.steps.back().endTime;
  o.wall = bench::seconds([&] {
    World w(scene, def);
    while (!w.finished()) {
      const StepReport r = w.step();
      o.assemble += r.timings.assemble;
      o.factorise += r.timings.factorise;
      o.solve += r.timings.solve;
      if (r.status != StepStatus::Converged) {
        o.failure = r.message + " (" + std::to_string(r.totalIterations) + " iterations)";
        break;
      }
      if (detail) printIncrement(r);
      ++o.increments;
      o.iterations += r.totalIterations;
      o.cutbacks += r.cutbacks;
      o.maxIterations = std::max(o.maxIterations, r.totalIterations);
      o.viscous = std::max(o.viscous, r.viscousForce);
      o.held = std::max(o.held, r.contact.frictionHeld);
    }
    o.reached = w.time();
    if (w.scene().tools.size() > 1) o.toolForce = w.toolReaction(1).z();
    const ContactSnapshot c = w.contactSnapshot();
    for (Index e = 0; e < c.size(); ++e)
      if (!c.tool[e]) o.friction += Vec3(c.friction[e]).norm();
  });
  return o;
}

void printRow(const char* load, size_t fibres, int elements, double mu, double pMax,
              const Outcome& o) {
  const double other = o.wall - o.assemble - o.factorise - o.solve;
  const auto share = [&](double x) { return 100 * x / o.wall; };
  std::printf("| %s | %zu x %d | %.1f | %.0e | %s | %d | %.1f / %d | %d | %.1e | %d | %.6g | %.6g | %.1f | %.0f / %.0f / %.0f / %.0f |\n",
              load, fibres, elements, mu, pMax,
              o.failure.empty() ? "yes" : ("no, t = " + std::to_string(o.reached)).c_str(),
              o.increments, o.increments ? double(o.iterations) / o.increments : 0.0,
              o.maxIterations, o.cutbacks, o.viscous, o.held, o.toolForce, o.friction, o.wall, share(o.assemble), share(o.factorise),
              share(o.solve), share(other));
  if (!o.failure.empty()) std::printf("  failure: %s\n", o.failure.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  std::vector<double> rings{1, 2}, mus{0.1, 0.3}, pMaxes{5e-4, 1e-4};
  std::vector<std::string> loads{"squeeze", "twist"};
  int elements = 10;
  bool lineSearch = false;
  bool cycleDamping = SolverDef{}.cycleDamping;
  double damping = 0;
  int holdAfter = ContactDef{}.frictionHoldAfter;
  bool facing = ContactDef{}.facingParticles;
  bool heldSpin = false;
  bool detail = false, iterations = false;
  int increments = 0;        // 0: the scene's
  double tolerance = 0;      // 0: the step's forceTolerance
  NormalUpdate normalUpdate = ContactDef{}.normalUpdate;
  WorldDef def;
  def.threads = 2;
  const char* known[] = {"--rings", "--mu", "--pmax", "--load", "--elements", "--threads",
                         "--line-search", "--cycle-damping", "--damping", "--hold-after",
                         "--normal-update", "--facing", "--end-spin", "--increments",
                         "--tolerance", "--detail"};
  for (int i = 1; i < argc; i += 2) {
    const bool ok = std::any_of(std::begin(known), std::end(known),
                                [&](const char* k) { return !std::strcmp(argv[i], k); });
    if (!ok || i + 1 == argc) {
      std::fprintf(stderr, "bench_bundles: %s '%s'; options (each with a value):",
                   ok ? "no value after" : "unknown option", argv[i]);
      for (const char* k : known) std::fprintf(stderr, " %s", k);
      std::fprintf(stderr, "\n");
      return 2;
    }
  }
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--rings")) rings = parseList(argv[i + 1]);
    if (!std::strcmp(argv[i], "--mu")) mus = parseList(argv[i + 1]);
    if (!std::strcmp(argv[i], "--pmax")) pMaxes = parseList(argv[i + 1]);
    if (!std::strcmp(argv[i], "--load")) loads = parseWords(argv[i + 1]);
    if (!std::strcmp(argv[i], "--elements")) elements = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--threads")) def.threads = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--line-search")) lineSearch = !std::strcmp(argv[i + 1], "on");
    if (!std::strcmp(argv[i], "--cycle-damping")) cycleDamping = !std::strcmp(argv[i + 1], "on");
    if (!std::strcmp(argv[i], "--damping")) damping = std::atof(argv[i + 1]);
    if (!std::strcmp(argv[i], "--hold-after")) holdAfter = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--normal-update"))
      normalUpdate = !std::strcmp(argv[i + 1], "loop")     ? NormalUpdate::Loop
                     : !std::strcmp(argv[i + 1], "newton") ? NormalUpdate::Newton
                     : !std::strcmp(argv[i + 1], "auto")   ? NormalUpdate::Auto
                                                           : NormalUpdate::NewtonFrictionless;
    if (!std::strcmp(argv[i], "--facing")) facing = !std::strcmp(argv[i + 1], "on");
    if (!std::strcmp(argv[i], "--end-spin")) heldSpin = !std::strcmp(argv[i + 1], "held");
    if (!std::strcmp(argv[i], "--increments")) increments = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--tolerance")) tolerance = std::atof(argv[i + 1]);
    if (!std::strcmp(argv[i], "--detail")) {
      iterations = !std::strcmp(argv[i + 1], "iterations");
      detail = iterations || !std::strcmp(argv[i + 1], "on");
    }
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::printf("threads %d, line search %s, cycle damping %s, damping %g, friction_hold_after %d, "
              "facing particles %s, normal update %s, squeezed fibres' end spin %s\n\n",
              def.threads, lineSearch ? "on" : "off", cycleDamping ? "on" : "off", damping,
              holdAfter, facing ? "on" : "off",
              normalUpdate == NormalUpdate::Loop     ? "loop"
              : normalUpdate == NormalUpdate::Newton ? "newton"
              : normalUpdate == NormalUpdate::Auto   ? "auto"
                                                     : "newton_frictionless",
              heldSpin ? "held" : "free");
  std::printf("| load | fibres x elements | mu | p_max mm | converged | increments | iterations "
              "per increment, mean / max | cutbacks | viscous force, max | held statuses, max | "
              "tool force N | friction sum N | wall s | %% asm / fac / sol / other |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (double r : rings)
    for (const std::string& load : loads)
      for (double mu : mus)
        for (double p : pMaxes) {
          SceneDef s = load == "twist" ? scenes::twistedBundle(int(r), elements, p, mu)
                                       : scenes::bundle(int(r), elements, 0.01, p, mu);
          if (heldSpin && load != "twist") scenes::holdEndSpin(s);
          if (increments > 0) s.steps.back().increments = increments;
          if (tolerance > 0)
            for (StepDef& st : s.steps) st.forceTolerance = tolerance;
          for (StepDef& st : s.steps) st.lineSearch = lineSearch, st.damping = damping;
          s.solver.cycleDamping = cycleDamping;
          s.contact.frictionHoldAfter = holdAfter;
          s.contact.normalUpdate = normalUpdate;
          s.contact.facingParticles = facing;
          printRow(load.c_str(), s.fibres.size(), elements, mu, p, run(s, def, detail, iterations));
        }
}
