// Initial geometry by forced normals (paper section 5.2.1, docs/CONTACT.md): between fibres of
// different contact classes with different levels, a step with forced_normals sets N = +-D,
// oriented by the levels. Checks: fibres whose centrelines cross (distance 0) keep their contact
// elements with the forced orientation and the gap measured along it; the contact tangent under
// forced normals matches central finite differences (with friction, in stick and in slip); the
// sample samples/forced_normals.json (two flat interpenetrating yarns) ends its forced step with
// the over yarn above the other and the centrelines apart by at least R_I + R_J - p_max,
// measured from the nodes alone, and the step with the normal rules after it converges; a flat
// 2 x 2 plain weave whose pattern is in the warp fibres' level tables ends its forced step with
// every crossing in the pattern's order, within p_max; the sample's state hashes the same with
// 1, 2 and 4 threads.
#include "centreline_measure.h"
#include "contact_scenes.h"
#include "engine/world_state.h"
#include "fd_tangent.h"
#include "io/scene_loader.h"
#include "store_bits.h"

#include <doctest/doctest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <utility>

using namespace fibra;
using namespace fibra::test;

namespace {

// Two fibres crossing at 90 degrees in the plane z = 0 (centrelines cut at the origin), of
// classes "a" (level levelA) and "b" (level 0), held at their ends; the first step forces the
// normals along +z.
SceneDef cutCrossing(double levelA, double mu) {
  SceneDef s = crossingBeams(0.01, 1e-3);
  s.fibres[1].geometry.points = {Vec3(0, -2, 0), Vec3(0, 2, 0)};
  s.fibres[0].contactClass = "a";
  s.fibres[1].contactClass = "b";
  s.fibres[0].levels = {{0, levelA}};
  s.contact.friction = mu;
  s.contact.maxReversibleSlip = 5e-4;
  s.steps[0].forcedNormal = Vec3::UnitZ();
  return s;
}

// Detection at the start of the forced step, with the overlap it allows (mm).
void detectForced(WorldState& w, const SceneDef& s, double allowance = 0) {
  w.scene = s;
  buildWorld(w);
  w.contact.forcedNormal = s.steps[0].forcedNormal;
  w.contact.forcedAllowance = allowance;
  runStage(w, w.pipeline.detect, 0);
}

void assembleAt(WorldState& w, bool tangent) { runStage(w, w.pipeline.assemble, 0, tangent); }

using test::centreline;
using test::Closest;
using test::closestApproach;

// A 2 x 2 plain weave of single-fibre yarns, flat: warp i along x at y = -0.5 + i, weft j along
// y at x = -0.5 + j, all in z = 0, 4 mm long (s = coordinate + 2), R = 0.1 mm. The pattern is in
// the warp fibres' level tables: warp i lies over weft j where (i + j) is even (level +1 on the
// piece holding that crossing), under it otherwise (-1); the weft fibres keep level 0. Each
// fibre is held at its start (and against spin) and pulled at its end by 0.01 N along its axis.
SceneDef plainWeave() {
  const int kWeaveElements = 40;
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  for (int i = 0; i < 2; ++i) {
    const double c = -0.5 + i;
    FibreDef warp = straightFibre("warp" + std::to_string(i), Vec3(-2, c, 0), Vec3(2, c, 0), 0.1,
                                  kWeaveElements, Vec3::UnitZ());
    warp.contactClass = "warp";
    const double first = i % 2 == 0 ? 1 : -1;  // at weft 0 (s = 1.5), then the opposite
    warp.levels = {{0, first}, {2, -first}};
    FibreDef weft = straightFibre("weft" + std::to_string(i), Vec3(c, -2, 0), Vec3(c, 2, 0), 0.1,
                                  kWeaveElements, Vec3::UnitZ());
    weft.contactClass = "weft";
    s.fibres.push_back(warp);
    s.fibres.push_back(weft);
    hold(s, warp.name + ".start", {X, Y, Z, G1Y});
    hold(s, warp.name + ".end", {Y, Z});
    hold(s, weft.name + ".start", {X, Y, Z, G1X});
    hold(s, weft.name + ".end", {X, Z});
    s.loads.push_back({LoadKind::Force, warp.name + ".end", Vec3(0.01, 0, 0), {{0, 2}, {1, 1}}});
    s.loads.push_back({LoadKind::Force, weft.name + ".end", Vec3(0, 0.01, 0), {{0, 2}, {1, 1}}});
  }
  s.contact.enabled = true;
  s.contact.maxPenetration = 5e-4;
  StepDef forced, plain;
  forced.increments = 4;
  forced.forcedNormal = Vec3::UnitZ();
  plain.endTime = 2;
  s.steps = {forced, plain};
  return s;
}

}  // namespace

