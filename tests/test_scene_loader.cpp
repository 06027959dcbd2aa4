// Scene loader on good input: the samples load to the SceneDef they describe, every key of the
// format reaches its Def field (units converted where the file differs), and defaults are the
// Def structs'.
#include "io/scene_loader.h"
#include "io/scene_validate.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace fibra;
using namespace fibra::test;

namespace {

const double kPi = std::numbers::pi;

bool same(const Table& a, const std::vector<double>& t, const std::vector<double>& v) {
  return a.t == t && a.v == v;
}

// Every section of the format, each key given a value other than its default.
const char* const kFullScene = R"({
  /* block comments and */ // line comments are allowed
  "description": "every key",
  "units": "mm-N-MPa",
  "materials": [{"name": "glass", "young_modulus": 73000, "poisson_ratio": 0.25,
                 "bending_factor": 0.12, "torsion_factor": 0.5, "law": "neo_hookean"}],
  "fibres": [
    {"name": "a", "material": "glass", "radius": 0.026, "elements": 5, "order": 1,
     "geometry": {"type": "polyline", "points": [[0, 0, 0], [1, 0, 0], [2, 1, 0]], "director": [0, 0, 1]},
     "integration": {"axial": "full", "section": "quadrature", "rings": 2, "sectors": 6}},
    {"name": "h", "material": "glass", "radius": 0.01, "elements": 6,
     "geometry": {"type": "helix", "origin": [1, 2, 3], "axis": [1, 0, 0], "radius": 0.3,
                  "pitch": 0.2, "turns": -1.5, "phase": 0.25}}
  ],
  "groups": [{"name": "mid", "fibre": "a", "nodes": [2, 3]}],
  "tables": {"ramp": [[0, 0], [1, 1]], "turn": [[0, 0], [2, 3.14]]},
  "boundary_conditions": [
    {"type": "clamp", "group": "a.start", "displacement": [0, 0, -0.1], "table": [[0, 0], [2, 1]],
     "rotation": {"axis": [0, 0, 2], "centre": [0, 0, 0], "angle": "turn"}},
    {"type": "fix", "group": "a.end", "dofs": ["x0", "g1z"]},
    {"type": "pin", "group": "h.all"}
  ],
  "loads": [
    {"type": "line_force", "group": "a.all", "vector": [0, 0, -1e-3], "table": "ramp"},
    {"type": "moment", "group": "mid", "vector": [1e-4, 0, 0]}
  ],
  "steps": [
    {"name": "press", "end_time": 1, "increments": 4, "max_iterations": 20, "force_tolerance": 1e-9,
     "increment_tolerance": 1e-11, "max_cutbacks": 3, "line_search": true, "output_every": 2},
    {"end_time": 2.5, "damping": 0.01, "damping_from": "failure"}
  ],
  "contact": {"proximity_distance": 0.06, "test_point_spacing": 0.01, "theta_cross_deg": 30,
              "theta_parallel_deg": 10, "self_contact": true, "self_contact_separation": 0.5,
              "skin": 0.02, "max_penetration": 2e-4, "regularisation": 0.25, "initial_penalty": 100,
              "penalty_change": 4, "friction": 0.1, "max_reversible_slip": 5e-4,
              "friction_tangent": "symmetrised", "max_detection_loops": 5, "max_normal_loops": 2,
              "friction_hold_after": 3, "friction_hold_tolerance": 0.02, "normal_acceleration": 5,
              "step_penetration": 3},
  "tools": [
    {"name": "floor", "type": "plane", "point": [0, 0, -1], "normal": [0, 0, 1], "friction": 0.2,
     "max_penetration": 1e-4, "displacement": [0, 0, 0.5], "table": "ramp"},
    {"name": "roller", "type": "cylinder", "point": [1, 0, 1], "axis": [0, 1, 0], "radius": 0.4,
     "inside": true, "rotation": {"axis": [0, 1, 0], "angle": [[0, 0], [1, 1]]}}
  ],
  "stabilisation": {"stiffness": 1e-3, "fibres": ["a"]},
  "output": {"vtu": false, "history": false, "final_state": false, "moment_point": [1, 2, 3],
             "probes": [{"name": "tip", "fibre": "h", "node": 12}]}
})";

}  // namespace

