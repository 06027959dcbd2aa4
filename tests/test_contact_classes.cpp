// Contact settings per pair class (docs/SCENE.md, contact `pairs`): two pairs of crossing beams,
// far apart, of four classes with their own friction and p_max; each pair presses with the same
// load, then its upper beam is dragged across the lower one. Each pair's deepest penetration
// sits at its own p_max, and the drag force on its upper beam is its own mu times the normal
// force (both from the beams' holds, not from the law); the true overlap the acceptance check
// reports is each pair's own (from the centrelines) over its own p_max, and names the pair. The
// rules' errors name the field.
#include "contact_scenes.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace fibra;
using namespace fibra::test;

namespace {

constexpr double kLoad = 0.01;  // N at each upper beam's midspan

// Pair k (k = 0, 1): lower beam Ak along x at y = 10 k, upper beam Bk along y over it, touching;
// classes "ak" and "bk". Step 1 presses each Bk down by kLoad; step 2 drags Bk's ends by
// 0.05 mm along x.
SceneDef twoPairs(double mu0, double pMax0, double mu1, double pMax1) {
  const SceneDef one = crossingBeams(kLoad, 1e-3);
  SceneDef s;
  s.materials = one.materials;
  s.contact = one.contact;
  s.contact.maxReversibleSlip = 5e-4;
  const Table drag{{0, 1, 2}, {0, 0, 1}};
  for (int k = 0; k < 2; ++k) {
    const std::string a = "A" + std::to_string(k), b = "B" + std::to_string(k);
    const Vec3 shift(0, 10 * k, 0);
    for (FibreDef f : one.fibres) {
      f.name = f.name == "A" ? a : b;
      for (Vec3& p : f.geometry.points) p += shift;
      f.contactClass = f.name == a ? "a" + std::to_string(k) : "b" + std::to_string(k);
      s.fibres.push_back(f);
    }
    s.groups.push_back({b + ".mid", b, {10}, {}});
    hold(s, a + ".start", {X, Y, Z, G1Y});
    hold(s, a + ".end", {X, Y, Z});
    hold(s, b + ".start", {X, Y, Z, G1X}, Vec3(0.05, 0, 0), drag);
    hold(s, b + ".end", {X, Y, Z}, Vec3(0.05, 0, 0), drag);
    s.loads.push_back({LoadKind::Force, b + ".mid", Vec3(0, 0, -kLoad), {{0, 1, 2}, {0, 1, 1}}});
  }
  // The section's penalty floor (penalty_min 1 x E R = 400 N/mm) would hold these light contacts
  // below p_max: each rule lowers its own, so that each zone's penetration reaches its p_max.
  ContactPairDef p0, p1;
  p0.classes = {"a0", "b0"}, p0.friction = mu0, p0.maxPenetration = pMax0, p0.penaltyMin = 1e-2;
  p1.classes = {"b1", "a1"}, p1.friction = mu1, p1.maxPenetration = pMax1, p1.penaltyMin = 1e-2;
  s.contact.pairs = {p0, p1};
  StepDef press, slide;
  press.increments = 4;
  slide.endTime = 2;
  slide.increments = 4;
  s.steps = {press, slide};
  return s;
}

// Deepest penetration of the elements between fibres 2k and 2k + 1, mm.
double deepest(const World& w, int k) {
  double d = 0;
  const ContactElementStore& el = w.contact().elements;
  for (Index e = 0; e < el.size(); ++e)
    if (el.fibreI[e] / 2 == k) d = std::max(d, -w.contact().forces.gap[e]);
  return d;
}

}  // namespace