TEST_CASE("centrelines that cut each other keep their contact elements under forced normals") {
  for (double levelA : {1.0, -1.0}) {
    CAPTURE(levelA);
    WorldState w;
    detectForced(w, cutCrossing(levelA, 0));
    const ContactElementStore& el = w.trial.elements;
    REQUIRE(w.trial.zones.size() == 1);  // one zone: the crossing, not dropped
    REQUIRE(el.size() >= 1);
    const double R = 0.1;
    for (Index e = 0; e < el.size(); ++e) {
      CAPTURE(e);
      REQUIRE(el.fibreI[e] == 0);  // A is I: N = +z when A's level is the higher
      CHECK(el.forced[e] == int(levelA));  // the sign, kept for loop B and the law
      CHECK((el.normal[e] - levelA * Vec3::UnitZ()).norm() < 1e-15);
      // Both centrelines lie in z = 0: the gap along the forced normal is -(R_I + R_J).
      CHECK(std::abs(el.gap[e] + 2 * R) < 1e-12);
    }
    // The normal update of loop B keeps them.
    runStage(w, w.pipeline.normals, 0);
    for (Index e = 0; e < el.size(); ++e)
      CHECK((el.normal[e] - levelA * Vec3::UnitZ()).norm() < 1e-15);
  }
}

TEST_CASE("the normal rules come back for equal levels and for fibres of one class") {
  SceneDef s = cutCrossing(0, 0);  // equal levels
  s.fibres[1].geometry.points = {Vec3(0, -2, 0.15), Vec3(0, 2, 0.15)};  // B above, penetrating
  // A third fibre 50 mm away, of its own class and level: a scene where no pair could be forced
  // is refused (tests/test_contact_classes.cpp); this one has such pairs, A-B is not one.
  FibreDef far = s.fibres[0];
  far.name = "C";
  far.contactClass = "c";
  far.levels = {{0, 1}};
  for (Vec3& p : far.geometry.points) p.y() += 50;
  s.fibres.push_back(far);
  for (bool sameClass : {false, true}) {
    CAPTURE(sameClass);
    if (sameClass) s.fibres[0].levels = {{0, 1}}, s.fibres[1].contactClass = "a";
    WorldState w;
    detectForced(w, s);
    const ContactElementStore& el = w.trial.elements;
    REQUIRE(el.size() >= 1);
    for (Index e = 0; e < el.size(); ++e) {  // eq. 10: from J (B, above) to I (A): -z
      CHECK(el.forced[e] == 0);
      CHECK((el.normal[e] + Vec3::UnitZ()).norm() < 1e-9);
    }
  }
}