TEST_CASE("scene loader: the cantilever sample loads to its SceneDef") {
  const SceneDef s = loadScene(sourcePath("samples/cantilever.json"));
  CHECK(s.units == "mm-N-MPa");
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].name == "polymer");
  CHECK(s.materials[0].youngModulus == 4000);
  CHECK(s.materials[0].poissonRatio == 0.3);
  CHECK(s.materials[0].bendingFactor == 1);
  CHECK(s.materials[0].law == MaterialLaw::SaintVenantKirchhoff);
  REQUIRE(s.fibres.size() == 1);
  const FibreDef& f = s.fibres[0];
  CHECK(f.name == "beam");
  CHECK(f.material == "polymer");
  CHECK(f.radius == 0.1);
  CHECK(f.elements == 10);
  CHECK(f.order == 2);
  CHECK(f.geometry.kind == GeometryKind::Line);
  REQUIRE(f.geometry.points.size() == 2);
  CHECK(f.geometry.points[1] == Vec3(10, 0, 0));
  CHECK(f.geometry.director == Vec3(0, 1, 0));
  CHECK(f.integration.axial == AxialRule::Reduced);
  CHECK(f.integration.section == SectionRule::Quadrature);
  REQUIRE(s.bcs.size() == 1);
  CHECK(s.bcs[0].kind == BcKind::Clamp);
  CHECK(s.bcs[0].group == "beam.start");
  REQUIRE(s.loads.size() == 1);
  CHECK(s.loads[0].kind == LoadKind::Force);
  CHECK(s.loads[0].group == "beam.end");
  // P = 3 EI / L^2, as the sample says.
  const double EI = 4000 * kPi * std::pow(0.1, 4) / 4;
  CHECK(s.loads[0].vector.y() == doctest::Approx(-3 * EI / 100).epsilon(1e-14).scale(0));
  CHECK(same(s.loads[0].table, {0, 1}, {0, 1}));
  REQUIRE(s.steps.size() == 1);
  CHECK(s.steps[0].name == "load");
  CHECK(s.steps[0].increments == 10);
  CHECK(s.steps[0].maxIterations == StepDef{}.maxIterations);
  CHECK(s.steps[0].forceTolerance == StepDef{}.forceTolerance);
  CHECK_FALSE(s.contact.enabled);
  REQUIRE(s.output.probes.size() == 1);
  CHECK(s.output.probes[0].fibre == "beam");
  CHECK(s.output.probes[0].node == 20);  // "end" of 10 quadratic elements
  CHECK(s.output.vtu);
  CHECK(s.output.history);
  CHECK(s.output.finalState);
}

TEST_CASE("scene loader: the roll-up sample's end moment is 2 pi EI / L") {
  const SceneDef s = loadScene(sourcePath("samples/rollup.json"));
  const FibreDef& f = s.fibres.at(0);
  const double L = (f.geometry.points.at(1) - f.geometry.points.at(0)).norm();
  const double EI = s.materials.at(0).youngModulus * kPi * std::pow(f.radius, 4) / 4;
  REQUIRE(s.loads.size() == 1);
  CHECK(s.loads[0].kind == LoadKind::Moment);
  CHECK(s.loads[0].vector.z() == doctest::Approx(2 * kPi * EI / L).epsilon(1e-14).scale(0));
  CHECK(s.steps.at(0).outputEvery == 2);
}

TEST_CASE("scene loader: the helix sample resolves its named table into both steps") {
  const SceneDef s = loadScene(sourcePath("samples/helix.json"));
  const GeometryDef& g = s.fibres.at(0).geometry;
  CHECK(g.kind == GeometryKind::Helix);
  CHECK(g.helixRadius == 0.5);
  CHECK(g.pitch == 0.5);
  CHECK(g.turns == 3);
  CHECK(g.axis == Vec3(0, 0, 1));
  REQUIRE(s.bcs.size() == 2);
  CHECK(s.bcs[1].displacement == Vec3(0, 0, 1));
  CHECK(same(s.bcs[1].displacementTable, {0, 1, 2}, {0, 1, 0.5}));
  REQUIRE(s.steps.size() == 2);
  CHECK(s.steps[0].endTime == 1);
  CHECK(s.steps[1].endTime == 2);
  CHECK(s.steps[1].name == "release");
}

