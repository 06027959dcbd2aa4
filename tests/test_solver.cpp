// Solver: the assembled tangent (beams, moment loads, held DOFs) against finite differences of
// the assembled residual; determinism across thread counts; cutbacks, failure and cancellation
// reported and never silently accepted; task-graph edges from declared accesses.
#include "beam_fixtures.h"
#include "engine/world_state.h"

#include <doctest/doctest.h>

#include <random>

using namespace fibra;
using namespace fibra::test;

namespace {

// Two fibres (a helix and a polyline), moment and force loads, a clamp and a partial fix.
SceneDef mixedScene(int increments) {
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 0.5, 0.8});
  FibreDef h;
  h.name = "h";
  h.material = "m";
  h.radius = 0.05;
  h.elements = 8;
  h.geometry.kind = GeometryKind::Helix;
  h.geometry.helixRadius = 0.5;
  h.geometry.pitch = 2;
  h.geometry.turns = 1.2;
  s.fibres.push_back(h);
  FibreDef p;
  p.name = "p";
  p.material = "m";
  p.radius = 0.08;
  p.elements = 6;
  p.order = 1;
  p.geometry.kind = GeometryKind::Polyline;
  p.geometry.points = {Vec3(2, 0, 0), Vec3(4, 0.5, 0), Vec3(6, 0, 1)};
  s.fibres.push_back(p);
  for (const char* g : {"h.start", "p.start"}) {
    BcDef c;
    c.group = g;
    s.bcs.push_back(c);
  }
  BcDef fix;
  fix.kind = BcKind::Fix;
  fix.group = "p.end";
  fix.dofs[Y] = fix.dofs[G1Z] = true;
  s.bcs.push_back(fix);
  s.loads.push_back({LoadKind::Moment, "h.end", Vec3(0.0002, -0.0001, 0.0003), {{0, 1}, {0, 1}}});
  s.loads.push_back({LoadKind::Force, "h.end", Vec3(0.001, 0.002, -0.001), {{0, 1}, {0, 1}}});
  s.loads.push_back({LoadKind::Moment, "p.end", Vec3(0, 0.0004, 0), {{0, 1}, {0, 1}}});
  StepDef st;
  st.increments = increments;
  s.steps.push_back(st);
  return s;
}

void assemble(WorldState& w, bool tangent) { runStage(w, w.pipeline.assemble, 1, tangent); }

// Toy systems for the task graph: what they read and write is in their signatures.
struct Store {
  int value = 0;
};
void writeA(Store& a) { a.value = 1; }
void readAWriteB(const Store& a, Store& b) { b.value = a.value + 1; }
void readAWriteC(const Store& a, Store& c) { c.value = a.value + 2; }
void readBC(const Store& b, const Store& c, Store& d) { d.value = b.value * c.value; }
struct Whole {
  Store part;
};
void readWhole(const Whole& w, Store& out) { out.value = w.part.value; }

}  // namespace

TEST_CASE("assembled tangent with moment loads matches central finite differences") {
  WorldState w;
  w.scene = mixedScene(1);
  buildWorld(w);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Index i = 0; i < w.system.freeCount; ++i) w.fibres.q(w.system.dofOf[i]) += u(rng);
  assemble(w, true);
  const Eigen::MatrixXd K = Eigen::MatrixXd(w.system.K).selfadjointView<Eigen::Upper>();
  Eigen::MatrixXd Kfd(w.system.freeCount, w.system.freeCount);
  const double h = 1e-6;
  for (Index j = 0; j < w.system.freeCount; ++j) {
    const Index d = w.system.dofOf[j];
    Eigen::VectorXd rp, rm;
    w.fibres.q(d) += h;
    assemble(w, false);
    rp = w.system.r;
    w.fibres.q(d) -= 2 * h;
    assemble(w, false);
    rm = w.system.r;
    w.fibres.q(d) += h;
    for (Index i = 0; i < w.system.freeCount; ++i)
      Kfd(i, j) = (rp(w.system.dofOf[i]) - rm(w.system.dofOf[i])) / (2 * h);
  }
  CHECK((K - Kfd).norm() <= 1e-6 * K.norm());
}

TEST_CASE("the same scene gives bitwise the same state with 1 and 2 threads") {
  const SceneDef s = mixedScene(4);
  World one(s, {.threads = 1}), two(s, {.threads = 2});
  REQUIRE(solveAll(one));
  REQUIRE(solveAll(two));
  CHECK(one.fibres().q.cwiseNotEqual(two.fibres().q).count() == 0);
  CHECK(one.residual().cwiseNotEqual(two.residual()).count() == 0);
}

extern "C" int openblas_get_num_threads();

TEST_CASE("a world's thread setting also sets the BLAS threads of its factorisations") {
  BeamSpec b;
  SceneDef s = straightBeam(b, 1);
  clampStart(s);
  tipLoad(s, LoadKind::Force, Vec3(0, -0.01, 0));
  for (int threads : {1, 2}) {
    World w(s, {.threads = threads});
    REQUIRE(w.step().status == StepStatus::Converged);
    CHECK(openblas_get_num_threads() == threads);
  }
}