TEST_CASE("contact tangent under forced normals matches finite differences, in stick and in slip") {
  // With an allowance a (the gap widened by a constant), the same penetration a lower lift.
  for (const auto& [slide, allowance] : {std::pair{1e-5, 0.0}, {3e-3, 0.0}, {1e-5, 0.05}, {3e-3, 0.05}}) {
    CAPTURE(slide);
    CAPTURE(allowance);
    WorldState w;
    detectForced(w, cutCrossing(1, 0.3), allowance);
    // the detection and loop B measure the crossing's gap with the allowance: -2R + a
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) runStage(w, w.pipeline.normals, 0);
      for (Index e = 0; e < w.trial.elements.size(); ++e)
        CHECK(std::abs(w.trial.elements.gap[e] - (-0.2 + allowance)) < 1e-12);
    }
    // Lift A part of the way out of B and slide it: penetrating, with friction.
    for (Index n = w.fibres.firstNode[0]; n < w.fibres.firstNode[0] + w.fibres.nodeCount[0]; ++n)
      x0Of(w.fibres.q, n) += Vec3(0.3 * slide, slide, 0.2 - 6e-4 - allowance);
    assembleAt(w, true);
    const ContactForceStore& f = w.trial.forces;
    REQUIRE(f.size() > 0);
    Index loaded = 0;
    for (Index e = 0; e < f.size(); ++e) loaded += f.normalForce[e] > 0;
    REQUIRE(loaded > 0);
    for (Index e = 0; e < f.size(); ++e)  // the centres 0.2 - 6e-4 - a apart along +z
      if (f.normalForce[e] > 0) CHECK(std::abs(f.gap[e] + 6e-4) < 1e-9);
    bool slips = false;
    for (Index e = 0; e < f.size(); ++e) slips = slips || f.slip[e];
    CHECK(slips == (slide > 1e-3));
    const Eigen::MatrixXd K(w.system.K);
    const Eigen::MatrixXd Kfd = test::finiteDifferenceTangent(w, 0);
    CHECK((K - Kfd).norm() <= 1e-6 * K.norm());
  }
}

TEST_CASE("forced normals push two flat interpenetrating yarns apart, the over yarn on top") {
  const SceneDef scene = loadScene(FIBRA_SOURCE_DIR "/samples/forced_normals.json");
  World w(scene);
  const double R = 0.1, pMax = 5e-4;  // the warp-weft pairs take the contact section's p_max
  int increments = 0;
  while (w.currentStep() == 0) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    ++increments;
  }
  CHECK(increments == 4);
  const FibreStore& fs = w.fibres();
  double smallest = 1e300;
  for (Index I = 0; I < 3; ++I)      // warp fibres, along x from x = -2 (s = x + 2)
    for (Index J = 3; J < 6; ++J) {  // weft fibres, along y from y = -2
      CAPTURE(I);
      CAPTURE(J);
      const double xJ = x0Of(fs.qRef, fs.firstNode[J]).x(), yI = x0Of(fs.qRef, fs.firstNode[I]).y();
      const Closest c = closestApproach(fs, fs.q, I, J, xJ + 2, yI + 2);
      CHECK(c.fromJtoI.z() > 0.99 * c.distance);  // the warp fibre lies above, along +z
      CHECK(c.distance >= 2 * R - pMax);
      smallest = std::min(smallest, c.distance);
    }
  MESSAGE("closest warp-weft centrelines after the forced step: "
          << smallest << " mm (2R - p_max = " << 2 * R - pMax << ")");
  Index forcedElements = 0;
  for (const std::int8_t f : w.contact().elements.forced) forcedElements += f != 0;
  CHECK(forcedElements > 0);
  const StepReport r = w.step();  // the normal rules
  REQUIRE(r.status == StepStatus::Converged);
  CHECK(w.finished());
  for (const std::int8_t f : w.contact().elements.forced) CHECK(f == 0);  // its detections' rule
  for (Index I = 0; I < 3; ++I)
    for (Index J = 3; J < 6; ++J) {
      const double xJ = x0Of(fs.qRef, fs.firstNode[J]).x(), yI = x0Of(fs.qRef, fs.firstNode[I]).y();
      const Closest c = closestApproach(fs, fs.q, I, J, xJ + 2, yI + 2);
      CHECK(c.fromJtoI.z() > 0.99 * c.distance);
      CHECK(c.distance >= 2 * R - 1.5 * pMax);
    }
}

