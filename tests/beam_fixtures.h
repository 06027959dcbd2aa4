// Scenes for the beam verification tests, built in code.
#pragma once

#include "engine/world.h"

#include <cmath>
#include <numbers>

namespace fibra::test {

struct BeamSpec {
  double length = 10;        // mm
  double radius = 0.1;       // mm
  int elements = 10;
  int order = 2;
  double young = 4000;       // MPa
  double poisson = 0.3;
  double bendingFactor = 1;
  double torsionFactor = 1;
  MaterialLaw law = MaterialLaw::SaintVenantKirchhoff;
  BeamIntegration integration{};
};

inline double inertia(const BeamSpec& b) { return std::numbers::pi * std::pow(b.radius, 4) / 4; }
inline double area(const BeamSpec& b) { return std::numbers::pi * b.radius * b.radius; }
inline double bendingStiffness(const BeamSpec& b) { return b.young * inertia(b) * b.bendingFactor; }

// A straight beam along x from the origin, one material, one step of `increments`.
inline SceneDef straightBeam(const BeamSpec& b, int increments = 1) {
  SceneDef s;
  s.materials.push_back({"m", b.young, b.poisson, b.bendingFactor, b.torsionFactor, b.law});
  FibreDef f;
  f.name = "b";
  f.material = "m";
  f.radius = b.radius;
  f.elements = b.elements;
  f.order = b.order;
  f.geometry.points = {Vec3::Zero(), Vec3(b.length, 0, 0)};
  f.geometry.director = Vec3::UnitY();
  f.integration = b.integration;
  s.fibres.push_back(f);
  StepDef st;
  st.increments = increments;
  s.steps.push_back(st);
  return s;
}

inline void clampStart(SceneDef& s) {
  BcDef c;
  c.kind = BcKind::Clamp;
  c.group = "b.start";
  s.bcs.push_back(c);
}

inline void tipLoad(SceneDef& s, LoadKind kind, const Vec3& v) {
  LoadDef l;
  l.kind = kind;
  l.group = "b.end";
  l.vector = v;
  s.loads.push_back(l);
}

// Runs every increment; false if one did not converge.
inline bool solveAll(World& w) {
  while (!w.finished())
    if (w.step().status != StepStatus::Converged) return false;
  return true;
}

inline Vec3 tipPosition(const World& w) { return x0Of(w.fibres().q, w.fibres().nodes() - 1); }
inline Vec3 tipDirector(const World& w, int a) {
  const Index n = w.fibres().nodes() - 1;
  return a == 1 ? Vec3(g1Of(w.fibres().q, n)) : Vec3(g2Of(w.fibres().q, n));
}

}  // namespace fibra::test
