// Beam stiffnesses against closed form (small strains): EA with free Poisson contraction, EI
// about both section axes (bending factor 1 and 0.12), GJ (torsion factor 1 and 0.5), at
// slenderness L/R = 100 and 1000, nu = 0.3, for both material laws (Saint Venant-Kirchhoff's
// Poisson-locking cure is a constitutive split, neo-Hookean's enhanced transverse strains).
// Tolerance 1%.
#include "beam_fixtures.h"

#include <doctest/doctest.h>

using namespace fibra;
using namespace fibra::test;

namespace {

constexpr MaterialLaw kLaws[] = {MaterialLaw::SaintVenantKirchhoff, MaterialLaw::NeoHookean};

BeamSpec spec(double slenderness, MaterialLaw law, double fBend = 1, double fTors = 1) {
  BeamSpec b;
  b.law = law;
  b.radius = b.length / slenderness;
  b.bendingFactor = fBend;
  b.torsionFactor = fTors;
  return b;
}

double rel(double value, double expected) { return std::abs(value / expected - 1); }

}  // namespace

TEST_CASE("axial stiffness EA and Poisson contraction") {
  for (MaterialLaw law : kLaws)
  for (double slenderness : {100.0, 1000.0}) {
    CAPTURE(int(law));
    CAPTURE(slenderness);
    const BeamSpec b = spec(slenderness, law);
    SceneDef s = straightBeam(b);
    // Start: centroid pinned, directors kept in direction (g1 along y, g2 along z) but free to
    // change length, so the section contracts freely everywhere.
    BcDef pin;
    pin.kind = BcKind::Pin;
    pin.group = "b.start";
    BcDef dirs;
    dirs.kind = BcKind::Fix;
    dirs.group = "b.start";
    dirs.dofs[G1X] = dirs.dofs[G1Z] = dirs.dofs[G2X] = dirs.dofs[G2Y] = true;
    s.bcs = {pin, dirs};
    const double EA = b.young * area(b), F = 1e-6 * EA;
    tipLoad(s, LoadKind::Force, Vec3(F, 0, 0));
    World w(s);
    REQUIRE(solveAll(w));
    const double strain = (tipPosition(w).x() - b.length) / b.length;
    CHECK(rel(F / strain, EA) < 0.01);
    const Index mid = w.fibres().nodes() / 2;
    const double contraction = g1Of(w.fibres().q, mid).norm() - 1;
    CHECK(rel(-contraction / strain, b.poisson) < 0.01);
    CHECK(rel(-(g2Of(w.fibres().q, mid).norm() - 1) / strain, b.poisson) < 0.01);
  }
}

TEST_CASE("bending stiffness EI about both axes, with the reduction factor") {
  for (MaterialLaw law : kLaws)
  for (double slenderness : {100.0, 1000.0})
    for (double fBend : {1.0, 0.12}) {
      CAPTURE(int(law));
      CAPTURE(slenderness);
      CAPTURE(fBend);
      const BeamSpec b = spec(slenderness, law, fBend);
      const double EI = bendingStiffness(b), M = 1e-3 * EI / b.length;
      // Moment about z bends in the xy plane and turns g1 (along y); about y turns g2 (along z).
      for (int axis : {2, 1}) {
        CAPTURE(axis);
        SceneDef s = straightBeam(b);
        clampStart(s);
        tipLoad(s, LoadKind::Moment, M * Vec3::Unit(axis));
        World w(s);
        REQUIRE(solveAll(w));
        const Vec3 g = tipDirector(w, axis == 2 ? 1 : 2);
        const double theta = axis == 2 ? std::atan2(-g.x(), g.y()) : std::atan2(g.x(), g.z());
        CHECK(rel(theta, M * b.length / EI) < 0.01);
        const double deflection = axis == 2 ? tipPosition(w).y() : -tipPosition(w).z();
        CHECK(rel(deflection, M * b.length * b.length / (2 * EI)) < 0.01);
      }
    }
}

TEST_CASE("torsion stiffness GJ, with the torsion factor") {
  for (MaterialLaw law : kLaws)
  for (double slenderness : {100.0, 1000.0})
    for (double fTors : {1.0, 0.5}) {
      CAPTURE(int(law));
      CAPTURE(slenderness);
      CAPTURE(fTors);
      const BeamSpec b = spec(slenderness, law, 1, fTors);
      const double G = b.young / (2 * (1 + b.poisson));
      const double GJ = fTors * G * std::numbers::pi * std::pow(b.radius, 4) / 2;
      const double T = 1e-3 * GJ / b.length;
      SceneDef s = straightBeam(b);
      clampStart(s);
      tipLoad(s, LoadKind::Moment, Vec3(T, 0, 0));
      World w(s);
      REQUIRE(solveAll(w));
      const Vec3 g1 = tipDirector(w, 1);
      CHECK(rel(std::atan2(g1.z(), g1.y()), T * b.length / GJ) < 0.01);
    }
}

TEST_CASE("no shear locking: a slender cantilever under a tip force bends as PL^3 / 3EI") {
  for (MaterialLaw law : kLaws)
  for (double slenderness : {100.0, 1000.0}) {
    CAPTURE(int(law));
    CAPTURE(slenderness);
    const BeamSpec b = spec(slenderness, law);
    const double EI = bendingStiffness(b), P = 1e-4 * EI / (b.length * b.length);
    SceneDef s = straightBeam(b);
    clampStart(s);
    tipLoad(s, LoadKind::Force, Vec3(0, -P, 0));
    World w(s);
    REQUIRE(solveAll(w));
    CHECK(rel(-tipPosition(w).y(), P * std::pow(b.length, 3) / (3 * EI)) < 0.01);
  }
}

TEST_CASE("a uniform line load on a simply supported beam: midspan deflection 5 w L^4 / 384 EI") {
  for (int order : {1, 2}) {
    CAPTURE(order);
    BeamSpec b = spec(100, MaterialLaw::SaintVenantKirchhoff);
    b.order = order;
    b.elements = order == 2 ? 10 : 40;
    const double EI = bendingStiffness(b), w = 1e-5 * EI / std::pow(b.length, 3);
    SceneDef s = straightBeam(b);
    for (const char* end : {"b.start", "b.end"}) {
      BcDef pin;
      pin.kind = BcKind::Pin;
      pin.group = end;
      s.bcs.push_back(pin);
    }
    BcDef twist;  // no rotation about the beam's own axis
    twist.kind = BcKind::Fix;
    twist.group = "b.start";
    twist.dofs[G1Z] = true;
    s.bcs.push_back(twist);
    s.loads.push_back({LoadKind::LineForce, "b.all", Vec3(0, -w, 0), {{0, 1}, {0, 1}}});
    World world(s);
    REQUIRE(solveAll(world));
    const Index mid = world.fibres().nodes() / 2;
    CHECK(rel(-x0Of(world.fibres().q, mid).y(), 5 * w * std::pow(b.length, 4) / (384 * EI)) < 0.01);
    CHECK(rel(world.reaction(0).force.y() + world.reaction(1).force.y(), w * b.length) < 1e-9);
  }
}
