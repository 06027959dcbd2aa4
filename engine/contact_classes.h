// Contact classes and pair classes resolved from the scene (docs/SCENE.md: a fibre's `class`
// and `levels`, contact `pairs`, a step's `forced_normals`), into ContactClasses
// (components/contact_params.h).
//
// Classes are numbered in order of first appearance along the fibres, the default class "" being
// 0. Pair classes: 0 is the contact section's own settings; each rule of contact.pairs is one
// more, and every class pair (a, b) takes the most specific rule that covers it: a named pair,
// else `within` (a == b) or `between` (a != b), else 0. A rule's NaN values take the contact
// section's.
#pragma once

#include "components/contact_params.h"
#include "engine/scene.h"

namespace fibra {

// The settings of one pair class.
struct PairSettings {
  double mu = 0;            // friction coefficient
  double pMax = 0;          // mm
  double penaltyMin = 1;    // penalty bounds, multiples of the zone's section stiffness
  double penaltyMax = 1e4;
};

// One class, one pair class with the settings `all`, no level tables, for n fibres.
ContactClasses defaultContactClasses(Index fibres, const PairSettings& all);

// The scene's classes, levels and pair classes; `section` holds the contact section's resolved
// values. Throws SceneError naming the field: an unknown or empty class in a rule, a class pair
// or keyword rule given twice, a negative friction, a p_max <= 0, a penalty_min <= 0, a
// penalty_max below penalty_min (the rule's or the section's; a rule's penalty_min above the
// section's penalty_max names penalty_min), a level table that does not start at 0 or whose
// `from` do not increase, forced normals in a scene without fibre contact, with every fibre in
// one class, or with every fibre at one level (no pair would be forced).
ContactClasses resolveContactClasses(const SceneDef& scene, const PairSettings& section);

}  // namespace fibra