TEST_CASE("each pair class has its own friction and p_max: penetration and slip force") {
  const double mu[2] = {0.1, 0.3}, pMax[2] = {1e-4, 4e-4};
  World w(twoPairs(mu[0], pMax[0], mu[1], pMax[1]));
  while (w.currentStep() == 0) REQUIRE(w.step().status == StepStatus::Converged);
  for (int k = 0; k < 2; ++k) {
    CAPTURE(k);
    MESSAGE("pair " << k << ": deepest penetration " << deepest(w, k) << " mm, p_max " << pMax[k]);
    CHECK(deepest(w, k) <= pMax[k]);
    CHECK(deepest(w, k) >= 0.5 * pMax[k]);
  }
  for (const ZoneStore& z = w.contact().zones; Index i : {Index(0), z.size() - 1}) {
    const int k = int(z.fibreI[i] / 2);
    CHECK(z.friction[i] == mu[k]);
    CHECK(z.pMax[i] == pMax[k]);
    CHECK(z.penaltyMin[i] == 1e-2);
  }
  while (!w.finished()) REQUIRE(w.step().status == StepStatus::Converged);
  for (int k = 0; k < 2; ++k) {
    CAPTURE(k);
    // A's holds (bcs 4k, 4k + 1) carry the contact's normal force (A has no other load); B's
    // holds (4k + 2, 4k + 3) balance, along x, the friction force on B alone.
    const double normal = std::abs((w.reaction(4 * k).force + w.reaction(4 * k + 1).force).z());
    const double drag = std::abs((w.reaction(4 * k + 2).force + w.reaction(4 * k + 3).force).x());
    MESSAGE("pair " << k << ": drag " << drag << " N, normal " << normal << " N, ratio "
                    << drag / normal << " (mu " << mu[k] << ")");
    CHECK(normal > 0.4 * kLoad);  // about half the load: B's own supports carry the rest
    CHECK(std::abs(drag / (mu[k] * normal) - 1) < 0.02);
  }
}

TEST_CASE("the true overlap at acceptance is a multiple of each pair's own p_max, and names the pair") {
  // The section's p_max is 1e-3 mm; pair 0's 1e-4, pair 1's 4e-4, but pair 1's penalty floor
  // (400 N/mm) holds it far shallower: pair 0, near its own p_max, is the deepest overlap both
  // in mm and in its own p_max (a tenth of the section's).
  const double pMax[2] = {1e-4, 4e-4};
  SceneDef scene = twoPairs(0, pMax[0], 0, pMax[1]);
  scene.contact.pairs[1].penaltyMin = 400;
  World w(scene);
  StepReport r;
  while (w.currentStep() == 0) {
    r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
  }
  // Independently, from the nodes at the crossing (both beams' midspan nodes, s = 2 mm, over
  // each other): w_A + w_B - |x0A - x0B|, w = R |G^T n| the half-width of the deformed section
  // along the line of centres n (the contact flattens the sections: 2R - d over-states the
  // overlap by 4% here).
  const FibreStore& fs = w.fibres();
  const auto width = [&](Index node, const Vec3& n) {
    return 0.1 * std::hypot(g1Of(fs.q, node).dot(n), g2Of(fs.q, node).dot(n));
  };
  double overlap[2];
  for (int k = 0; k < 2; ++k) {
    const Index a = fs.firstNode[2 * k] + 10, b = fs.firstNode[2 * k + 1] + 10;
    const Vec3 d = x0Of(fs.q, a) - x0Of(fs.q, b);
    const Vec3 n = d.normalized();
    overlap[k] = width(a, n) + width(b, n) - d.norm();
  }
  MESSAGE("overlaps " << overlap[0] << ", " << overlap[1] << " mm; reported " << r.contact.maxOverlap
                      << " mm, " << r.contact.maxOverlapRatio << " p_max");
  REQUIRE(overlap[0] / pMax[0] > 0.5);
  REQUIRE(overlap[0] / pMax[0] > 2 * overlap[1] / pMax[1]);
  CHECK(r.contact.maxOverlap == doctest::Approx(std::max(overlap[0], overlap[1])).epsilon(0.01).scale(0));
  CHECK(r.contact.maxOverlapRatio == doctest::Approx(overlap[0] / pMax[0]).epsilon(0.01).scale(0));
  CHECK(r.contact.overlapFibreI + r.contact.overlapFibreJ == 1);  // fibres 0 and 1: pair 0
  CHECK(r.contact.overlapSI == doctest::Approx(2).epsilon(0.01));
  CHECK(r.contact.overlapSJ == doctest::Approx(2).epsilon(0.01));
}

