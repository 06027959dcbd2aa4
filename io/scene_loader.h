// Scene loader: a JSON scene file (format: docs/SCENE.md) -> SceneDef, validated.
//
// Every error is a SceneError "FILE: FIELD.PATH: what is wrong" (e.g. "samples/x.json:
// fibres[2].radius: must be > 0, got -1"), or "FILE: line L, column C: malformed JSON: ..." for
// text that is not JSON. Unknown fields, wrong types, missing required fields, unresolved names
// and out-of-range values are all errors: a scene loads completely or not at all.
#pragma once

#include "engine/scene.h"

#include <string>

namespace fibra {

// Reads, parses and validates (validateScene) a scene file.
SceneDef loadScene(const std::string& path);

// The same for scene text; `displayName` stands for the file name in messages.
SceneDef loadSceneFromString(const std::string& text, const std::string& displayName);

// The scene file's text with its generators expanded (docs/SCENE.md "Generators"): plain JSON
// (json_reader::readableDump: keys sorted, numbers that read back exactly, comments dropped) that loads to
// the same SceneDef. Checked as loadScene checks it; its errors are loadScene's.
std::string expandScene(const std::string& path);
std::string expandSceneFromString(const std::string& text, const std::string& displayName);

}  // namespace fibra
