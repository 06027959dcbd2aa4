// The order in which a scene's groups are resolved (docs/SCENE.md "Groups"): a union may name any
// other group of the scene, listed before or after it - a generator's groups are appended after
// the scene's own (io/generators.h), and a scene union may name them - so unions are resolved
// after the scene groups they name. Used by the validation (io/scene_validate.cpp) and the build
// (engine/scene_build.cpp), so that both accept the same scenes.
#pragma once

#include "engine/scene.h"

#include <vector>

namespace fibra {

// Indices of `groups` in an order where every union comes after the scene groups among its
// members (members that are not scene groups, such as automatic groups, do not count): the
// groups that name no scene group first, in scene order, then the others as their members are
// resolved. Iterative, however long a chain of unions. Throws SceneError
// "groups[i].union[k]: ... (a cycle: a -> b -> a)" when unions name each other in a cycle,
// reported at the cycle's group listed first; a group that names itself: "a group cannot be a
// union of itself". A name given to two groups stands for the first.
std::vector<size_t> groupResolutionOrder(const std::vector<GroupDef>& groups);

}  // namespace fibra