TEST_CASE("an increment too large is rescued by cutbacks, and the report says so") {
  BeamSpec b;
  b.radius = 0.01;
  SceneDef s = straightBeam(b, 1);
  clampStart(s);
  tipLoad(s, LoadKind::Moment, Vec3(0, 0, 2 * std::numbers::pi * bendingStiffness(b) / b.length));
  World w(s);
  const StepReport r = w.step();
  CHECK(r.status == StepStatus::Converged);
  CHECK(r.cutbacks >= 1);
  CHECK(r.message.find("cutback") != std::string::npos);
  CHECK(tipPosition(w).norm() < 0.005 * b.length);
}

TEST_CASE("a failed increment leaves the last converged state and says why") {
  BeamSpec b;
  b.radius = 0.01;
  SceneDef s = straightBeam(b, 1);
  s.steps[0].maxCutbacks = 0;
  s.steps[0].maxIterations = 5;
  clampStart(s);
  tipLoad(s, LoadKind::Moment, Vec3(0, 0, 2 * std::numbers::pi * bendingStiffness(b) / b.length));
  World w(s);
  const Eigen::VectorXd before = w.fibres().q;
  const StepReport r = w.step();
  CHECK(r.status == StepStatus::Failed);
  CHECK(r.message.find("no convergence in 5 iterations") != std::string::npos);
  CHECK(w.fibres().q == before);
  CHECK(w.time() == 0);
  CHECK_FALSE(w.finished());
}

TEST_CASE("cancellation stops at the last converged state") {
  BeamSpec b;
  SceneDef s = straightBeam(b, 4);
  clampStart(s);
  tipLoad(s, LoadKind::Force, Vec3(0, -0.03, 0));
  int iterations = 0;
  WorldDef def;
  def.progress = [&](const Progress&) { ++iterations; };
  def.cancel = [&] { return iterations >= 3; };
  World w(s, def);
  const StepReport r = w.step();
  CHECK(r.status == StepStatus::Cancelled);
  CHECK(w.time() == 0);
  CHECK(w.fibres().q == w.fibres().qRef);
}

TEST_CASE("task graph edges follow the reads and writes of the systems' signatures") {
  Store a, b, c, d;
  StoreNames names;
  names.add(a, "a"), names.add(b, "b"), names.add(c, "c"), names.add(d, "d");
  TaskGraph g(&names);
  g.add("write a", writeA, a);                // 0
  g.add("read a write b", readAWriteB, a, b); // 1: after 0 (read after write)
  g.add("read a write c", readAWriteC, a, c); // 2: after 0 only: beside 1
  g.add("write a again", writeA, a);          // 3: after 0 (write after write), 1, 2 (after read)
  g.add("read b and c", readBC, b, c, d);     // 4: after 1 and 2
  g.build();
  CHECK(g.reads(1) == std::vector<std::string>{"a"});
  CHECK(g.writes(1) == std::vector<std::string>{"b"});
  CHECK(g.predecessors(1) == std::vector<int>{0});
  CHECK(g.predecessors(2) == std::vector<int>{0});
  CHECK(g.predecessors(3) == std::vector<int>{0, 1, 2});
  CHECK(g.predecessors(4) == std::vector<int>{1, 2});
  CHECK_FALSE(g.ordered(1, 2));
  CHECK(g.ordered(0, 4));
  g.run(nullptr);
  CHECK(d.value == 2 * 3);
  Store unnamed;
  CHECK_THROWS_AS(g.add("unnamed", writeA, unnamed), std::logic_error);

  // A part of a store bound on its own counts as the whole store for the edges.
  Whole whole;
  Store out;
  names.add(whole, "whole"), names.addPart(whole.part, "whole.part", whole), names.add(out, "out");
  TaskGraph h(&names);
  h.add("read the whole", readWhole, whole, out);  // 0
  h.add("write the part", writeA, whole.part);      // 1: after 0 (write after read)
  h.build();
  CHECK(h.predecessors(1) == std::vector<int>{0});
  CHECK(h.writes(1) == std::vector<std::string>{"whole.part"});
}

TEST_CASE("a larger scene splits across threads and still gives bitwise the same state") {
  // 48 helical springs loaded onto a plane tool: parallel beam assembly, tool contact and the
  // contact loops run with 2 threads.
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  for (int i = 0; i < 48; ++i) {
    FibreDef f;
    f.name = "f" + std::to_string(i);
    f.material = "m";
    f.radius = 0.05;
    f.elements = 12;
    f.geometry.kind = GeometryKind::Helix;
    f.geometry.origin = Vec3(1.5 * (i % 8), 1.5 * (i / 8), 0.56);
    f.geometry.axis = Vec3::UnitX();
    f.geometry.helixRadius = 0.5;
    f.geometry.pitch = 1;
    f.geometry.turns = 3;
    s.fibres.push_back(f);
    BcDef c;
    c.group = f.name + ".start";
    s.bcs.push_back(c);
    s.loads.push_back({LoadKind::Force, f.name + ".end", Vec3(0, 0, -0.002), {{0, 1}, {0, 1}}});
  }
  ToolDef plane;
  plane.name = "floor";
  s.tools.push_back(plane);
  StepDef st;
  st.increments = 2;
  s.steps.push_back(st);
  World one(s, {.threads = 1}), two(s, {.threads = 2});
  REQUIRE(solveAll(one));
  REQUIRE(solveAll(two));
  CHECK(one.fibres().q.cwiseNotEqual(two.fibres().q).count() == 0);
  CHECK(one.toolReaction(0) == two.toolReaction(0));
  CHECK(one.toolReaction(0).z() < 0);
}
