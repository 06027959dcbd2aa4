// bending_factor 0 (paper Table 2): a fibre without bending stiffness, whose section keeps its
// own stiffness. Under tension it stretches as Saint Venant-Kirchhoff's uniaxial closed form;
// taut, it carries a transverse load as a string; slack, it has no transverse stiffness at all,
// so a transverse load before any tension needs the stabilisation (docs/SCENE.md).
// torsion_factor 0: refused without the stabilisation (the sections' twist has no stiffness);
// with it, a cantilever that carries no torque follows the elastica.
#include "beam_fixtures.h"
#include "bench/elastica.h"

#include <doctest/doctest.h>

using namespace fibra;
using namespace fibra::test;

namespace {

double relative(double value, double expected) { return std::abs(value / expected - 1); }

BeamSpec glassFibre() {
  BeamSpec b;
  b.length = 1;
  b.radius = 0.01;
  b.elements = 8;
  b.young = 73000;
  b.bendingFactor = 0;
  return b;
}

// The middle node of the beam, where a group "mid" puts the transverse load.
void midLoad(SceneDef& s, const BeamSpec& b, const Vec3& force, const Table& table) {
  s.groups.push_back({"mid", "b", {b.elements}, {}});  // quadratic: node `elements` is mid-span
  LoadDef l;
  l.group = "mid";
  l.vector = force;
  l.table = table;
  s.loads.push_back(l);
}

// Both ends pinned, the end pulled along x by `stretch` (mm) over the first step.
SceneDef taut(const BeamSpec& b, double stretch) {
  SceneDef s = straightBeam(b);
  BcDef start, end;
  start.kind = end.kind = BcKind::Pin;
  start.group = "b.start";
  end.group = "b.end";
  end.displacement = Vec3(stretch, 0, 0);
  end.displacementTable = Table{{0, 1, 2}, {0, 1, 1}};
  s.bcs = {start, end};
  return s;
}

}  // namespace

TEST_CASE("bending_factor 0: a fibre under tension stretches as F = E A lambda (lambda^2 - 1) / 2") {
  const BeamSpec b = glassFibre();
  SceneDef s = straightBeam(b, 4);
  // Start: centroid pinned, directors kept in direction but free to change length (the section
  // contracts freely); the end is free.
  BcDef pin, dirs;
  pin.kind = BcKind::Pin;
  pin.group = dirs.group = "b.start";
  dirs.kind = BcKind::Fix;
  dirs.dofs[G1X] = dirs.dofs[G1Z] = dirs.dofs[G2X] = dirs.dofs[G2Y] = true;
  s.bcs = {pin, dirs};
  const double EA = b.young * area(b), F = 0.02 * EA;  // a 2% stretch: finite strain shows
  tipLoad(s, LoadKind::Force, Vec3(F, 0, 0));
  World w(s);
  REQUIRE(solveAll(w));
  const double lambda = tipPosition(w).x() / b.length;
  // Uniaxial stress in Saint Venant-Kirchhoff: S11 = E E11, E11 = (lambda^2 - 1) / 2, and the
  // force is the first Piola-Kirchhoff stress lambda S11 on the reference area.
  CHECK(relative(lambda * (lambda * lambda - 1) / 2, F / EA) < 1e-9);  // measured 2e-14
  CHECK(std::abs(lambda - 1 - F / EA) > 0.02 * F / EA);  // not the small-strain answer
  CHECK(std::abs(tipPosition(w).y()) < 1e-12);
}

