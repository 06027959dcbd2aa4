// Fibre ends as finite bodies: a fibre is a cylinder cut flat at its end sections, and its end
// face (centre and rim) touches the tools (systems/tool_detection.h). A vertical fibre (R = 0.1,
// L = 2, E = 4000), clamped at the top, is brought end-first onto a rigid plane and pressed
// 0.002 mm past touch: its end face rests on the plane within p_max, and the plane carries
// EA x the fibre's shortening (a straight bar: F = E pi R^2 (0.002 + z_tip) / L).
#include "engine/world.h"
#include "engine/world_state.h"
#include "fd_tangent.h"
#include "io/scene_loader.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace fibra;

TEST_CASE("a fibre's flat end face rests on a plane and carries EA x its shortening") {
  const SceneDef scene = loadSceneFromString(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [{"name": "f", "material": "m", "radius": 0.1, "elements": 6,
                "geometry": {"type": "line", "points": [[0, 0, 0.05], [0, 0, 2.05]],
                             "director": [1, 0, 0]}}],
    "tools": [{"name": "wall", "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}],
    "boundary_conditions": [{"type": "clamp", "group": "f.end", "displacement": [0, 0, -0.052],
                             "table": [[0, 0], [0.5, 0.8653846153846154], [1, 1]]}],
    "steps": [{"end_time": 1, "increments": 10}]})",
                                             "end_on_plane.json");
  World w(scene);
  const double pMax = 5e-4, EA = 4000 * std::numbers::pi * 0.01;
  // The top's displacement -0.052 f(t), f piecewise linear through (0, 0), (0.5, a), (1, 1):
  // the end touches when 0.052 f = 0.05.
  const double a = 0.8653846153846154;
  const auto f = [a](double t) { return t <= 0.5 ? 2 * a * t : a + (1 - a) * (t - 0.5) / 0.5; };
  int pressed = 0;
  while (!w.finished()) {
    REQUIRE(w.step().status == StepStatus::Converged);
    const double tip = x0Of(w.fibres().q, 0).z();
    const double force = -w.toolReaction(0).z();  // the fibre pushes the wall down
    const double reach = 0.052 * f(w.time());       // how far the top has come down, mm
    CAPTURE(w.time());
    if (reach < 0.05 - 2 * pMax) {  // still above the wall: no force
      CHECK(tip > 0);
      CHECK(force == 0);
      continue;
    }
    if (reach < 0.05 + 0.001) continue;  // touching: the penalty is being adapted
    ++pressed;
    CHECK(tip >= -1.5 * pMax);
    CHECK(tip <= pMax);
    const double shortening = tip - 0.05 + reach;  // L - current length, mm
    CHECK(force == doctest::Approx(EA * shortening / 2).epsilon(0.03).scale(0));
  }
  CHECK(pressed >= 1);
}

