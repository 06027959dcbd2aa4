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

// One class, one pair class with friction mu and p_max (mm), no level tables, for n fibres.
ContactClasses defaultContactClasses(Index fibres, double mu, double pMax);

// The scene's classes, levels and pair classes; mu and pMax are the contact section's resolved
// values. Throws SceneError naming the field: an unknown or empty class in a rule, a class pair
// or keyword rule given twice, a negative friction, a p_max <= 0, a level table that does not
// start at 0 or whose `from` do not increase, a forced normal in a scene without fibre contact.
ContactClasses resolveContactClasses(const SceneDef& scene, double mu, double pMax);

}  // namespace fibra