TEST_CASE("bending_factor 0: a taut fibre carries a transverse load as a string, P L / (4 T)") {
  const double stretch = 1e-3;  // mm: strain 1e-3
  // Mid-span deflection over the string's P lambda L / (4 T), for a load P that deflects the
  // string by 1e-4 L (small rotations).
  const auto ratio = [&](double bendingFactor, double radius) {
    BeamSpec b = glassFibre();
    b.bendingFactor = bendingFactor;
    b.radius = radius;
    b.elements = 16;
    const double lambda = 1 + stretch / b.length;
    const double T = b.young * area(b) * lambda * (lambda * lambda - 1) / 2;  // N
    const double P = 4e-4 * T;
    SceneDef s = taut(b, stretch);
    s.steps.push_back(s.steps[0]);
    s.steps[1].endTime = 2;
    midLoad(s, b, Vec3(0, -P, 0), Table{{0, 1, 2}, {0, 0, 1}});
    World w(s);
    REQUIRE(solveAll(w));
    return -x0Of(w.fibres().q, b.elements).y() / (P * lambda * b.length / (4 * T));
  };
  // The section keeps its own stiffness, which stiffens the kinks over a length of the order
  // of R: measured 1.0% at R/L = 0.01, 0.5% at 0.005 (16 elements; the same with 32).
  const double coarse = 1 - ratio(0, 0.01), fine = 1 - ratio(0, 0.005);
  CHECK(coarse > 0);
  CHECK(coarse < 0.012);
  CHECK(relative(fine, coarse / 2) < 0.1);
  // With the full bending stiffness the fibre is much stiffer (EI / (T L^2) = 0.025).
  CHECK(ratio(1, 0.01) < 0.8);
}

TEST_CASE("bending_factor 0: a slack fibre loaded sideways needs the stabilisation") {
  const BeamSpec b = glassFibre();
  const auto solves = [&](double stabilisation) {
    SceneDef s = taut(b, 1e-3);  // tension and transverse load rise together from zero
    s.steps[0].increments = 2;
    midLoad(s, b, Vec3(0, 1e-3, 0), Table{{0, 1}, {0, 1}});
    s.stabilisation.stiffness = stabilisation;
    World w(s);
    return solveAll(w);
  };
  CHECK_FALSE(solves(0));  // the first iteration meets a zero transverse stiffness
  CHECK(solves(1e-3));
}

TEST_CASE("torsion_factor 0: refused without the stabilisation, with it a cantilever follows the elastica") {
  BeamSpec b;  // L/R = 100, 10 quadratic elements
  b.torsionFactor = 0;
  const double lambda = 3, P = lambda * bendingStiffness(b) / (b.length * b.length);
  SceneDef s = straightBeam(b, 10);
  clampStart(s);
  tipLoad(s, LoadKind::Force, Vec3(0, -P, 0));
  std::string refusal;
  try {
    World bare(s);
  } catch (const SceneError& e) {
    refusal = e.what();
  }
  CHECK(refusal.starts_with("materials[0].torsion_factor: 0 leaves the twist of fibre 'b' about "
                            "its centreline without stiffness"));
  // A spring so weak that its force at convergence is 1e-10 of the load's scale.
  s.stabilisation.stiffness = 1e-10;
  World w(s);
  REQUIRE(solveAll(w));
  const Eigen::Vector2d ref = elasticaTip(lambda) * b.length;
  const Vec3 tip = tipPosition(w);
  // Against the same cantilever with the full factor: the factor scales the whole cross-shear
  // fluctuation of the section (docs/SCENE.md), which a varying section stretch feeds too.
  // Measured: 1.4e-4 of the tip's deflection v, 2.0e-4 of its shortening u; each run is within
  // 4.3e-4 of the elastica (the full factor 2.3e-4).
  SceneDef full = s;
  full.materials[0].torsionFactor = 1;
  World withTorsion(full);
  REQUIRE(solveAll(withTorsion));
  const Vec3 t1 = tipPosition(withTorsion);
  CHECK(std::abs(tip.y() - t1.y()) < 2e-4 * std::abs(ref.y()));
  CHECK(std::abs(tip.x() - t1.x()) < 3e-4 * (b.length - ref.x()));
  CHECK(std::abs(tip.y() / ref.y() - 1) < 5e-4);
  CHECK(std::abs((b.length - tip.x()) / (b.length - ref.x()) - 1) < 5e-4);
  // Damping in every step carries it as well.
  s.stabilisation.stiffness = 0;
  s.steps[0].damping = 1e-8;
  World damped(s);
  CHECK(solveAll(damped));
}