TEST_CASE("penalty bounds per pair class: the section's floor holds the other pair shallow") {
  SceneDef s = twoPairs(0.1, 1e-4, 0.3, 4e-4);
  s.contact.pairs[1].penaltyMin = std::nan("");  // pair 1 takes the section's floor, 1 x E R
  s.steps.resize(1);
  World w(s);
  while (!w.finished()) REQUIRE(w.step().status == StepStatus::Converged);
  MESSAGE("deepest penetration: pair 0 " << deepest(w, 0) << " mm, pair 1 " << deepest(w, 1)
                                         << " mm");
  CHECK(deepest(w, 0) >= 0.5 * 1e-4);  // its own floor, 1e-2 E R: at its p_max
  CHECK(deepest(w, 1) < 0.5 * 4e-4);   // held by the section's floor
  const ZoneStore& z = w.contact().zones;
  REQUIRE(z.size() == 2);
  CHECK(z.penaltyMin[1] == 1);
  CHECK(z.penalty[1] == doctest::Approx(400).epsilon(1e-12));  // E R: at the floor
  CHECK(z.penalty[0] < 400);
}

TEST_CASE("keyword pair rules: within and between, a named pair above them") {
  SceneDef s = twoPairs(0.1, 1e-4, 0.3, 4e-4);
  s.fibres[1].contactClass = "a0";  // pair 0 within class a0
  s.contact.pairs[0].classes = {"a0", "a0"};
  s.contact.pairs[1].friction = std::nan("");  // takes the contact section's
  ContactPairDef within, between;
  within.rule = PairRule::Within, within.friction = 0.05;
  between.rule = PairRule::Between, between.friction = 0.2, between.maxPenetration = 2e-4;
  between.penaltyMax = 50;
  s.contact.pairs.push_back(within);
  s.contact.pairs.push_back(between);
  s.contact.friction = 0.01;
  s.steps.resize(1);
  World w(s);
  REQUIRE(w.step().status == StepStatus::Converged);
  const ZoneStore& z = w.contact().zones;
  REQUIRE(z.size() == 2);
  CHECK(z.friction[0] == 0.1);   // the named pair (a0, a0) above `within`
  CHECK(z.pMax[0] == 1e-4);
  CHECK(z.friction[1] == 0.01);  // the named pair (a1, b1) without friction: the section's
  CHECK(z.pMax[1] == 4e-4);
  s.contact.pairs.erase(s.contact.pairs.begin(), s.contact.pairs.begin() + 2);
  World k(s);
  REQUIRE(k.step().status == StepStatus::Converged);
  CHECK(k.contact().zones.friction[0] == 0.05);  // within
  CHECK(k.contact().zones.friction[1] == 0.2);   // between
  CHECK(k.contact().zones.pMax[1] == 2e-4);
  CHECK(k.contact().zones.penaltyMax[1] == 50);
  CHECK(k.contact().zones.penaltyMax[0] == 1e4);  // the section's
}

TEST_CASE("pair rules and levels that cannot hold are scene errors naming the field") {
  const SceneDef base = twoPairs(0.1, 1e-4, 0.3, 4e-4);
  const auto errorWith = [&](auto change) {
    SceneDef s = base;
    change(s);
    return errorOf([&] { World world(s); });
  };
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[1].classes[0] = "c"; }) ==
        "contact.pairs[1].classes[0]: unknown class 'c' (no fibre has it; the fibres' classes: "
        "a0, a1, b0, b1)");
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[1].classes = {"b0", "a0"}; }) ==
        "contact.pairs[1].classes: the pair ('b0', 'a0') is given twice");
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[0].classes[1] = ""; }) ==
        "contact.pairs[0].classes[1]: empty class name (the default class is unnamed)");
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[0].friction = -1; }) ==
        "contact.pairs[0].friction: must be a finite value >= 0");
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[1].maxPenetration = 0; }) ==
        "contact.pairs[1].max_penetration: must be a finite value > 0");
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[1].penaltyMin = 0; }) ==
        "contact.pairs[1].penalty_min: must be a finite value > 0");
  CHECK(errorWith([](SceneDef& s) { s.contact.pairs[0].penaltyMax = 1e-3; }) ==
        "contact.pairs[0].penalty_max: must be finite and >= penalty_min (0.01, the rule's), got "
        "0.001");
  CHECK(errorWith([](SceneDef& s) {
          s.contact.pairs[0].rule = s.contact.pairs[1].rule = PairRule::Between;
        }) == "contact.pairs[1].classes: this keyword rule is given twice");
  CHECK(errorWith([](SceneDef& s) { s.fibres[2].levels = {{0.5, 1}}; }) ==
        "fibres[2].levels[0].from: the first piece must start at 0");
  CHECK(errorWith([](SceneDef& s) { s.fibres[2].levels = {{0, 1}, {1, 0}, {1, 1}}; }) ==
        "fibres[2].levels[2].from: must exceed the previous piece's start");
  CHECK(errorWith([](SceneDef& s) {
          s.contact.enabled = false;
          s.steps[1].forcedNormal = Vec3::UnitZ();
        }) == "steps[1].forced_normals: needs fibre contact (a contact section)");
  CHECK(errorWith([](SceneDef& s) { s.steps[0].forcedNormal = Vec3(0, 0, 2); }) ==
        "steps[0].forced_normals.direction: must be a finite unit vector");
  CHECK(errorWith([](SceneDef& s) {
          s.steps[0].forcedNormal = Vec3::UnitZ();
          s.steps[0].forcedAllowance = -1e-3;
        }) == "steps[0].forced_normals.allowance: must be a finite overlap >= 0, mm");
  CHECK(errorWith([](SceneDef& s) { s.steps[1].forcedAllowance = 0.1; }) ==
        "steps[1].forced_normals.allowance: needs a forced direction");
}

