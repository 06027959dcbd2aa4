#include "engine/contact_classes.h"

#include "core/errors.h"
#include "core/format.h"

#include <cmath>
#include <map>
#include <set>
#include <string>

namespace fibra {
namespace {

std::string at(const char* list, size_t i) {
  return std::string(list) + "[" + std::to_string(i) + "]";
}

// Class index of every fibre, in order of first appearance ("" is 0).
std::vector<int> classIndices(const SceneDef& s, std::map<std::string, int>& index) {
  index[""] = 0;
  std::vector<int> out;
  for (const FibreDef& f : s.fibres) {
    const auto [it, fresh] = index.emplace(f.contactClass, int(index.size()));
    out.push_back(it->second);
  }
  return out;
}

void levelTables(const SceneDef& s, ContactClasses& c) {
  c.firstLevel.assign(1, 0);
  for (size_t i = 0; i < s.fibres.size(); ++i) {
    const std::vector<LevelDef>& t = s.fibres[i].levels;
    for (size_t k = 0; k < t.size(); ++k) {
      const std::string path = at("fibres", i) + "." + at("levels", k);
      if (k == 0 && t[k].from != 0)
        throw SceneError(path + ".from: the first piece must start at 0");
      if (k > 0 && !(t[k].from > t[k - 1].from))
        throw SceneError(path + ".from: must exceed the previous piece's start");
      if (!std::isfinite(t[k].level) || !std::isfinite(t[k].from))
        throw SceneError(path + ": must be finite");
      c.levelFrom.push_back(t[k].from);
      c.level.push_back(t[k].level);
    }
    c.firstLevel.push_back(Index(c.levelFrom.size()));
  }
}

// penalty_max >= penalty_min, the rule's or the section's: blames the field the rule gives (a
// penalty_min above the section's penalty_max is the rule's penalty_min).
void checkPenaltyBounds(const ContactPairDef& r, const std::string& path, double lo, double hi) {
  if (hi >= lo && std::isfinite(hi)) return;
  const bool ownMin = !std::isnan(r.penaltyMin), ownMax = !std::isnan(r.penaltyMax);
  if (ownMin && !ownMax)
    throw SceneError(path + ".penalty_min: must be <= penalty_max (" + number(hi) +
                     ", the contact section's; or give the rule its own penalty_max), got " +
                     number(lo));
  throw SceneError(path + ".penalty_max: must be finite and >= penalty_min (" + number(lo) +
                   (ownMin ? ", the rule's" : ", the contact section's") + "), got " +
                   number(hi));
}

// The rule's values (NaN: the contact section's) appended as a new pair class.
void addPairClass(const ContactPairDef& r, const std::string& path, ContactClasses& c) {
  if (!std::isnan(r.friction) && !(r.friction >= 0 && std::isfinite(r.friction)))
    throw SceneError(path + ".friction: must be a finite value >= 0");
  const double p = r.maxPenetration;
  if (!std::isnan(p) && !(p > 0 && std::isfinite(p)))
    throw SceneError(path + ".max_penetration: must be a finite value > 0");
  const auto orSection = [](double given, double section) {
    return std::isnan(given) ? section : given;
  };
  const double lo = orSection(r.penaltyMin, c.penaltyMin[0]);
  const double hi = orSection(r.penaltyMax, c.penaltyMax[0]);
  if (!(lo > 0 && std::isfinite(lo)))
    throw SceneError(path + ".penalty_min: must be a finite value > 0");
  checkPenaltyBounds(r, path, lo, hi);
  c.mu.push_back(orSection(r.friction, c.mu[0]));
  c.pMax.push_back(orSection(r.maxPenetration, c.pMax[0]));
  c.penaltyMin.push_back(lo);
  c.penaltyMax.push_back(hi);
}

// "unknown class 'c' (no fibre has it; the fibres' classes: a, b)": the first 8 classes by name.
std::string unknownClass(const std::map<std::string, int>& index, const std::string& name) {
  std::string list;
  int shown = 0;
  for (const auto& [n, i] : index) {
    if (n.empty()) continue;
    list += shown ? ", " : "";
    list += ++shown > 8 ? "..." : n;
    if (shown > 8) break;
  }
  const std::string what = "unknown class '" + name + "' (no fibre has it; ";
  if (list.empty()) return what + "no fibre has a class: give the fibres a \"class\")";
  return what + "the fibres' classes: " + list + ")";
}

int classIndex(const std::map<std::string, int>& index, const std::string& name,
               const std::string& path) {
  if (name.empty()) throw SceneError(path + ": empty class name (the default class is unnamed)");
  const auto it = index.find(name);
  if (it == index.end()) throw SceneError(path + ": " + unknownClass(index, name));
  return it->second;
}

void pairTable(const SceneDef& s, const std::map<std::string, int>& index, ContactClasses& c) {
  const int n = c.classes;
  std::vector<int> named(n * n, 0);
  int within = 0, between = 0;
  const std::vector<ContactPairDef>& rules = s.contact.pairs;
  for (size_t i = 0; i < rules.size(); ++i) {
    const std::string path = "contact." + at("pairs", i);
    addPairClass(rules[i], path, c);
    const int id = int(c.mu.size()) - 1;
    int& keyword = rules[i].rule == PairRule::Within ? within : between;
    if (rules[i].rule != PairRule::Named) {
      if (keyword) throw SceneError(path + ".classes: this keyword rule is given twice");
      keyword = id;
      continue;
    }
    const int a = classIndex(index, rules[i].classes[0], path + ".classes[0]");
    const int b = classIndex(index, rules[i].classes[1], path + ".classes[1]");
    if (named[a * n + b])
      throw SceneError(path + ".classes: the pair ('" + rules[i].classes[0] + "', '" +
                       rules[i].classes[1] + "') is given twice");
    named[a * n + b] = named[b * n + a] = id;
  }
  c.pairOf.resize(n * n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      c.pairOf[a * n + b] = named[a * n + b] ? named[a * n + b] : a == b ? within : between;
}

// Forced normals act between fibres of different classes whose levels differ: a scene where no
// pair can qualify would run the step with the normal rules, silently. With two classes or more
// and two levels or more, some fibres of different classes have different levels.
void checkForcedPairs(const SceneDef& s, const ContactClasses& c, const std::string& path) {
  const std::set<int> classes(c.classOf.begin(), c.classOf.end());
  if (classes.size() < 2) {
    const std::string& name = s.fibres.empty() ? "" : s.fibres[0].contactClass;
    throw SceneError(path + ": act between fibres of different classes, but every fibre is in " +
                     (name.empty() ? std::string("the default class (no fibre has a \"class\")")
                                   : "class '" + name + "'"));
  }
  std::set<double> levels(c.level.begin(), c.level.end());
  for (size_t f = 0; f + 1 < c.firstLevel.size(); ++f)
    if (c.firstLevel[f] == c.firstLevel[f + 1]) levels.insert(0.0);  // no table: level 0
  if (levels.size() < 2)
    throw SceneError(path + ": every fibre has level " + number(*levels.begin()) +
                     ", so no crossing is oriented (give the fibres on top higher \"levels\")");
}

void checkForcedNormals(const SceneDef& s, const ContactClasses& c) {
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const Vec3& d = s.steps[i].forcedNormal;
    const double allowance = s.steps[i].forcedAllowance;
    const std::string path = at("steps", i) + ".forced_normals";
    if (!(allowance >= 0) || !std::isfinite(allowance))
      throw SceneError(path + ".allowance: must be a finite overlap >= 0, mm");
    if (d.squaredNorm() == 0) {
      if (allowance > 0) throw SceneError(path + ".allowance: needs a forced direction");
      continue;
    }
    if (!s.contact.enabled) throw SceneError(path + ": needs fibre contact (a contact section)");
    if (!d.allFinite() || std::abs(d.norm() - 1) > 1e-12)
      throw SceneError(path + ".direction: must be a finite unit vector");
    checkForcedPairs(s, c, path);
  }
}

}  // namespace

ContactClasses defaultContactClasses(Index fibres, const PairSettings& all) {
  ContactClasses c;
  c.classOf.assign(fibres, 0);
  c.firstLevel.assign(fibres + 1, 0);
  c.classes = 1;
  c.pairOf = {0};
  c.mu = {all.mu};
  c.pMax = {all.pMax};
  c.penaltyMin = {all.penaltyMin};
  c.penaltyMax = {all.penaltyMax};
  return c;
}

ContactClasses resolveContactClasses(const SceneDef& s, const PairSettings& section) {
  ContactClasses c = defaultContactClasses(0, section);
  std::map<std::string, int> index;
  c.classOf = classIndices(s, index);
  c.classes = int(index.size());
  levelTables(s, c);
  pairTable(s, index, c);
  checkForcedNormals(s, c);
  return c;
}

}  // namespace fibra