TEST_CASE("a forced step's allowance removes the yarns' overlap in equal parts") {
  SceneDef scene = loadScene(FIBRA_SOURCE_DIR "/samples/forced_normals.json");
  const double R = 0.1, pMax = 5e-4;
  const double A = 2 * R;  // the flat start's overlap: the centrelines cut each other
  scene.steps[0].forcedAllowance = A;
  const int n = scene.steps[0].increments;
  World w(scene);
  const FibreStore& fs = w.fibres();
  // The deepest warp-weft overlap 2R - d, d the closest approach of the centrelines (from the
  // nodes alone, independent of the contact elements), and the smallest height of the warp
  // fibre over the weft fibre there.
  const auto deepestOverlap = [&](double& lowestOver) {
    double deepest = -1e300;
    lowestOver = 1e300;
    for (Index I = 0; I < 3; ++I)
      for (Index J = 3; J < 6; ++J) {
        const double xJ = x0Of(fs.qRef, fs.firstNode[J]).x(), yI = x0Of(fs.qRef, fs.firstNode[I]).y();
        const Closest c = closestApproach(fs, fs.q, I, J, xJ + 2, yI + 2);
        deepest = std::max(deepest, 2 * R - c.distance);
        lowestOver = std::min(lowestOver, c.fromJtoI.z());
      }
    return deepest;
  };
  for (int k = 1; k <= n; ++k) {
    CAPTURE(k);
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    // What the step still allows after increment k; the overlap beyond it is the penalty's
    // penetration, about p_max, and the elements report it as such.
    const double allowed = A * (1 - double(k) / n);
    double lowestOver;
    const double overlap = deepestOverlap(lowestOver);
    MESSAGE("increment " << k << ": allowance " << allowed << " mm, deepest overlap " << overlap
                         << " mm, reported penetration " << r.contact.maxPenetration << " mm, "
                         << r.totalIterations << " Newton iterations");
    CHECK(overlap <= allowed + 1.5 * pMax);
    CHECK(overlap >= allowed);
    CHECK(r.contact.maxPenetration <= 1.5 * pMax);
    CHECK(r.contact.redetectGapChange < 0.1);  // the acceptance's fresh gaps with the allowance
    CHECK(lowestOver > 0);  // the warp yarn moved up, the weft yarn down
  }
  CHECK(w.currentStep() == 1);
  double lowestOver;
  CHECK(deepestOverlap(lowestOver) <= pMax);
  REQUIRE(w.step().status == StepStatus::Converged);  // the normal rules
  CHECK(w.finished());
}

TEST_CASE("a step that fails after its cutbacks says what it ran with and what to change") {
  SceneDef scene = loadScene(FIBRA_SOURCE_DIR "/samples/forced_normals.json");
  scene.steps[0].forcedAllowance = 0.2;
  scene.steps[0].maxIterations = 1;
  scene.steps[0].maxCutbacks = 2;
  World w(scene);
  const StepReport r = w.step();
  REQUIRE(r.status == StepStatus::Failed);
  CHECK(r.cutbacks == 3);
  MESSAGE(r.message);
  // the first increment (0.25 of the step's t = 0 .. 1) cut twice, to a quarter each time (one
  // iteration that never lowered the residual: engine/step_driver.cpp, nextIncrement)
  CHECK(r.message.find("failed after 2 cutbacks") != std::string::npos);
  CHECK(r.message.find("the last attempt was an increment of 0.015625;") != std::string::npos);
  CHECK(r.message.find("`increments` (now 4)") != std::string::npos);
  CHECK(r.message.find("`max_iterations` (now 1)") != std::string::npos);
  CHECK(r.message.find("`max_cutbacks` (now 2)") != std::string::npos);
  CHECK(r.message.find("a `damping`") != std::string::npos);
  CHECK(r.message.find("larger `forced_normals.allowance` (now 0.2 mm)") != std::string::npos);
  CHECK(r.message.find("no convergence in 1 iteration ") != std::string::npos);
  // What a resume takes (the checkpoint's fingerprint refuses the rest) comes first: no step
  // has damping, so a damping needs a fresh run, as the increments and the allowance do.
  const std::size_t resume = r.message.find("with `--resume`: a larger `max_iterations`");
  const std::size_t fresh = r.message.find("in a fresh run, also: more `increments`");
  REQUIRE(resume != std::string::npos);
  REQUIRE(fresh != std::string::npos);
  CHECK(resume < fresh);
  CHECK(r.message.find("a `damping`") > fresh);
  CHECK(r.message.find("`forced_normals.allowance`") > fresh);

  // With a damped step a resume takes a new damping too.
  scene.steps[0].damping = 1e-3;
  World damped(scene);
  const StepReport d = damped.step();
  REQUIRE(d.status == StepStatus::Failed);
  MESSAGE(d.message);
  const std::size_t larger = d.message.find("a larger `damping` (now 0.001)");
  REQUIRE(larger != std::string::npos);
  CHECK(larger < d.message.find("in a fresh run, also:"));
}