TEST_CASE("a rule's penalty bound that conflicts with the section's names the rule's own field") {
  SceneDef s = twoPairs(0.1, 1e-4, 0.3, 4e-4);
  const auto errorWith = [&](auto change) {
    SceneDef t = s;
    change(t);
    return errorOf([&] { World world(t); });
  };
  // penalty_min above the section's penalty_max (1e4), no penalty_max of its own: before, the
  // message blamed penalty_max, a field the rule does not give.
  CHECK(errorWith([](SceneDef& t) { t.contact.pairs[1].penaltyMin = 1e5; }) ==
        "contact.pairs[1].penalty_min: must be <= penalty_max (10000, the contact section's; or "
        "give the rule its own penalty_max), got 100000");
  // penalty_max below the section's penalty_min (1), no penalty_min of its own.
  CHECK(errorWith([](SceneDef& t) {
          t.contact.pairs[1].penaltyMin = std::nan("");
          t.contact.pairs[1].penaltyMax = 0.5;
        }) == "contact.pairs[1].penalty_max: must be finite and >= penalty_min (1, the contact "
              "section's), got 0.5");
  CHECK(errorWith([](SceneDef& t) {
          for (FibreDef& f : t.fibres) f.contactClass = "";
        }) == "contact.pairs[0].classes[0]: unknown class 'a0' (no fibre has it; no fibre has a "
              "class: give the fibres a \"class\")");
  // Both bounds given by the rule and consistent: accepted.
  s.contact.pairs[1].penaltyMin = 2e4;
  s.contact.pairs[1].penaltyMax = 3e4;
  CHECK(errorOf([&] { World world(s); }) == "(no error)");
}

TEST_CASE("forced normals that could force no pair are scene errors naming the step") {
  SceneDef s = twoPairs(0.1, 1e-4, 0.3, 4e-4);
  s.steps[0].forcedNormal = Vec3::UnitZ();
  const auto errorWith = [&](auto change) {
    SceneDef t = s;
    change(t);
    return errorOf([&] { World world(t); });
  };
  // Four classes, every fibre at the default level 0: nothing is oriented.
  CHECK(errorWith([](SceneDef&) {}) ==
        "steps[0].forced_normals: every fibre has level 0, so no crossing is oriented (give the "
        "fibres on top higher \"levels\")");
  CHECK(errorWith([](SceneDef& t) {
          for (FibreDef& f : t.fibres) f.levels = {{0, 2}};
        }) == "steps[0].forced_normals: every fibre has level 2, so no crossing is oriented "
              "(give the fibres on top higher \"levels\")");
  // No classes: forced normals act only between classes.
  CHECK(errorWith([](SceneDef& t) {
          t.contact.pairs.clear();
          for (FibreDef& f : t.fibres) f.contactClass = "";
        }) == "steps[0].forced_normals: act between fibres of different classes, but every fibre "
              "is in the default class (no fibre has a \"class\")");
  CHECK(errorWith([](SceneDef& t) {
          t.contact.pairs.clear();
          for (FibreDef& f : t.fibres) f.contactClass = "yarn";
        }) == "steps[0].forced_normals: act between fibres of different classes, but every fibre "
              "is in class 'yarn'");
  // The upper beams one level up: accepted.
  CHECK(errorWith([](SceneDef& t) {
          t.fibres[1].levels = t.fibres[3].levels = {{0, 1}};
        }) == "(no error)");
}

