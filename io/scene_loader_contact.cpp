// Scene loader: the contact classes of the scene file (docs/SCENE.md) - a fibre's level table,
// a contact pair-class rule, a step's forced normals. Ranges and cross-references (unknown
// classes, repeated pairs, level order) are checked when the world resolves them
// (engine/contact_classes.h), so that a SceneDef filled in code gets the same errors.
#include "core/format.h"
#include "io/json_reader.h"
#include "io/scene_sections.h"

#include <cmath>

namespace fibra::scene_sections {

using namespace json_reader;

std::vector<LevelDef> readLevels(const Json& j, const std::string& path) {
  if (j.is_number()) return {{0, asNumber(j, path)}};
  if (!j.is_array()) fail(path, typeMismatch("a level or a table [[from, level], ...]", j));
  std::vector<LevelDef> out;
  forEachItem(j, path, [&](const Json& p, const std::string& at) {
    if (!p.is_array() || p.size() != 2) fail(at, typeMismatch("a piece [from, level]", p));
    out.push_back({asNumber(p[0], at + "[0]"), asNumber(p[1], at + "[1]")});
  });
  if (out.empty())
    fail(path, "must list at least one piece [from, level] (or give one level for the whole "
               "fibre)");
  return out;
}

ContactPairDef readContactPair(const Json& j, const std::string& path) {
  const Fields f(j, path, {"classes", "friction", "max_penetration", "penalty_min", "penalty_max"});
  ContactPairDef d;
  const Json& c = f.at("classes");
  if (c.is_string()) {
    const std::string k = asString(c, f.path("classes"));
    if (k != "within" && k != "between")
      fail(f.path("classes"), "must be two class names or \"within\" or \"between\", got \"" +
                                  shown(k) + "\"");
    d.rule = k == "within" ? PairRule::Within : PairRule::Between;
  } else {
    if (!c.is_array())
      fail(f.path("classes"),
           typeMismatch("two class names [a, b] or \"within\" or \"between\"", c));
    if (c.size() != 2)
      fail(f.path("classes"), "must be two class names [a, b] (for the pairs within one class: "
                              "[a, a]), got " + std::to_string(c.size()) +
                                  (c.size() == 1 ? " name" : " names"));
    d.classes = {asString(c[0], f.path("classes") + "[0]"),
                 asString(c[1], f.path("classes") + "[1]")};
  }
  d.friction = f.number("friction", d.friction);
  d.maxPenetration = f.number("max_penetration", d.maxPenetration);
  d.penaltyMin = f.number("penalty_min", d.penaltyMin);
  d.penaltyMax = f.number("penalty_max", d.penaltyMax);
  return d;
}

void readForcedNormals(const Json& j, const std::string& path, StepDef& s) {
  const Fields f(j, path, {"direction", "allowance"});
  const Vec3 d = asVec3(f.at("direction"), f.path("direction"));
  // stableNorm: a direction of huge or tiny components (1e160, 1e-170) neither overflows to a
  // zero normal nor underflows to a refused one.
  if (!d.allFinite() || !(d.stableNorm() > 0))
    fail(f.path("direction"), "must be a finite, non-zero vector");
  s.forcedNormal = d.stableNormalized();
  s.forcedAllowance = f.number("allowance", 0.0);
  if (!(s.forcedAllowance >= 0) || !std::isfinite(s.forcedAllowance))
    fail(f.path("allowance"), "must be a finite overlap >= 0, mm (got " +
                                  number(s.forcedAllowance) + ")");
}

}  // namespace fibra::scene_sections
