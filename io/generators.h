// Scene generators (docs/SCENE.md "Generators"): the optional top-level `generators` list of a
// scene file, each entry expanded into plain scene entries (fibres, groups) before the scene is
// read, so the usual reading and validation, with their field-named errors, apply to the result.
// An error in a generator's own fields names it "generators[i].field".
//
// Adding a generator: a function that reads its spec and appends to the scene (the yarn's is
// io/yarn_generator.h), and a line in the table in generators.cpp.
#pragma once

#include "io/json_reader.h"

namespace fibra {

// Appends to `scene` what the generator described by `spec` (at `path`, "generators[i]") makes.
using GeneratorExpand = void (*)(const json_reader::Json& spec, const std::string& path,
                                 json_reader::Json& scene);

// The scene with every entry of its `generators` expanded, in order, and the key removed; a
// scene without generators is returned unchanged. Throws SceneError "PATH: what is wrong".
json_reader::Json expandGenerators(const json_reader::Json& scene);

// The list `key` ("fibres", "groups", ...) of the scene, created empty when absent, to append
// to (an error naming `key` when it is not a list).
json_reader::Json& sceneList(json_reader::Json& scene, const char* key);

}  // namespace fibra