TEST_CASE("scene loader: every key of the format reaches its Def field") {
  const SceneDef s = loadSceneFromString(kFullScene, "full.json");
  const MaterialDef& m = s.materials.at(0);
  CHECK(m.youngModulus == 73000);
  CHECK(m.poissonRatio == 0.25);
  CHECK(m.bendingFactor == 0.12);
  CHECK(m.torsionFactor == 0.5);
  CHECK(m.law == MaterialLaw::NeoHookean);

  const FibreDef& a = s.fibres.at(0);
  CHECK(a.order == 1);
  CHECK(a.geometry.kind == GeometryKind::Polyline);
  CHECK(a.geometry.points.size() == 3);
  CHECK(a.geometry.director == Vec3(0, 0, 1));
  CHECK(a.integration.axial == AxialRule::Full);
  CHECK(a.integration.section == SectionRule::Quadrature);
  CHECK(a.integration.rings == 2);
  CHECK(a.integration.sectors == 6);
  const GeometryDef& h = s.fibres.at(1).geometry;
  CHECK(h.origin == Vec3(1, 2, 3));
  CHECK(h.axis == Vec3(1, 0, 0));
  CHECK(h.helixRadius == 0.3);
  CHECK(h.pitch == 0.2);
  CHECK(h.turns == -1.5);
  CHECK(h.phase == 0.25);

  CHECK(s.groups.at(0).nodes == std::vector<int>{2, 3});
  const BcDef& c = s.bcs.at(0);
  CHECK(c.displacement == Vec3(0, 0, -0.1));
  CHECK(same(c.displacementTable, {0, 2}, {0, 1}));
  CHECK(c.rotates);
  CHECK(c.axis == Vec3(0, 0, 2));
  CHECK(c.centre == Vec3(0, 0, 0));
  CHECK(same(c.angle, {0, 2}, {0, 3.14}));
  const BcDef& fix = s.bcs.at(1);
  CHECK(fix.kind == BcKind::Fix);
  CHECK(fix.dofs == std::array<bool, 9>{true, true, true, false, false, true, false, false, false});
  CHECK_FALSE(fix.rotates);
  CHECK(fix.centre.array().isNaN().all());
  CHECK(s.bcs.at(2).kind == BcKind::Pin);

  CHECK(s.loads.at(0).kind == LoadKind::LineForce);
  CHECK(s.loads.at(1).kind == LoadKind::Moment);
  CHECK(same(s.loads.at(1).table, {0, 1}, {0, 1}));  // default ramp

  const StepDef& st = s.steps.at(0);
  CHECK(st.name == "press");
  CHECK(st.maxIterations == 20);
  CHECK(st.forceTolerance == 1e-9);
  CHECK(st.incrementTolerance == 1e-11);
  CHECK(st.maxCutbacks == 3);
  CHECK(st.lineSearch);
  CHECK(st.outputEvery == 2);
  CHECK(s.steps.at(1).endTime == 2.5);
  CHECK(s.steps.at(1).increments == 1);
  CHECK(s.steps.at(1).damping == 0.01);
  CHECK(s.steps.at(1).dampingFrom == DampingFrom::Failure);
  CHECK(st.dampingFrom == DampingFrom::Start);

  const ContactDef& k = s.contact;
  CHECK(k.enabled);  // a contact section turns contact on
  CHECK(k.proximityDistance == 0.06);
  CHECK(k.testPointSpacing == 0.01);
  CHECK(k.thetaCross == doctest::Approx(kPi / 6).epsilon(1e-15));  // degrees in the file
  CHECK(k.thetaParallel == doctest::Approx(kPi / 18).epsilon(1e-15).scale(0));
  CHECK(k.selfContact);
  CHECK(k.selfContactSeparation == 0.5);
  CHECK(k.skin == 0.02);
  CHECK(k.maxPenetration == 2e-4);
  CHECK(k.regularisation == 0.25);
  CHECK(k.initialPenalty == 100);
  CHECK(k.penaltyChange == 4);
  CHECK(k.friction == 0.1);
  CHECK(k.maxReversibleSlip == 5e-4);
  CHECK(k.frictionTangent == FrictionTangent::Symmetrised);
  CHECK(k.maxDetectionLoops == 5);
  CHECK(k.maxNormalLoops == 2);
  CHECK(k.frictionHoldAfter == 3);
  CHECK(k.frictionHoldTolerance == 0.02);
  CHECK(k.normalAcceleration == 5);
  CHECK(k.stepPenetration == 3);

  const ToolDef& plane = s.tools.at(0);
  CHECK(plane.kind == ToolKind::Plane);
  CHECK(plane.point == Vec3(0, 0, -1));
  CHECK(plane.direction == Vec3(0, 0, 1));
  CHECK(plane.friction == 0.2);
  CHECK(plane.maxPenetration == 1e-4);
  CHECK(plane.displacement == Vec3(0, 0, 0.5));
  const ToolDef& roller = s.tools.at(1);
  CHECK(roller.kind == ToolKind::Cylinder);
  CHECK(roller.direction == Vec3(0, 1, 0));
  CHECK(roller.radius == 0.4);
  CHECK(roller.inside);
  CHECK(roller.rotates);
  CHECK(same(roller.angle, {0, 1}, {0, 1}));

  CHECK(s.stabilisation.stiffness == 1e-3);
  CHECK(s.stabilisation.fibres == std::vector<std::string>{"a"});
  CHECK_FALSE(s.output.vtu);
  CHECK_FALSE(s.output.history);
  CHECK_FALSE(s.output.finalState);
  CHECK(s.output.momentPoint == Vec3(1, 2, 3));
  CHECK(s.output.probes.at(0).name == "tip");
}

