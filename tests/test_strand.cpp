// A frictionless seven-wire strand pulled to 1% axial strain: a straight core (R 1.97 mm), six
// helical wires (R 1.865 mm) on it, two lay lengths of 115.3 mm (lay angle 11.8 deg), every end
// clamped, steel; the physics of ../shared/cases/strand_two_lays.json at 40 quadratic elements per
// fibre instead of 100 (5.1k DOFs). Frictionless contact between circular fibres puts no torque on
// the core, the axial force rises with the strain, and the elements report the overlap that the
// centrelines show. With the paper's material particles the wires' line force, acting a little off
// the core's axis, spins the core: its torque jumps to a few % of the strand's at 0.5% strain
// (docs/CONTACT.md "Facing particles"). And ../shared/cases/strand_zero_load_step.json: a step
// with no load before a pull costs the pull nothing.
#include "centreline_measure.h"
#include "engine/world.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

using namespace fibra;
using namespace fibra::test;
using Json = nlohmann::json;

namespace {

constexpr double kLay = 115.34112130484495;  // mm, the lay length
constexpr double kCoreR = 1.97, kWireR = 1.865, kPMax = 0.005 * kWireR;  // mm

// The strand over `lays` lay lengths, its ends pulled along the axis by `strain` x its length as
// the table "pull" goes from 0 to 1; frictionless; no steps yet. Boundary conditions: fibre f's
// start clamp is 2f, its pulled end clamp 2f + 1.
Json strand(int lays, double strain, bool facing) {
  const double length = lays * kLay;
  const Json steel = {{"name", "steel"}, {"young_modulus", 188000}, {"poisson_ratio", 0.3}};
  Json fibres = Json::array(), bcs = Json::array();
  fibres.push_back({{"name", "core"}, {"material", "steel"}, {"radius", kCoreR},
                    {"elements", 40}, {"order", 2},
                    {"geometry", {{"type", "line"}, {"points", {{0, 0, 0}, {0, 0, length}}},
                                  {"director", {1, 0, 0}}}}});
  for (int i = 0; i < 6; ++i)
    fibres.push_back({{"name", "w" + std::to_string(i)}, {"material", "steel"},
                      {"radius", kWireR}, {"elements", 40}, {"order", 2},
                      {"geometry", {{"type", "helix"}, {"radius", kCoreR + kWireR},
                                    {"pitch", kLay}, {"turns", double(lays)},
                                    {"origin", {0, 0, 0}}, {"axis", {0, 0, 1}},
                                    {"phase", i * std::numbers::pi / 3}}}});
  for (const Json& f : fibres) {
    const std::string name = f["name"];
    bcs.push_back({{"type", "clamp"}, {"group", name + ".start"}});
    bcs.push_back({{"type", "clamp"}, {"group", name + ".end"},
                   {"displacement", {0, 0, strain * length}}, {"table", "pull"}});
  }
  return {{"units", "mm-N-MPa"}, {"materials", {steel}}, {"fibres", fibres},
          {"boundary_conditions", bcs},
          {"contact", {{"friction", 0.0}, {"facing_particles", facing}}},
          {"output", {{"moment_point", {0, 0, length}}, {"vtu", false}}}};
}

// Two lay lengths pulled by 1% in `increments` increments up to t = end (1% at t = 1).
Json pulled(bool facing, double end, int increments) {
  Json j = strand(2, 0.01, facing);
  j["tables"] = {{"pull", {{0, 0}, {1, 1}}}};
  j["steps"] = {{{"name", "pull"}, {"end_time", end}, {"increments", increments},
                 {"max_iterations", 30}}};
  return j;
}

// The core's end torque about the strand axis over the whole strand's (all seven end clamps).
double coreTorqueShare(const World& w) {
  double total = 0;
  for (int f = 0; f < 7; ++f) total += w.reaction(2 * f + 1).moment.z();
  return std::abs(w.reaction(1).moment.z()) / std::abs(total);
}

double axialForce(const World& w) {
  double total = 0;
  for (int f = 0; f < 7; ++f) total += w.reaction(2 * f + 1).force.z();
  return total;
}

// The deepest overlap of a wire with the core, from the centrelines and the deformed sections
// (tests/centreline_measure.h), not from the contact elements: at every wire node, the closest
// approach of the core within 0.5 mm of the node's height, mm.
double trueOverlap(const World& w) {
  const FibreStore& fs = w.fibres();
  const double stretch = 1 + 0.01 * w.time();  // the core's, at the pull's strain
  double deepest = -1e300;
  for (Index wire = 1; wire < 7; ++wire)
    for (Index n = 0; n < fs.nodeCount[wire]; ++n) {
      const double s = fs.length[wire] * double(n) / double(fs.nodeCount[wire] - 1);
      const double height = centreline(fs, fs.q, wire, s).z();
      const Closest c = closestApproach(fs, fs.q, 0, wire, height / stretch, s);
      deepest = std::max(deepest, overlapAt(fs, fs.q, 0, wire, c));
    }
  return deepest;
}

}  // namespace