TEST_CASE("a forced step without an allowance fails at once, with one it cuts back") {
  // Too few iterations for the first increment: without an allowance nothing changes with t,
  // so a smaller increment would repeat the attempt (the message says what to give); with one,
  // a smaller increment pushes less, and the step cuts back.
  SceneDef scene = loadScene(FIBRA_SOURCE_DIR "/samples/forced_normals.json");
  scene.steps[0].maxIterations = 3;
  for (double allowance : {0.0, 0.2}) {
    CAPTURE(allowance);
    scene.steps[0].forcedAllowance = allowance;
    World w(scene);
    const StepReport r = w.step();
    const bool atOnce = r.message.find("would repeat this attempt exactly") != std::string::npos;
    if (allowance == 0) {
      CHECK(r.status == StepStatus::Failed);
      CHECK(atOnce);
      CHECK(r.message.find("forced_normals.allowance") != std::string::npos);
    } else {
      CHECK(!atOnce);
      CHECK(r.cutbacks > 0);
    }
  }
}

TEST_CASE("forced normals weave a flat 2 x 2 plain weave by the warp fibres' level tables") {
  World w(plainWeave());
  const FibreStore& fs = w.fibres();
  const double R = 0.1, pMax = 5e-4;
  for (int step = 0; step < 2; ++step) {
    CAPTURE(step);
    StepReport last;
    while (w.currentStep() == step) {
      last = w.step();
      REQUIRE(last.status == StepStatus::Converged);
    }
    double smallest = 1e300, deepest = -1e300;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        CAPTURE(i);
        CAPTURE(j);
        const Index warp = 2 * i, weft = 2 * j + 1;
        const Closest c = closestApproach(fs, fs.q, warp, weft, 1.5 + j, 1.5 + i);
        const double over = (i + j) % 2 == 0 ? 1 : -1;  // the pattern: warp over weft
        // The yarns slope through the crossings: the closest approach is within 25 deg of +-z.
        CHECK(over * c.fromJtoI.z() > 0.9 * c.distance);
        smallest = std::min(smallest, c.distance);
        deepest = std::max(deepest, test::overlapAt(fs, fs.q, warp, weft, c));
      }
    MESSAGE("step " << step << ": closest warp-weft centrelines " << smallest
                    << " mm, deepest overlap of the deformed sections there " << deepest
                    << " mm; the increment reports a deepest penetration of "
                    << last.contact.maxPenetration << " mm");
    // Forced normals hold every crossing within p_max. With the normal rules the increment's
    // deepest penetration is above p_max (one increment for the whole step), but it is the
    // truth: the sections at the closest approach (their half-widths along the line of centres,
    // flattening included) overlap by at most 1.5x what the elements report. Before the
    // elements nearest the crossings were moved to the closest points (docs/CONTACT.md
    // "Crossings in long zones") the centrelines' overlap was 3.8x that.
    if (step == 0) CHECK(smallest >= 2 * R - pMax);
    if (step == 1) CHECK(deepest <= 1.5 * last.contact.maxPenetration);
  }
}

TEST_CASE("the forced-normal sample hashes the same with 1, 2 and 4 threads") {
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 4);
  const SceneDef scene = loadScene(FIBRA_SOURCE_DIR "/samples/forced_normals.json");
  std::uint64_t reference = 0;
  for (int threads : {1, 2, 4}) {
    CAPTURE(threads);
    World w(scene, {.threads = threads});
    while (!w.finished()) REQUIRE(w.step().status == StepStatus::Converged);
    REQUIRE(w.contact().elements.size() > 0);
    std::uint64_t h = test::hashBits(w.fibres().q);
    h = test::hashBits(w.residual(), h);
    h = test::hashBits(w.contact(), h);
    if (threads == 1) reference = h;
    CHECK(h == reference);
  }
}
