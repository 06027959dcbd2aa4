// The woven fabric's test loadings (paper section 5.2.2) on the reduced plain weave of
// samples/fabric_biaxial.json and samples/fabric_shear.json (2 x 2 yarns of 3 fibres, 12
// elements per fibre; scripts/fabric_loadings.py writes them): after the initial geometry
// (forced normals, then the normal rules, frictionless), biaxial tension converges in every
// increment with an edge force that rises with the strain from about the small end tensions,
// within 3% of minus the sum of the reactions on the opposite edge; one shear cycle gives an edge
// force that changes sign with the displacement, and friction between the yarns dissipates
// energy over the cycle (energy.friction of the energy balance).
#include "engine/world.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace fibra;
using namespace fibra::test;

namespace {

constexpr double kTension = 0.01;  // N per fibre end during the initial geometry
constexpr int kFibresPerDirection = 6;

// Index of the boundary condition on `group` (the first when several share it).
Index bcOn(const SceneDef& s, const std::string& group) {
  for (size_t i = 0; i < s.bcs.size(); ++i)
    if (s.bcs[i].group == group) return Index(i);
  FAIL("no boundary condition on " << group);
  return -1;
}

// Sum of the reactions of the per-fibre start conditions of one direction ("warp" / "weft"): the
// edge opposite the direction's ends, N.
Vec3 startReactions(const World& w, const std::string& dir) {
  Vec3 sum = Vec3::Zero();
  for (int y = 0; y < 2; ++y)
    for (int k = 0; k < 3; ++k)
      sum += w.reaction(bcOn(w.scene(), "fab." + dir + std::to_string(y) + ".f" +
                                            std::to_string(k) + ".start")).force;
  return sum;
}

// Sum of every boundary condition's reaction, N: zero at equilibrium (the scenes have no loads).
Vec3 allReactions(const World& w) {
  Vec3 sum = Vec3::Zero();
  for (Index b = 0; b < Index(w.scene().bcs.size()); ++b) sum += w.reaction(b).force;
  return sum;
}

// Runs the increments up to the end of step `last` (0-based), each one required to converge;
// the energy balance of the last one (N mm).
EnergyBalance runThrough(World& w, int last) {
  EnergyBalance e;
  while (!w.finished() && w.currentStep() <= last) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    e = r.energy;
  }
  return e;
}

}  // namespace

TEST_CASE("fabric loadings: reduced biaxial tension converges with a rising edge force") {
  World w(loadScene(sourcePath("samples/fabric_biaxial.json")));
  REQUIRE(w.scene().steps.size() == 3);
  const Index warpEnd = bcOn(w.scene(), "fab.warp.end"), weftEnd = bcOn(w.scene(), "fab.weft.end");
  runThrough(w, 1);  // the initial geometry: forced normals, the normal rules
  // Zero strain: the edge force is about the small tensions of the force-controlled settle run
  // the fibres' starts are held at (scripts/fabric_loadings.py).
  const double f0 = w.reaction(warpEnd).force.x();
  CHECK(std::abs(f0 - kFibresPerDirection * kTension) < 0.03);
  std::vector<double> warp{f0}, weft{w.reaction(weftEnd).force.y()};
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    warp.push_back(w.reaction(warpEnd).force.x());
    weft.push_back(w.reaction(weftEnd).force.y());
    // The opposite edge (the fibres' starts) holds the fabric with about the opposite force;
    // the rest goes to the crossing yarns' held ends (friction and sloped contacts at the
    // crossings), and all the reactions balance.
    CHECK(-startReactions(w, "warp").x() == doctest::Approx(warp.back()).epsilon(0.03));
    CHECK(-startReactions(w, "weft").y() == doctest::Approx(weft.back()).epsilon(0.03));
    CHECK(allReactions(w).norm() < 1e-6 * warp.back());
  }
  REQUIRE(warp.size() == 21);
  for (size_t i = 1; i < warp.size(); ++i) {
    CAPTURE(i);
    CHECK(warp[i] > warp[i - 1]);
    CHECK(weft[i] > weft[i - 1]);
  }
  const size_t n = warp.size() - 1;
  CHECK(warp[n] > 10 * f0);
  MESSAGE("biaxial edge force: " << f0 << " N at zero strain, " << warp[n] << " N (warp), "
                                 << weft[n] << " N (weft) at the end");
}

TEST_CASE("fabric loadings: one shear cycle with friction gives a loop that dissipates energy") {
  SceneDef scene = loadScene(sourcePath("samples/fabric_shear.json"));
  // The sample's first cycle (mu = 0.1 between the yarns, damping 0.1 in the shear steps): to
  // +u (t = 3), to -u (t = 5), back to +u (t = 7), 2 increments per quarter.
  REQUIRE(scene.steps.size() >= 5);
  scene.steps.resize(5);
  World w(scene);
  const Index warpEnd = bcOn(w.scene(), "fab.warp.end");
  const EnergyBalance atPlus = runThrough(w, 2);  // the initial geometry, the first quarter
  const double plus = w.reaction(warpEnd).force.y();
  runThrough(w, 3);  // to -u
  const double minus = w.reaction(warpEnd).force.y();
  CHECK(plus * minus < 0);  // the force changes sign with the displacement
  CHECK(std::abs(plus) > 0.05);
  CHECK(std::abs(minus) > 0.05);
  const EnergyBalance back = runThrough(w, 4);  // back to +u: a closed cycle
  CHECK(w.finished());
  CHECK(w.reaction(warpEnd).force.y() == doctest::Approx(plus).epsilon(0.05));
  // Friction's work on the fibres over the cycle is negative: the loop's dissipated energy,
  // far above what the balance makes of frictionless contact (5e-6 N mm in such a cycle).
  const double dissipated = atPlus.friction - back.friction;
  CHECK(dissipated > 5e-4);
  MESSAGE("shear edge force: " << plus << " N at +u, " << minus << " N at -u; friction "
                               << "dissipated over the cycle: " << dissipated << " N mm");
}

TEST_CASE("fabric loadings: a step's friction_factor is read and must not be negative") {
  const auto withFactor = [](const std::string& factor) {
    return R"({"units": "mm-N-MPa", "materials": [{"name": "m", "young_modulus": 1000}],
      "fibres": [{"name": "a", "material": "m", "radius": 0.1, "elements": 2,
                  "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
      "boundary_conditions": [{"type": "clamp", "group": "a.start"}],
      "steps": [{"friction_factor": )" + factor + "}, {\"end_time\": 2}]}";
  };
  const SceneDef s = loadSceneFromString(withFactor("0"), "s.json");
  CHECK(s.steps[0].frictionFactor == 0);
  CHECK(s.steps[1].frictionFactor == 1);
  const std::string error =
      errorOf([&] { loadSceneFromString(withFactor("-0.5"), "s.json"); });
  CHECK(error.find("steps[0].friction_factor") != std::string::npos);
}