TEST_CASE("a frictionless strand pulled to 1%: no torque on the core, the overlap reported") {
  World w(loadSceneFromString(pulled(true, 1, 10).dump(), "strand.json"));
  REQUIRE(w.scene().contact.facingParticles);
  double axial = 0, worstShare = 0, reported = 0, gapChange = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    CHECK(axialForce(w) > axial);  // rises at every increment
    axial = axialForce(w);
    worstShare = std::max(worstShare, coreTorqueShare(w));
    reported = r.contact.maxPenetration;
    gapChange = std::max(gapChange, r.contact.redetectGapChange);
  }
  const double overlap = trueOverlap(w);
  MESSAGE("axial force " << axial << " N; core torque up to " << worstShare
                         << " of the strand's; true overlap " << overlap << " mm, reported "
                         << reported << " mm; a fresh detection moves a gap by up to "
                         << gapChange << " p_max");
  CHECK(worstShare <= 1e-9);  // frictionless on circular sections: none but round-off
  CHECK(overlap <= 2 * kPMax);
  CHECK(reported >= 0.8 * overlap);
  // The accepted set is the one a detection from the converged state finds: its gaps, measured
  // on facing particles as the solve's were, within a tenth of p_max.
  CHECK(gapChange <= 0.1);
}

TEST_CASE("with material particles the strand's core picks up torque by 0.5% strain") {
  World w(loadSceneFromString(pulled(false, 0.5, 5).dump(), "strand.json"));
  REQUIRE_FALSE(w.scene().contact.facingParticles);
  double share = 0;
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    share = coreTorqueShare(w);
  }
  MESSAGE("core torque at 0.5% strain: " << share << " of the strand's");
  CHECK(share > 0.01);
}

TEST_CASE("a step with no load does not make the next pull of a strand harder") {
  // ../shared/cases/strand_zero_load_step.json: one lay length, p_max 1e-5 mm, strain 1e-3. The
  // empty step once decayed the zone penalties and the pull that followed stalled.
  const auto run = [](bool empty) {
    Json j = strand(1, 1e-3, true);
    j["contact"]["max_penetration"] = 1e-5;
    if (empty) {
      j["tables"] = {{"pull", {{0, 0}, {1, 0}, {2, 1}}}};
      j["steps"] = {{{"name", "settle"}, {"end_time", 1}, {"increments", 1}},
                    {{"name", "pull"}, {"end_time", 2}, {"increments", 1}}};
    } else {
      j["tables"] = {{"pull", {{0, 0}, {1, 1}}}};
      j["steps"] = {{{"name", "pull"}, {"end_time", 1}, {"increments", 1}}};
    }
    World w(loadSceneFromString(j.dump(), "strand.json"));
    int iterations = 0, cutbacks = 0;
    while (!w.finished()) {
      const StepReport r = w.step();
      REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
      if (r.step == (empty ? 1 : 0)) iterations += r.totalIterations, cutbacks += r.cutbacks;
    }
    return std::pair{iterations, cutbacks};
  };
  const auto [after, cutbacks] = run(true);
  const auto [direct, directCutbacks] = run(false);
  MESSAGE("pull after the empty step: " << after << " iterations, " << cutbacks
                                        << " cutbacks; without it: " << direct);
  CHECK(cutbacks == 0);
  CHECK(double(after) <= 1.5 * double(direct));
}
