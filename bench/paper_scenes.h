// Paper-size contact scenes for the linear-solve bench, as SceneDefs (bench/contact_assemblies.h
// gives the layouts):
// - yarnScene(fibres, mu): the twisted yarn of the paper's Table 2 (fibre diameter 0.02 mm,
//   15 quadratic elements, E = 73 000 MPa, nu = 0.3), packed at `clearance` (neighbour
//   distance / 2R; 1: touching, so that contact is detected from the start; at 0.995 they
//   overlap by 1e-4 mm, and Newton does not converge in the first increment even with exact
//   solves); squeezed in x between two plane tools touching its outermost fibres, the one at
//   +x moving by `squeeze` mm over the step's increments. Fibre ends held axially (z) and in y.
// - fabricScene(mu): the 480-fibre plain weave (10 yarns x 48 fibres, diameter 0.052 mm,
//   40 quadratic elements), packed at 0.995 inside the yarns; fibre ends held in x, y, z.
// Both: fibre-fibre contact with friction mu (0: frictionless), stabilisation 1e-4 N/mm.
#pragma once

#include "bench/contact_assemblies.h"
#include "engine/scene.h"

#include <algorithm>

namespace fibra::scenes {

// Holds the listed translations of both ends of every fibre.
inline void holdEnds(SceneDef& s, std::initializer_list<int> dofs) {
  for (const FibreDef& f : s.fibres)
    for (const char* end : {".start", ".end"}) {
      BcDef b;
      b.kind = BcKind::Fix;
      b.group = f.name + end;
      for (int d : dofs) b.dofs[d] = true;
      s.bcs.push_back(b);
    }
}

inline void contactSettings(SceneDef& s, double mu, int increments) {
  s.contact.enabled = true;
  s.contact.friction = mu;
  s.stabilisation.stiffness = 1e-4;
  StepDef st;
  st.increments = increments;
  s.steps.push_back(st);
}

inline SceneDef yarnScene(int fibres, double mu, double squeeze = 0.002, int increments = 5,
                          double clearance = 1.0) {
  SceneDef s;
  s.materials.push_back({"m", 73000, 0.3, 1, 1});
  assemblies::YarnDef y;
  y.fibres = fibres;
  y.clearance = clearance;
  double outer = 0;
  for (FibreDef f : assemblies::yarnFibres(y)) {
    f.material = "m";
    outer = std::max(outer, f.geometry.helixRadius);
    s.fibres.push_back(f);
  }
  holdEnds(s, {Z, Y});
  for (int side : {-1, 1}) {
    ToolDef t;
    t.name = side < 0 ? "left" : "right";
    t.point = Vec3(side * (outer + y.radius), 0, 0);
    t.direction = Vec3(-side, 0, 0);
    if (side > 0) t.displacement = Vec3(-squeeze, 0, 0);
    t.friction = mu;
    s.tools.push_back(t);
  }
  contactSettings(s, mu, increments);
  return s;
}

inline SceneDef fabricScene(double mu, int increments = 1) {
  SceneDef s;
  s.materials.push_back({"m", 73000, 0.3, 1, 1});
  assemblies::WovenDef w;
  w.clearance = 0.995;
  int k = 0;
  for (FibreDef f : assemblies::wovenFibres(w)) {
    f.name.append("_").append(std::to_string(k++));
    f.material = "m";
    s.fibres.push_back(f);
  }
  holdEnds(s, {X, Y, Z});
  contactSettings(s, mu, increments);
  return s;
}

}  // namespace fibra::scenes