namespace {

SceneDef tee(int increments) {
  std::string text = R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [
      {"name": "A", "material": "m", "radius": 0.1, "elements": 10,
       "geometry": {"type": "line", "points": [[-2, 0, 0], [2, 0, 0]], "director": [0, 0, 1]}},
      {"name": "B", "material": "m", "radius": 0.1, "elements": 10,
       "geometry": {"type": "line", "points": [[0, 0, 0.3], [0, 0, 2.3]], "director": [1, 0, 0]}}],
    "boundary_conditions": [{"type": "clamp", "group": "A.start"}, {"type": "clamp", "group": "A.end"},
                            {"type": "clamp", "group": "B.end", "displacement": [0, 0, -0.3]}],
    "contact": {},
    "steps": [{"end_time": 1, "increments": )";
  text += std::to_string(increments) + "}]}";
  return loadSceneFromString(text, "tee.json");
}

}  // namespace

TEST_CASE("a fibre's end face pushed onto the side of another rests on it and loads it") {
  // B (vertical) comes down 0.3 mm onto A (horizontal, clamped at both ends): its end face
  // touches A's top once B has come 0.2 mm down (t = 2/3), then A bends under it. B's end centre stays
  // on A's top (0.1 above A's axis) within -1.5 p_max ... +p_max, and A's supports carry B.
  World w(tee(15));
  const double pMax = 5e-4;  // 0.005 R
  const FibreStore& fs = w.fibres();
  const Index tip = fs.firstNode[1], mid = fs.firstNode[0] + fs.nodeCount[0] / 2;
  int resting = 0;
  while (!w.finished()) {
    REQUIRE(w.step().status == StepStatus::Converged);
    const double rel = x0Of(fs.q, tip).z() - x0Of(fs.q, mid).z();
    const double carried = w.reaction(0).force.z() + w.reaction(1).force.z();
    CAPTURE(w.time());
    CHECK(rel >= 0.1 - 1.5 * pMax);  // never through A
    if (w.time() < 0.75) continue;   // pressed from t = 2/3
    ++resting;
    CHECK(rel <= 0.1 + pMax);
    CHECK(std::abs(carried) > 1e-6);
  }
  CHECK(resting >= 3);
}

TEST_CASE("no contact past a fibre's end: an end that slid off a fibre leaves no force behind") {
  // B, a cantilever crossing A near its free end, is pressed 0.05 mm onto A, then pulled back
  // 0.6 mm along its axis: its end rides over A's flank and leaves it. Past A (tip y < -0.11),
  // A carries nothing and B's tip is back at its free height 0.2 - 0.05 = 0.150.
  const SceneDef scene = loadSceneFromString(R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [
      {"name": "A", "material": "m", "radius": 0.1, "elements": 10,
       "geometry": {"type": "line", "points": [[-2, 0, 0], [2, 0, 0]], "director": [0, 0, 1]}},
      {"name": "B", "material": "m", "radius": 0.1, "elements": 16,
       "geometry": {"type": "line", "points": [[0, -3, 0.2], [0, 0.3, 0.2]], "director": [0, 0, 1]}}],
    "tables": {"press": [[0, 0], [1, 1]], "slide": [[0, 0], [1, 0], [2, 1]]},
    "boundary_conditions": [
      {"type": "clamp", "group": "A.start"}, {"type": "clamp", "group": "A.end"},
      {"type": "fix", "group": "B.start", "dofs": ["x", "z", "g1", "g2"],
       "displacement": [0, 0, -0.05], "table": "press"},
      {"type": "fix", "group": "B.start", "dofs": ["y"], "displacement": [0, -0.6, 0], "table": "slide"}],
    "contact": {},
    "steps": [{"end_time": 1, "increments": 5}, {"end_time": 2, "increments": 30}]})",
                                             "end_slides_off.json");
  World w(scene);
  const FibreStore& fs = w.fibres();
  const Index tip = fs.firstNode[1] + fs.nodeCount[1] - 1;
  int past = 0;
  double pressed = 0;
  while (!w.finished()) {
    REQUIRE(w.step().status == StepStatus::Converged);
    const double onA = w.reaction(0).force.z() + w.reaction(1).force.z();
    if (w.time() == 1) pressed = std::abs(onA);
    if (x0Of(fs.q, tip).y() >= -0.11) continue;
    ++past;
    CAPTURE(w.time());
    CHECK(std::abs(onA) <= 1e-9);
    CHECK(x0Of(fs.q, tip).z() == doctest::Approx(0.15).epsilon(1e-6));
  }
  CHECK(pressed > 1e-4);  // A carried B before the slide
  CHECK(past >= 3);
}

TEST_CASE("an end face's contact tangent matches finite differences, frictionless and in slip") {
  // The tee: B's end face (at z = 0.3 on B's start) brought 0.2 mm + 3e-4 mm down, into A's top,
  // and, with friction, slid 3e-3 mm along A (past g_T,max): the element on B's end face.
  for (double mu : {0.0, 0.3}) {
    CAPTURE(mu);
    WorldState w;
    w.scene = tee(1);
    w.scene.contact.friction = mu;
    buildWorld(w);
    const FibreStore& fs = w.fibres;
    const auto moveB = [&](const Vec3& by) {
      for (Index n = fs.firstNode[1]; n < fs.firstNode[1] + fs.nodeCount[1]; ++n)
        x0Of(w.fibres.q, n) += by;
    };
    moveB(Vec3(0, 0, -0.2 - 3e-4));
    runStage(w, w.pipeline.detect, 0);  // the friction reference at the pressed state
    moveB(Vec3(mu > 0 ? 3e-3 : 0, 0, 0));
    const ContactElementStore& el = w.trial.elements;
    int faces = 0;
    for (Index e = 0; e < el.size(); ++e) faces += (el.fallback[e] & (kEndFaceI | kEndFaceJ)) != 0;
    REQUIRE(faces > 0);
    runStage(w, w.pipeline.assemble, 0, true);
    double pressed = 0;
    int sliding = 0;
    for (Index e = 0; e < el.size(); ++e) {
      pressed = std::max(pressed, w.trial.forces.normalForce[e]);
      sliding += w.trial.forces.slip[e] != 0;
    }
    REQUIRE(pressed > 0);
    CHECK((sliding > 0) == (mu > 0));
    const Eigen::MatrixXd K = test::fullTangent(w.system);  // both triangles
    CHECK(w.system.symmetric == (mu == 0));
    const Eigen::MatrixXd Kfd = test::finiteDifferenceTangent(w, 0);
    MESSAGE("|K - K_fd| / |K| = " << (K - Kfd).norm() / K.norm());
    CHECK((K - Kfd).norm() <= 1e-6 * K.norm());
  }
}

