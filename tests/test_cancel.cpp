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