TEST_CASE("the scene file reads classes, level tables, pair rules and forced normals") {
  const SceneDef s = loadScene(FIBRA_SOURCE_DIR "/samples/forced_normals.json");
  CHECK(s.fibres[0].contactClass == "warp");
  REQUIRE(s.fibres[0].levels.size() == 1);
  CHECK(s.fibres[0].levels[0].level == 1);
  REQUIRE(s.contact.pairs.size() == 2);
  CHECK(s.contact.pairs[0].rule == PairRule::Named);
  CHECK(s.contact.pairs[0].classes[1] == "weft");
  CHECK(s.contact.pairs[1].rule == PairRule::Within);
  CHECK(s.steps[0].forcedNormal == Vec3::UnitZ());
  CHECK(s.steps[1].forcedNormal == Vec3::Zero());
  const std::string text = R"({"units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 1}],
    "fibres": [{"name": "f", "material": "m", "radius": 0.1, "elements": 2, "class": "y",
                "levels": [[0, 1], [2, -1]],
                "geometry": {"type": "line", "points": [[0, 0, 0], [4, 0, 0]]}}],
    "contact": {"pairs": [{"classes": "across"}]},
    "steps": [{"forced_normals": {"direction": [0, 0, 1]}}]})";
  CHECK(errorOf([&] { loadSceneFromString(text, "s.json"); }) ==
        "s.json: contact.pairs[0].classes: must be two class names or \"within\" or "
        "\"between\", got \"across\"");
  nlohmann::json j = nlohmann::json::parse(text);
  j["contact"]["pairs"][0]["classes"] = {"y"};
  CHECK(errorOf([&] { loadSceneFromString(j.dump(), "s.json"); }) ==
        "s.json: contact.pairs[0].classes: must be two class names [a, b] (for the pairs within "
        "one class: [a, a]), got 1 name");
  j["contact"]["pairs"][0]["classes"] = "between";
  j["fibres"][0]["levels"] = nlohmann::json::array();
  CHECK(errorOf([&] { loadSceneFromString(j.dump(), "s.json"); }) ==
        "s.json: fibres[0].levels: must list at least one piece [from, level] (or give one level "
        "for the whole fibre)");
  j["fibres"][0]["levels"] = {{0, 1}, {2, -1}};
  j["steps"][0]["forced_normals"]["direction"] = {0, 0, 0};
  CHECK(errorOf([&] { loadSceneFromString(j.dump(), "s.json"); }) ==
        "s.json: steps[0].forced_normals.direction: must be a finite, non-zero vector");
  // Huge and tiny components: the unit vector, not an overflow to a zero normal (forcing off)
  // nor an underflow to a refused one.
  j["steps"][0]["forced_normals"]["direction"] = {0, 0, 1e160};
  CHECK(loadSceneFromString(j.dump(), "s.json").steps[0].forcedNormal == Vec3::UnitZ());
  j["steps"][0]["forced_normals"]["direction"] = {0, 1e-170, 1e-170};
  CHECK((loadSceneFromString(j.dump(), "s.json").steps[0].forcedNormal -
         Vec3(0, 1, 1).normalized()).norm() < 1e-15);
  j["steps"][0]["forced_normals"]["direction"] = {0, 0, -3};
  const SceneDef r = loadSceneFromString(j.dump(), "s.json");
  CHECK(r.steps[0].forcedNormal == -Vec3::UnitZ());
  CHECK(r.steps[0].forcedAllowance == 0);
  j["steps"][0]["forced_normals"]["allowance"] = -0.1;
  CHECK(errorOf([&] { loadSceneFromString(j.dump(), "s.json"); }) ==
        "s.json: steps[0].forced_normals.allowance: must be a finite overlap >= 0, mm (got -0.1)");
  j["steps"][0]["forced_normals"]["allowance"] = 0.25;
  CHECK(loadSceneFromString(j.dump(), "s.json").steps[0].forcedAllowance == 0.25);
  REQUIRE(r.fibres[0].levels.size() == 2);
  CHECK(r.fibres[0].levels[1].from == 2);
  CHECK(r.fibres[0].levels[1].level == -1);
}
