// The stages of an iteration as built for real scenes (engine/pipeline.h): their edges follow
// from the systems' signatures, independent systems are not ordered, the scatter into the
// linear system is a chain in a fixed order, and a scene pays only for what it needs.
#include "contact_scenes.h"
#include "engine/world_state.h"

#include <doctest/doctest.h>

#include <set>

using namespace fibra;
using namespace fibra::test;

namespace {

// Parallel beams with friction, resting on a floor tool, with the stabilisation on: every kind
// of system is in the graphs.
std::unique_ptr<WorldState> contactWorld() {
  auto w = std::make_unique<WorldState>();
  w->scene = parallelBeams(0.01, 1e-4);
  w->scene.contact.friction = 0.2;
  w->scene.tools[0].friction = 0.1;
  buildWorld(*w);
  return w;
}

int index(const TaskGraph& g, const char* name) {
  const int i = g.find(name);
  REQUIRE_MESSAGE(i >= 0, "no system '" << name << "'");
  return i;
}

bool runsAfter(const TaskGraph& g, const char* later, const char* earlier) {
  const auto& p = g.predecessors(index(g, later));
  return std::find(p.begin(), p.end(), index(g, earlier)) != p.end();
}

std::set<std::string> set(const std::vector<std::string>& v) { return {v.begin(), v.end()}; }

}  // namespace

TEST_CASE("assemble stage: evaluations side by side, the scatter a chain in a fixed order") {
  const auto w = contactWorld();
  const TaskGraph& g = w->pipeline.assemble;
  const char* evaluations[] = {"beam evaluation", "fibre contact law", "tool contact law", "clear"};
  for (const char* a : evaluations) {
    CHECK(g.predecessors(index(g, a)).empty());
    for (const char* b : evaluations)
      if (a != b) CHECK_MESSAGE(!g.ordered(index(g, a), index(g, b)), a << " / " << b);
  }
  const char* chain[] = {"clear", "beam scatter", "loads", "fibre contact scatter",
                         "tool contact scatter", "stabilisation"};
  for (int i = 1; i < 6; ++i) CHECK_MESSAGE(runsAfter(g, chain[i], chain[i - 1]), chain[i]);
  CHECK(runsAfter(g, "beam scatter", "beam evaluation"));
  CHECK(runsAfter(g, "fibre contact scatter", "fibre contact law"));
  CHECK(runsAfter(g, "tool contact scatter", "tool contact law"));
  // What a system reads and writes is its signature's.
  const int law = index(g, "fibre contact law");
  CHECK(set(g.reads(law)) ==
        std::set<std::string>{"fibres", "contact params", "zones", "contact elements", "input"});
  CHECK(set(g.writes(law)) == std::set<std::string>{"friction status", "contact forces"});
  CHECK(set(g.writes(index(g, "tool contact scatter"))) == std::set<std::string>{"linear system"});
}

TEST_CASE("detect, normals and adapt stages: fibre-fibre and fibre-tool branches side by side") {
  const auto w = contactWorld();
  const Pipeline& p = w->pipeline;
  const TaskGraph& d = p.detect;
  const char* fibreChain[] = {"broadphase",       "zone builder",      "zone identity",
                              "zone penalties",   "adopt zones",       "contact elements",
                              "contact particles", "contact cliques"};
  for (int i = 1; i < 8; ++i) CHECK_MESSAGE(runsAfter(d, fibreChain[i], fibreChain[i - 1]), fibreChain[i]);
  for (const char* s : fibreChain) CHECK_FALSE(d.ordered(index(d, s), index(d, "tool detection")));
  CHECK(d.ordered(index(d, "friction reference"), index(d, "tool detection")));
  CHECK(d.ordered(index(d, "friction reference"), index(d, "contact cliques")));
  // Zone identity reads the previous zones, which the adoption then replaces.
  CHECK(set(d.reads(index(d, "zone identity"))).count("zones") == 1);
  CHECK(runsAfter(d, "adopt zones", "zone penalties"));

  CHECK_FALSE(p.normals.ordered(index(p.normals, "contact normals"), index(p.normals, "tool normals")));
  const TaskGraph& a = p.adapt;
  const char* adapt[] = {"zone penalty adapter", "tool penalty adapter", "friction history"};
  for (const char* x : adapt)
    for (const char* y : adapt)
      if (x != y) CHECK_FALSE(a.ordered(index(a, x), index(a, y)));
  CHECK(p.reference.size() == 1);
}

TEST_CASE("a scene pays only for what it needs: no contact, no tools, no stabilisation") {
  WorldState w;
  w.scene = crossingBeams(0.01, 1e-4);  // fibre-fibre contact, no tool, no stabilisation
  buildWorld(w);
  const TaskGraph& g = w.pipeline.assemble;
  CHECK(g.find("fibre contact law") >= 0);
  CHECK(g.find("tool contact law") < 0);
  CHECK(g.find("tool contact scatter") < 0);
  CHECK(g.find("stabilisation") < 0);
  CHECK(w.pipeline.detect.find("tool detection") < 0);
  CHECK(w.pipeline.detect.find("friction reference") < 0);  // frictionless
  CHECK(w.pipeline.adapt.find("friction history") < 0);
  CHECK(w.pipeline.reference.size() == 0);

  WorldState bare;
  bare.scene = crossingBeams(0.01, 1e-4);
  bare.scene.contact.enabled = false;
  buildWorld(bare);
  CHECK(bare.pipeline.detect.size() == 0);
  CHECK(bare.pipeline.normals.size() == 0);
  CHECK(bare.pipeline.adapt.size() == 0);
  std::set<std::string> names;
  for (int i = 0; i < bare.pipeline.assemble.size(); ++i) names.insert(bare.pipeline.assemble.name(i));
  CHECK(names == std::set<std::string>{"beam evaluation", "clear", "beam scatter", "loads"});
}

TEST_CASE("the step report carries the detection statistics") {
  World w(crossingBeams(0.01, 1e-4));
  const StepReport first = w.step();
  REQUIRE(first.status == StepStatus::Converged);
  const ContactReport& c = first.contact;
  // One detection opens the attempt and one follows every loop A pass but the last.
  CHECK(c.restarts == 0);
  CHECK(c.detections == c.detectionLoops);
  CHECK(c.broadphaseRebuilds >= 1);  // the first detection builds the candidate set
  CHECK(c.broadphaseRebuilds <= c.detections);
  // Two crossing beams of 10 elements: the candidate pairs are element pairs of A and B whose
  // boxes overlap near the crossing, at least one and far fewer than all 100.
  CHECK(c.candidatePairs >= 1);
  CHECK(c.candidatePairs < 100);
}
