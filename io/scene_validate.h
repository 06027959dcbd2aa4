// Semantic validation of a SceneDef, run by the scene-file loader (and callable on a SceneDef
// filled in code before it is given to a World, whose constructor checks only what building
// needs): every name resolves, every number is in range, every table is monotone. Throws SceneError
// whose message starts with the field path (e.g. "fibres[2].radius: must be > 0, got -1").
#pragma once

#include "engine/scene.h"

#include <string>

namespace fibra {

void validateScene(const SceneDef& scene);

// One table: at least one point, finite values, times strictly increasing. `path` names it
// (e.g. "loads[0].table"); a point is named "path[i]".
void validateTable(const Table& table, const std::string& path);

}  // namespace fibra
