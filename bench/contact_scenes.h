// Contact scenes shared by the benches, built as SceneDefs through the public API.
//
// bundle(rings, elements, squeeze, pMax, mu): a hexagonal bundle of 1 + 3 rings (rings + 1)
// touching fibres (R = 0.1 mm, L = 4 mm, E = 4000 MPa) along x, pressed in z between two plane
// tools, the top one moving down by `squeeze` mm in 10 increments; ends held axially (x, y),
// friction mu between fibres and with the tools, p_max in mm, stabilisation 1e-4 N/mm. Each
// fibre is free to spin about its axis: only friction holds that spin, and not at all once every
// contact of the fibre slips (holdEndSpin below removes the mode).
// holdEndSpin(s): also holds the y component of the director g1 (z at the start) at every held
// end: the section's spin about the fibre axis there, to first order (ends gripped in jaws).
// twistedBundle(rings, elements, pMax, mu): the same bundle without tools, every fibre clamped
// at both ends; step 1 pulls the end sections by 0.004 mm (0.1% strain) in 2 increments, step 2
// turns them by 90 degrees about the bundle axis (x, through the end centre) under that
// tension, in 10 increments.
#pragma once

#include "engine/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace fibra::scenes {

// Centres of a hexagonal section of touching fibres of radius R, in the y-z plane.
inline std::vector<Vec3> hexagonalCentres(int rings, double R) {
  std::vector<Vec3> centres{Vec3::Zero()};
  for (int ring = 1; ring <= rings; ++ring)
    for (int side = 0; side < 6; ++side)
      for (int k = 0; k < ring; ++k) {
        const double a = side * std::numbers::pi / 3, b = a + 2 * std::numbers::pi / 3;
        const Vec3 corner(0, std::cos(a), std::sin(a)), step(0, std::cos(b), std::sin(b));
        centres.push_back(2 * R * (ring * corner + k * step));
      }
  return centres;
}

// The bundle's material and fibres (named f0, f1, ... from the centre out), along x.
inline SceneDef bundleFibres(int rings, int elements, double L, double R) {
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  const std::vector<Vec3> centres = hexagonalCentres(rings, R);
  for (size_t i = 0; i < centres.size(); ++i) {
    FibreDef f;
    f.name = "f" + std::to_string(i);
    f.material = "m";
    f.radius = R;
    f.elements = elements;
    f.geometry.points = {centres[i] - Vec3(L / 2, 0, 0), centres[i] + Vec3(L / 2, 0, 0)};
    f.geometry.director = Vec3::UnitZ();
    s.fibres.push_back(f);
  }
  return s;
}

inline SceneDef bundle(int rings, int elements, double squeeze, double pMax, double mu) {
  const double L = 4, R = 0.1;
  SceneDef s = bundleFibres(rings, elements, L, R);
  double top = 0;
  for (const FibreDef& f : s.fibres) {
    for (const char* end : {".start", ".end"}) {
      BcDef b;
      b.kind = BcKind::Fix;
      b.group = f.name + end;
      b.dofs[X] = true;
      b.dofs[Y] = true;
      s.bcs.push_back(b);
    }
    top = std::max(top, f.geometry.points[0].z());
  }
  for (int side : {-1, 1}) {
    ToolDef t;
    t.name = side < 0 ? "bottom" : "top";
    t.point = Vec3(0, 0, side * (top + R));
    t.direction = Vec3(0, 0, -side);
    if (side > 0) t.displacement = Vec3(0, 0, -squeeze);
    t.friction = mu;
    s.tools.push_back(t);
  }
  s.contact.enabled = true;
  s.contact.friction = mu;
  s.contact.maxPenetration = pMax;
  s.stabilisation.stiffness = 1e-4;
  StepDef st;
  st.increments = 10;
  s.steps.push_back(st);
  return s;
}

inline void holdEndSpin(SceneDef& s) {
  for (BcDef& b : s.bcs)
    if (b.kind == BcKind::Fix) b.dofs[G1Y] = true;
}

inline SceneDef twistedBundle(int rings, int elements, double pMax, double mu) {
  const double L = 4, R = 0.1;
  SceneDef s = bundleFibres(rings, elements, L, R);
  for (const FibreDef& f : s.fibres) {
    BcDef start;
    start.kind = BcKind::Clamp;
    start.group = f.name + ".start";
    s.bcs.push_back(start);
    BcDef end = start;
    end.group = f.name + ".end";
    end.displacement = Vec3(0.004, 0, 0);  // the default ramp: 0.1% strain at t = 1, then held
    end.rotates = true;
    end.axis = Vec3::UnitX();
    end.centre = Vec3(L / 2, 0, 0);
    end.angle = {{0, 1, 2}, {0, 0, std::numbers::pi / 2}};
    s.bcs.push_back(end);
  }
  s.contact.enabled = true;
  s.contact.friction = mu;
  s.contact.maxPenetration = pMax;
  StepDef pull;
  pull.name = "pull";
  pull.increments = 2;
  s.steps.push_back(pull);
  StepDef twist;
  twist.name = "twist";
  twist.endTime = 2;
  twist.increments = 10;
  s.steps.push_back(twist);
  return s;
}

}  // namespace fibra::scenes
