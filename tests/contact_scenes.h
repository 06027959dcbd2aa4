// Scenes with fibre-fibre contact for the tests and benches, built in code.
#pragma once

#include "engine/world.h"

#include <cmath>
#include <numbers>
#include <string>

namespace fibra::test {

inline FibreDef straightFibre(const std::string& name, const Vec3& a, const Vec3& b, double R,
                              int elements, const Vec3& director) {
  FibreDef f;
  f.name = name;
  f.material = "m";
  f.radius = R;
  f.elements = elements;
  f.geometry.points = {a, b};
  f.geometry.director = director;
  return f;
}

inline void hold(SceneDef& s, const std::string& group, std::initializer_list<Dof> dofs,
                 const Vec3& displacement = Vec3::Zero(), const Table& table = {{0, 1}, {0, 1}}) {
  BcDef b;
  b.kind = BcKind::Fix;
  b.group = group;
  for (Dof d : dofs) b.dofs[d] = true;
  b.displacement = displacement;
  b.displacementTable = table;
  s.bcs.push_back(b);
}

// Two identical simply supported beams (length L, radius R, E = 4000 MPa) crossing at their
// midspans, B on top of A, touching; a force P pushes B's midspan down. A's supports and B's
// supports carry P between them: by symmetry the contact carries P/2 when contact is rigid.
inline SceneDef crossingBeams(double P, double pMax, int elements = 10) {
  const double L = 4, R = 0.1;
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  s.fibres.push_back(straightFibre("A", Vec3(-L / 2, 0, 0), Vec3(L / 2, 0, 0), R, elements, Vec3::UnitZ()));
  s.fibres.push_back(straightFibre("B", Vec3(0, -L / 2, 2 * R), Vec3(0, L / 2, 2 * R), R, elements, Vec3::UnitZ()));
  GroupDef mid{"B.mid", "B", {elements}, {}};  // the midspan node of a quadratic mesh
  s.groups.push_back(mid);
  for (const char* f : {"A", "B"}) {
    hold(s, std::string(f) + ".start", {X, Y, Z});
    hold(s, std::string(f) + ".end", {X, Y, Z});
  }
  hold(s, "A.start", {G1Y});  // no spin of A about x
  hold(s, "B.start", {G1X});  // no spin of B about y
  s.loads.push_back({LoadKind::Force, "B.mid", Vec3(0, 0, -P), {{0, 1}, {0, 1}}});
  s.contact.enabled = true;
  s.contact.maxPenetration = pMax;
  StepDef st;
  st.increments = 4;
  s.steps.push_back(st);
  return s;
}

// crossingBeams(0.01, 1e-4) with friction (fibre-fibre 0.2, g_T,max 5e-4 mm) and A resting on a
// plane tool with friction 0.3: step 1 presses B in `pressIncrements`, then `slide` (its end
// time set to 2) moves B's ends sideways by 0.3 mm.
inline SceneDef slidingCrossing(int pressIncrements, StepDef slide) {
  SceneDef s = crossingBeams(0.01, 1e-4);
  s.contact.friction = 0.2;
  s.contact.maxReversibleSlip = 5e-4;
  ToolDef floor;
  floor.name = "floor";
  floor.point = Vec3(0, 0, -0.1);
  floor.friction = 0.3;
  s.tools.push_back(floor);
  s.steps[0].increments = pressIncrements;
  for (BcDef& b : s.bcs)
    if (b.group == "B.start" || b.group == "B.end") {
      b.displacement = Vec3(0.3, 0, 0);
      b.displacementTable = {{0, 1, 2}, {0, 0, 1}};
    }
  slide.endTime = 2;
  s.steps.push_back(slide);
  return s;
}

// Two parallel beams along x, B on top of A; A rests on a frictionless plane; a uniform line
// load w presses B onto A. Away from the ends the contact line force is w. A tiny stabilisation
// spring holds the beams in the first iterations, before the contacts have stiffness.
inline SceneDef parallelBeams(double w, double pMax, int elements = 16) {
  const double L = 4, R = 0.1;
  SceneDef s;
  s.materials.push_back({"m", 4000, 0.3, 1, 1});
  s.fibres.push_back(straightFibre("A", Vec3(0, 0, R), Vec3(L, 0, R), R, elements, Vec3::UnitZ()));
  s.fibres.push_back(straightFibre("B", Vec3(0, 0, 3 * R), Vec3(L, 0, 3 * R), R, elements, Vec3::UnitZ()));
  for (const char* f : {"A", "B"}) {
    hold(s, std::string(f) + ".start", {X, Y, G1Y});
    hold(s, std::string(f) + ".end", {Y});
  }
  ToolDef floor;
  floor.name = "floor";
  s.tools.push_back(floor);
  s.loads.push_back({LoadKind::LineForce, "B.all", Vec3(0, 0, -w), {{0, 1}, {0, 1}}});
  s.stabilisation.stiffness = 1e-3;  // both beams rest on contacts that start without stiffness
  s.contact.enabled = true;
  s.contact.maxPenetration = pMax;
  StepDef st;
  st.increments = 4;
  s.steps.push_back(st);
  return s;
}

// line_contact_heavy reduced (scene JSON; contactExtra adds to its contact section): a 6 mm frictionless fibre U (R = 0.1 mm, 6 quadratic elements) on a
// clamped parallel fibre D under q = 1 N/mm, p_max = 5e-4 mm; U is held laterally (y) at both
// ends and axially (x) at its start. The lateral gain of plain loop B is ~ q / (2 R K) with K
// U's lateral bending stiffness EI (pi / L)^4 ~ 0.024 N/mm^2 (E 4000 MPa): ~ 200 at full load.
// length: mm, and elements per fibre (10: the shared case line_contact_heavy).
inline std::string heavyLineContact(const std::string& contactExtra, int length = 6) {
  const std::string n = std::to_string(length), h = std::to_string(length / 2.0);
  return R"({
    "units": "mm-N-MPa",
    "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
    "fibres": [
      {"name": "U", "material": "m", "radius": 0.1, "elements": )" + n + R"(, "order": 2,
       "geometry": {"type": "line", "points": [[-)" + h + R"(, 0, 0.2], [)" + h + R"(, 0, 0.2]],
                    "director": [0, 0, 1]}},
      {"name": "D", "material": "m", "radius": 0.1, "elements": )" + n + R"(, "order": 2,
       "geometry": {"type": "line", "points": [[-)" + h + R"(, 0, 0], [)" + h + R"(, 0, 0]],
                    "director": [0, 0, 1]}}],
    "boundary_conditions": [
      {"type": "fix", "group": "U.start", "dofs": ["x", "y", "g1y"]},
      {"type": "fix", "group": "U.end", "dofs": ["y"]},
      {"type": "clamp", "group": "D.all"}],
    "loads": [{"type": "line_force", "group": "U.all", "vector": [0, 0, -1.0]}],
    "contact": {"max_penetration": 0.0005)" +
         contactExtra + R"(},
    "stabilisation": {"stiffness": 1e-05, "fibres": ["U"]},
    "steps": [{"end_time": 1, "increments": 5}]})";
}

}  // namespace fibra::test