TEST_CASE("an end whose rim lies under a crossing fibre reports the rim's depth, not the sides'") {
  // A along x, ending at x = 0; B along y at x = c, its axis 2R - delta above A's: with c > 0
  // the centrelines come closest past A's end, and the deepest point of A in B is the top of
  // A's end rim, (0, 0, R), at sqrt(c^2 + (R - delta)^2) from B's axis: a depth of
  // R - sqrt(c^2 + (R - delta)^2) (1.49e-3 mm for c = 0.01, delta = 0.002). With c < 0, B lies
  // over A's side before the end: delta. Everything is clamped (the reference state); the
  // elements' deepest penetration and the acceptance's true overlap must both give that. With 8
  // elements per fibre the zone is a point zone; with 40 (h = R / 2) a long one, whose nearest
  // element goes to the end (the fibres cross at 90 deg, more than theta_cross). (Before the end,
  // c < 0, with 40 elements the crossing is no narrow minimum at this p_max and the long zone's
  // Gauss elements sample it as any line contact: not this test's subject.)
  constexpr double R = 0.1, delta = 0.002;
  for (const int elements : {8, 40})
  for (const double c : {0.005, 0.01, -0.01}) {
    if (elements == 40 && c < 0) continue;
    CAPTURE(elements);
    CAPTURE(c);
    const std::string x = std::to_string(c), z = std::to_string(2 * R - delta);
    const std::string n = std::to_string(elements);
    const SceneDef scene = loadSceneFromString(R"({
      "units": "mm-N-MPa",
      "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
      "fibres": [
        {"name": "A", "material": "m", "radius": 0.1, "elements": )" + n + R"(,
         "geometry": {"type": "line", "points": [[-2, 0, 0], [0, 0, 0]], "director": [0, 0, 1]}},
        {"name": "B", "material": "m", "radius": 0.1, "elements": )" + n + R"(,
         "geometry": {"type": "line", "points": [[)" + x + ", -1, " + z + "], [" + x + ", 1, " + z + R"(]],
                      "director": [0, 0, 1]}}],
      "boundary_conditions": [{"type": "clamp", "group": "A.all"}, {"type": "clamp", "group": "B.all"}],
      "contact": {"max_penetration": 0.01},
      "steps": [{"end_time": 1, "increments": 1}]})",
                                               "rim.json");
    World w(scene);
    const StepReport r = w.step();
    REQUIRE(r.status == StepStatus::Converged);
    const double expected = c > 0 ? R - std::hypot(c, R - delta) : delta;
    const ContactElementStore& el = w.contact().elements;
    double deepest = 0;
    int onFace = 0;
    for (Index e = 0; e < el.size(); ++e) {
      deepest = std::max(deepest, -el.gap[e]);
      onFace += (el.fallback[e] & (kEndFaceI | kEndFaceJ)) != 0;
    }
    MESSAGE(elements << " elements, c " << c << ": depth " << expected << " mm, elements "
                     << deepest << " (" << onFace << " on the end face, " << el.size()
                     << " in all), acceptance " << r.contact.maxOverlap);
    if (elements == 40) CHECK(el.size() > 1);
    CHECK(deepest == doctest::Approx(expected).epsilon(1e-6).scale(0));
    CHECK(r.contact.maxOverlap == doctest::Approx(expected).epsilon(1e-6).scale(0));
    CHECK((onFace >= 1) == (c > 0));
  }
}