TEST_CASE("scene loader: absent sections and keys take the Def structs' defaults") {
  const SceneDef s = loadSceneFromString(R"({"units": "mm-N-MPa",
      "materials": [{"name": "m", "young_modulus": 1}],
      "fibres": [{"name": "f", "material": "m", "radius": 1, "elements": 1,
                  "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
      "steps": [{}]})",
                                         "minimal.json");
  CHECK(s.materials[0].poissonRatio == MaterialDef{}.poissonRatio);
  CHECK(s.fibres[0].order == FibreDef{}.order);
  CHECK(s.fibres[0].geometry.director.array().isNaN().all());
  CHECK(s.steps[0].endTime == StepDef{}.endTime);
  CHECK(s.steps[0].increments == StepDef{}.increments);
  CHECK(s.steps[0].maxCutbacks == StepDef{}.maxCutbacks);
  CHECK_FALSE(s.contact.enabled);
  CHECK(std::isnan(s.contact.proximityDistance));
  CHECK(s.tools.empty());
  CHECK(s.stabilisation.stiffness == 0);
  CHECK(s.output.vtu);
  CHECK(s.output.momentPoint == Vec3::Zero());

  const SceneDef off = loadSceneFromString(R"({"units": "mm-N-MPa",
      "materials": [{"name": "m", "young_modulus": 1}],
      "fibres": [{"name": "f", "material": "m", "radius": 1, "elements": 1,
                  "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
      "contact": {"enabled": false, "friction": 0.3}, "steps": [{}]})",
                                           "off.json");
  CHECK_FALSE(off.contact.enabled);
  CHECK(off.contact.friction == 0.3);
  CHECK(std::isnan(off.contact.thetaCross));  // NaN stays NaN through the degree conversion
}

TEST_CASE("scene loader: boundary conditions on different DOFs of one node do not conflict") {
  const std::string text = R"({"units": "mm-N-MPa",
      "materials": [{"name": "m", "young_modulus": 1}],
      "fibres": [{"name": "f", "material": "m", "radius": 1, "elements": 2,
                  "geometry": {"type": "line", "points": [[0, 0, 0], [1, 0, 0]]}}],
      "boundary_conditions": [{"type": "fix", "group": "f.start", "dofs": ["x", "g1"]},
                              {"type": "fix", "group": "f.start", "dofs": ["y", "z", "g2"]}],
      "steps": [{}]})";
  CHECK(loadSceneFromString(text, "split.json").bcs.size() == 2);
}

TEST_CASE("validateScene accepts a scene built in code and names fields as the file does") {
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  FibreDef f;
  f.name = std::string("b");
  f.material = "m";
  f.radius = 0.1;
  f.elements = 4;
  f.geometry.points = {Vec3::Zero(), Vec3(1, 0, 0)};
  s.fibres.push_back(f);
  s.steps.push_back({});
  CHECK_NOTHROW(validateScene(s));
  s.fibres[0].radius = 0;
  CHECK(errorOf([&] { validateScene(s); }) == "fibres[0].radius: must be > 0, got 0");
  s.fibres[0].radius = 0.1;
  s.contact.thetaCross = kPi;  // radians in code, degrees in the message as in the file
  CHECK(errorOf([&] { validateScene(s); }) ==
        "contact.theta_cross_deg: must be in [0, 90] degrees, got 180");
  s.contact.thetaCross = kPi / 4;
  s.tools.push_back({});
  s.tools[0].name = "roll";
  s.tools[0].kind = ToolKind::Cylinder;
  CHECK(errorOf([&] { validateScene(s); }) == "tools[0].radius: must be > 0, got 0");
  s.tools[0].radius = 1;
  s.tools[0].direction = Vec3::Zero();
  CHECK(errorOf([&] { validateScene(s); }) == "tools[0].axis: must be a finite, non-zero vector");
  s.tools[0].direction = Vec3::UnitZ();
  s.steps[0].increments = 0;
  CHECK(errorOf([&] { validateScene(s); }) == "steps[0].increments: must be in [1, 1000000], got 0");
}
