// Determinism across thread counts, in the style of Box2D's: a contact scene with friction and
// tools (a 7-fibre bundle squeezed between two plane tools, fibre-fibre and fibre-tool friction,
// the stabilisation on) is solved for a few increments with 1, 2, 3, 4 and 8 TBB threads, and
// a hash of every column of the state (q, the residual, every store of the committed contact
// state) must be the same for all. The scene's non-symmetric tangent goes to Eigen's SparseLU,
// which uses no threaded BLAS (engine/world.h says what holds with CHOLMOD and UMFPACK).
#include "bench/contact_scenes.h"
#include "engine/world.h"
#include "store_bits.h"

#include <doctest/doctest.h>
#include <tbb/global_control.h>

using namespace fibra;

namespace {

std::uint64_t stateHash(const World& w) {
  std::uint64_t h = test::hashBits(w.fibres().q);
  h = test::hashBits(w.residual(), h);
  return test::hashBits(w.contact(), h);
}

}  // namespace

TEST_CASE("a frictional contact scene with tools hashes the same with 1, 2, 3, 4 and 8 threads") {
  // Up to 8 threads even on a machine with fewer cores.
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 8);
  const SceneDef scene = scenes::bundle(1, 8, 0.01, 5e-4, 0.1);
  const int increments = 3;
  std::uint64_t reference = 0;
  for (int threads : {1, 2, 3, 4, 8}) {
    CAPTURE(threads);
    World w(scene, {.threads = threads});
    for (int i = 0; i < increments; ++i) REQUIRE(w.step().status == StepStatus::Converged);
    REQUIRE(w.contact().elements.size() > 0);
    REQUIRE(w.contact().toolElements.size() > 0);
    int active = 0;
    for (double r : w.contact().forces.normalForce) active += r > 0;
    REQUIRE(active > 0);
    const std::uint64_t h = stateHash(w);
    if (threads == 1) reference = h;
    CHECK(h == reference);
  }
}

TEST_CASE("the state hash sees a change in any column") {
  const SceneDef scene = scenes::bundle(1, 8, 0.01, 5e-4, 0.1);
  World w(scene, {.threads = 1});
  REQUIRE(w.step().status == StepStatus::Converged);
  ContactState s = w.contact();
  const std::uint64_t h = test::hashBits(s);
  CHECK(test::hashBits(s) == h);
  s.zones.nextId += 1;  // a per-store scalar
  CHECK(test::hashBits(s) != h);
  s = w.contact();
  REQUIRE(s.toolElements.size() > 0);
  s.toolElements.side[0].c[1][2] = std::nextafter(s.toolElements.side[0].c[1][2], 1.0);  // deep
  CHECK(test::hashBits(s) != h);
  CHECK_FALSE(test::sameBits(s, w.contact()));
}
