// Cancellation reaches into long systems: the detection checks the embedder's cancel flag per
// chunk of work (core/cancel.h), polled only on the thread that called step(), and a cancelled
// attempt leaves the world at its last converged state.
#include "contact_fixtures.h"
#include "contact_scenes.h"
#include "systems/broadphase.h"

#include <doctest/doctest.h>

#include <thread>

using namespace fibra;
using namespace fibra::test;

TEST_CASE("a cancel during detection stops the attempt before any Newton iteration") {
  Trace trace;
  int polls = 0;
  std::thread::id pollThread;
  bool otherThread = false;
  WorldDef def;
  def.threads = 2;
  def.trace = &trace;
  def.cancel = [&] {
    if (polls++ > 0 && std::this_thread::get_id() != pollThread) otherThread = true;
    pollThread = std::this_thread::get_id();
    return true;
  };
  World w(parallelBeams(0.01, 1e-4), def);
  const Eigen::VectorXd q0 = w.fibres().q;
  trace.clear();
  const StepReport r = w.step();
  CHECK(r.status == StepStatus::Cancelled);
  CHECK(r.totalIterations == 0);
  CHECK(polls >= 1);
  CHECK_FALSE(otherThread);
  CHECK(pollThread == std::this_thread::get_id());
  bool detected = false, assembled = false;
  for (const Trace::Event& e : trace.events()) {
    detected |= std::string(e.name) == "broadphase";
    assembled |= std::string(e.name) == "beam evaluation";
  }
  CHECK(detected);
  CHECK_FALSE(assembled);
  CHECK(w.time() == 0);
  CHECK(w.fibres().q == q0);
}

TEST_CASE("a cancelled broadphase leaves its candidate set invalid, and the next call rebuilds it") {
  const FibreStore fs = fixtures::straight(7);
  const ContactParams p = fixtures::defaults(fs);
  ContactCache reference, cancelled;
  const Cancel never;
  Cancel now;
  now.arm([] { return true; });
  updateBroadphase(fs, fs.q, p, reference.centrelines, reference.broadphase, nullptr, never);
  updateBroadphase(fs, fs.q, p, cancelled.centrelines, cancelled.broadphase, nullptr, now);
  CHECK(now.requested());
  CHECK_FALSE(cancelled.broadphase.valid);
  REQUIRE(reference.broadphase.candidate.size() > 0);
  CHECK(updateBroadphase(fs, fs.q, p, cancelled.centrelines, cancelled.broadphase, nullptr, never));
  CHECK(sameBits(cancelled.broadphase.candidate, reference.broadphase.candidate));
  CHECK(sameBits(cancelled.broadphase.candidateFirst, reference.broadphase.candidateFirst));
}

TEST_CASE("a cancel at any poll of an increment either cancels it or leaves it as an uninterrupted run has it") {
  // The acceptance check of the contact set polls too: a cancel there used to accept the
  // increment with the check cut short (its overlap figures 0).
  const SceneDef scene = parallelBeams(0.01, 1e-4);
  World reference(scene);
  const StepReport full = reference.step();
  REQUIRE(full.status == StepStatus::Converged);
  REQUIRE(full.contact.maxOverlap > 0);
  int total = 0;
  {
    WorldDef counting;
    counting.cancel = [&] { return ++total < 0; };
    World w(scene, counting);
    REQUIRE(w.step().status == StepStatus::Converged);
  }
  REQUIRE(total > 4);
  int cancelled = 0;
  for (int k = 1; k <= total; ++k) {
    CAPTURE(k);
    int polls = 0;
    WorldDef def;
    def.cancel = [&] { return ++polls == k; };
    World w(scene, def);
    const StepReport r = w.step();
    if (r.status == StepStatus::Cancelled) {
      ++cancelled;
      CHECK(w.time() == 0);
      continue;
    }
    REQUIRE(r.status == StepStatus::Converged);
    CHECK(r.contact.maxOverlap == full.contact.maxOverlap);
    CHECK(w.fibres().q == reference.fibres().q);
  }
  CHECK(cancelled > 0);
}
